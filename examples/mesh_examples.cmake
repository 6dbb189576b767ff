# Examples 01-04 (meshing and surfaces) as CTest tests at a small size (label "example"),
# each a few seconds: the printed validity/manifold line is checked, outputs go to
# <build>/examples/example_out/. Plus one bad option per example (exit 1, one error line).
set(_exout ${CMAKE_CURRENT_BINARY_DIR}/example_out)
file(MAKE_DIRECTORY ${_exout})
set(_mesh_examples
  "01_square_paper_metric|--h 0.6 --out ${_exout}/ex01|Valid: yes|--h -1"
  "02_disk_three_metrics|--scale 3 --out ${_exout}/ex02|All valid: yes|--case ellipse"
  "03_square_with_hole|--scale 2 --out ${_exout}/ex03|Valid: yes, all 6 tags on the boundary: yes|--scale 0"
  "04_surface_paper_fig16|--h 0.15 --out ${_exout}/ex04|Manifold: yes|--radius 2")
foreach(_entry ${_mesh_examples})
  string(REPLACE "|" ";" _fields "${_entry}")
  list(GET _fields 0 _name)
  list(GET _fields 1 _args)
  list(GET _fields 2 _pass)
  list(GET _fields 3 _bad)
  if(NOT TARGET ex${_name})
    continue()
  endif()
  separate_arguments(_args)
  separate_arguments(_bad)
  add_test(NAME example_${_name} COMMAND ex${_name} ${_args})
  set_tests_properties(example_${_name} PROPERTIES LABELS example TIMEOUT 120
                       PASS_REGULAR_EXPRESSION "${_pass}" FAIL_REGULAR_EXPRESSION "(^|[ =(-])(nan|inf)([ ,)]|$)")
  add_test(NAME example_${_name}_bad_option COMMAND ex${_name} ${_bad})
  set_tests_properties(example_${_name}_bad_option PROPERTIES LABELS example WILL_FAIL TRUE)
endforeach()

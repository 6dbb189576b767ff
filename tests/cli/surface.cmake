# `ablmg surface` (issue 10): the list of built-ins, a small run that must report a manifold
# mesh and write its file, and a bad surface name (one error line, exit 1, no output).
if(EXISTS ${PROJECT_SOURCE_DIR}/cli/cmd_surface.cpp AND COMMAND ablmg_cli_failure)
  set(_sdir ${CMAKE_CURRENT_BINARY_DIR}/cli_out/surface)
  file(MAKE_DIRECTORY ${_sdir})
  add_test(NAME cli.surface_list COMMAND ablmg surface --list)
  set_tests_properties(cli.surface_list PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "paper-fig16.*sphere-patch.*torus.*cylinder.*saddle")
  add_test(NAME cli.surface_sphere COMMAND ablmg surface --surface sphere-patch --h 0.2 -o ${_sdir}/sphere.mesh --stl ${_sdir}/sphere.stl --vtu ${_sdir}/sphere.vtu)
  set_tests_properties(cli.surface_sphere PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "manifold: yes.*-> .*sphere.mesh")
  ablmg_cli_failure(surface_unknown_name "unknown|not a built-in|surface" surface --surface klein-bottle --h 0.1 -o ${_sdir}/klein.mesh)
  ablmg_cli_failure(surface_bad_h "--h: expected a positive number" surface --surface torus --h -1 -o ${_sdir}/bad_h.mesh)
endif()

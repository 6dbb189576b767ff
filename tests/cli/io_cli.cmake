# `ablmg remesh` / `ablmg mesh` on bad inputs: non-zero exit, one error line naming file:line
# (or the config key), and no output file left (check_failure.cmake.in).
set(_data ${CMAKE_CURRENT_SOURCE_DIR}/data)
set(_out ${CMAKE_CURRENT_BINARY_DIR}/cli_out)
file(MAKE_DIRECTORY ${_out})
function(ablmg_cli_failure name expect)
  add_test(NAME cli.${name}
           COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:ablmg>;${ARGN}" "-DEXPECT=${expect}" "-DOUT=${_out}/${name}.mesh"
                   -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/check_failure.cmake.in)
  set_tests_properties(cli.${name} PROPERTIES LABELS cli)
endfunction()
foreach(bad truncated nan bad_index empty garbage)
  ablmg_cli_failure(remesh_${bad} "${bad}.mesh:[0-9]+: " remesh -in ${_data}/${bad}.mesh -sol ${_data}/square.sol -out ${_out}/remesh_${bad}.mesh)
endforeach()
ablmg_cli_failure(remesh_nonspd "nonspd.sol:13: tensor of vertex 5 \\(1, 2, 1\\) is not positive definite"
                  remesh -in ${_data}/square.mesh -sol ${_data}/nonspd.sol -out ${_out}/remesh_nonspd.mesh)
ablmg_cli_failure(remesh_negative_size "negative-size.sol:8: size of vertex 3 is -0.2"
                  remesh -in ${_data}/square.mesh -met ${_data}/negative-size.sol -out ${_out}/remesh_negative_size.mesh)
ablmg_cli_failure(remesh_mismatch "mismatch.sol:4: 3 solution values but the mesh has 5 vertices"
                  remesh -in ${_data}/square.mesh -sol ${_data}/mismatch.sol -out ${_out}/remesh_mismatch.mesh)
ablmg_cli_failure(remesh_bad_flag "unknown option '-foo'" remesh -in ${_data}/square.mesh -foo -out ${_out}/remesh_bad_flag.mesh)
# Numbers follow one rule on every command (cli/parse_number.hpp).
ablmg_cli_failure(remesh_fractional_verbosity "remesh: -v: expected an integer in \\[-1, 10\\], got '1.5'"
                  remesh -in ${_data}/square.mesh -v 1.5 -out ${_out}/remesh_fractional_verbosity.mesh)
ablmg_cli_failure(remesh_nan_hmin "remesh: -hmin: expected a number, got 'nan'"
                  remesh -in ${_data}/square.mesh -hmin nan -out ${_out}/remesh_nan_hmin.mesh)
add_test(NAME cli.remesh_reports_post_pass
         COMMAND ablmg remesh -in ${_data}/square.mesh -sol ${_data}/square.sol -out ${_out}/remesh_post_pass.mesh -v 2)
set_tests_properties(cli.remesh_reports_post_pass PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "quality post-pass [0-9.e-]+ \\(q min [0-9.]+ -> [0-9.]+, [0-9]+ swaps, [0-9]+ moves, [0-9]+ collapses\\)")
add_test(NAME cli.remesh_report
         COMMAND ablmg remesh -in ${_data}/square.mesh -sol ${_data}/square.sol -out ${_out}/remesh_report.mesh
                 --report ${_out}/remesh_report.json -v 0)
set_tests_properties(cli.remesh_report PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "repaired triangles\\) -> ")
add_test(NAME cli.remesh_report_contents
         COMMAND ${CMAKE_COMMAND} -DREPORT=${_out}/remesh_report.json -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/check_remesh_report.cmake.in)
set_tests_properties(cli.remesh_report_contents PROPERTIES LABELS cli DEPENDS cli.remesh_report)
add_test(NAME cli.remesh_huge_page_heap
         COMMAND ${CMAKE_COMMAND} -DABLMG=$<TARGET_FILE:ablmg> -DDATA=${_data} -DOUT=${_out}/huge_page_heap
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/check_huge_page_heap.cmake.in)
set_tests_properties(cli.remesh_huge_page_heap PROPERTIES LABELS cli)
ablmg_cli_failure(remesh_report_is_output "--report must not be the output mesh or .sol"
                  remesh -in ${_data}/square.mesh -sol ${_data}/square.sol -out ${_out}/remesh_report_is_output.mesh
                  --report ${_out}/remesh_report_is_output.mesh)
ablmg_cli_failure(remesh_bad_lattice "lattice orientation: expected axes, short, long or auto, got 'rows'"
                  remesh -in ${_data}/square.mesh --lattice rows -out ${_out}/remesh_bad_lattice.mesh)
# The .sol is read on a second thread; the errors still come in the sequential order:
# the mesh's parse error, then the .sol's, then the mesh's validity.
ablmg_cli_failure(remesh_both_bad "truncated.mesh:[0-9]+: " remesh -in ${_data}/truncated.mesh -sol ${_data}/nonspd.sol -out ${_out}/remesh_both_bad.mesh)
ablmg_cli_failure(remesh_missing_sol "no_such.sol: cannot open" remesh -in ${_data}/square.mesh -sol ${_data}/no_such.sol -out ${_out}/remesh_missing_sol.mesh)
file(WRITE ${_out}/overlap.mesh "MeshVersionFormatted 2\nDimension 2\nVertices\n5\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n0.5 0.5 0\n"
                                "Edges\n4\n1 2 1\n2 3 1\n3 4 1\n4 1 1\nTriangles\n5\n1 2 5 0\n2 3 5 0\n3 4 5 0\n4 1 5 0\n1 2 3 0\nEnd\n")
ablmg_cli_failure(remesh_invalid_mesh "overlap.mesh: invalid mesh \\(ids from 1, as in the file\\): triangle 5 \\(1, 2, 3\\)|overlap.mesh: invalid mesh \\(ids from 1, as in the file\\): edge \\([1-5], [1-5]\\)" remesh -in ${_out}/overlap.mesh -sol ${_data}/square.sol -out ${_out}/remesh_invalid_mesh.mesh)
ablmg_cli_failure(remesh_invalid_mesh_bad_sol "nonspd.sol:13: tensor of vertex 5" remesh -in ${_out}/overlap.mesh -sol ${_data}/nonspd.sol -out ${_out}/remesh_invalid_mesh_bad_sol.mesh)
# Two boundary loops touching at vertex 3 (a valid mesh, but not a domain).
file(WRITE ${_out}/bowtie.mesh "MeshVersionFormatted 2\nDimension 2\nVertices\n5\n0 0 1\n1 0 1\n1 1 1\n2 1 1\n2 2 1\n"
                               "Edges\n6\n1 2 1\n2 3 1\n3 1 1\n3 4 2\n4 5 2\n5 3 2\nTriangles\n2\n1 2 3 0\n3 4 5 0\nEnd\n")
file(WRITE ${_out}/bowtie.sol "MeshVersionFormatted 2\nDimension 2\nSolAtVertices\n5\n1 1\n0.1\n0.1\n0.1\n0.1\n0.1\nEnd\n")
ablmg_cli_failure(remesh_pinched_boundary "bowtie.mesh: boundary vertex 3 starts two boundary edges \\(non-manifold boundary\\)"
                  remesh -in ${_out}/bowtie.mesh -sol ${_out}/bowtie.sol -out ${_out}/remesh_pinched_boundary.mesh)
# The .sol cannot be written (a directory in its place): the new .mesh is removed again.
file(MAKE_DIRECTORY ${_out}/remesh_sol_blocked.sol)
ablmg_cli_failure(remesh_sol_blocked "remesh_sol_blocked.sol: cannot rename" remesh -in ${_data}/square.mesh -sol ${_data}/square_scalar.sol -out ${_out}/remesh_sol_blocked.mesh -hmax 0.2)
file(WRITE ${_out}/bad_type.json "{\"domain\": {\"rectangle\": [0,0,1,1]}, \"metric\": {\"h1\": 0.1}}\n")
ablmg_cli_failure(mesh_bad_type "bad_type.json: metric.h1: expected string, got number" mesh ${_out}/bad_type.json -o ${_out}/mesh_bad_type.mesh)
file(WRITE ${_out}/bad_poly.json "{\"domain\": {\"poly\": \"${_data}/open_loop.poly\"}, \"metric\": {\"h\": \"0.1\"}}\n")
ablmg_cli_failure(mesh_open_loop "open_loop.poly:[0-9]+: boundary is not closed at vertex" mesh ${_out}/bad_poly.json -o ${_out}/mesh_open_loop.mesh)

# Successful runs (once meshing works end to end): output files exist afterwards.
add_test(NAME cli.remesh_square
         COMMAND ablmg remesh -in ${_data}/square.mesh -sol ${_data}/square_scalar.sol -out ${_out}/remesh_square.mesh -hmax 0.2 -hgrad 1.5)
set_tests_properties(cli.remesh_square PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "-> .*remesh_square.mesh")
# A square with a square hole, refs 1-4 outside and 5 on the hole (two boundary loops).
file(WRITE ${_out}/square_hole.mesh "MeshVersionFormatted 2\nDimension 2\nVertices\n8\n0 0 0\n3 0 0\n3 3 0\n0 3 0\n1 1 0\n2 1 0\n2 2 0\n1 2 0\n"
                                    "Edges\n8\n1 2 1\n2 3 2\n3 4 3\n4 1 4\n6 5 5\n7 6 5\n8 7 5\n5 8 5\n"
                                    "Triangles\n8\n1 2 6 0\n1 6 5 0\n2 3 7 0\n2 7 6 0\n3 4 8 0\n3 8 7 0\n4 1 5 0\n4 5 8 0\nEnd\n")
file(WRITE ${_out}/square_hole.sol "MeshVersionFormatted 2\nDimension 2\nSolAtVertices\n8\n1 1\n0.25\n0.25\n0.25\n0.25\n0.25\n0.25\n0.25\n0.25\nEnd\n")
add_test(NAME cli.remesh_hole COMMAND ablmg remesh -in ${_out}/square_hole.mesh -out ${_out}/remesh_hole.mesh -v 0)
set_tests_properties(cli.remesh_hole PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "-> .*remesh_hole.mesh")
file(WRITE ${_out}/disk.json "{\"domain\": {\"disk\": {\"center\": [0, 0], \"radius\": 1, \"samples\": 256}}, \"metric\": {\"h1\": \"0.3\", \"h2\": \"0.1\", \"theta\": \"atan2(y, x)\"}}\n")
add_test(NAME cli.mesh_disk_bubbles COMMAND ablmg mesh ${_out}/disk.json --bubbles-only -o ${_out}/disk_bubbles.png -o ${_out}/disk_bubbles.vtu --seed 2)
set_tests_properties(cli.mesh_disk_bubbles PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "vertices, 0 triangles")
add_test(NAME cli.mesh_disk COMMAND ablmg mesh ${_out}/disk.json -o ${_out}/disk.mesh -o ${_out}/disk.png --report ${_out}/disk_report.json)
set_tests_properties(cli.mesh_disk PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "triangles in")
# Slits in a JSON domain: meshed with the lips apart (each lip's tag on the output), and a slit
# that leaves the domain named by its key.
file(WRITE ${_out}/slit.json "{\"domain\": {\"rectangle\": [-1, -1, 1, 1], \"slits\": [{\"points\": [[1, 0], [0, 0]], \"tags\": [7, 8]},"
                             " {\"points\": [[-0.5, 0.5], [-0.5, -0.5]], \"tags\": [9, 9]}]}, \"metric\": {\"h\": \"0.1\"}}\n")
add_test(NAME cli.mesh_slit COMMAND ablmg mesh ${_out}/slit.json -o ${_out}/slit.mesh -v 0)
set_tests_properties(cli.mesh_slit PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "triangles in")
file(WRITE ${_out}/bad_slit.json "{\"domain\": {\"rectangle\": [-1, -1, 1, 1], \"slits\": [{\"points\": [[1, 0], [2, 0]]}]}, \"metric\": {\"h\": \"0.1\"}}\n")
ablmg_cli_failure(mesh_slit_outside "bad_slit.json: domain.slits\\[0\\]: domain: slit point 0 \\(1, 0\\): the slit leaves the domain" mesh ${_out}/bad_slit.json -o ${_out}/mesh_bad_slit.mesh)
ablmg_cli_failure(remesh_negative_metric_quantum "remesh: --metric-quantum must be >= 0 \\(0 = off\\), got -1"
                  remesh -in ${_data}/square.mesh --metric-quantum -1 -out ${_out}/remesh_negative_metric_quantum.mesh)
# A required vertex outside the domain (used by no triangle), and interface Edges that cross
# (the second is no side of a triangle): clean errors naming the file.
file(WRITE ${_out}/required_outside.mesh "MeshVersionFormatted 2\nDimension 2\nVertices\n5\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n5 5 0\n"
                                         "Triangles\n2\n1 2 3 1\n1 3 4 1\nRequiredVertices\n1\n5\nEnd\n")
ablmg_cli_failure(remesh_required_outside "required_outside.mesh: invalid mesh \\(ids from 1, as in the file\\): vertex 5 is used by no triangle"
                  remesh -in ${_out}/required_outside.mesh -hsiz 0.2 -out ${_out}/remesh_required_outside.mesh)
file(WRITE ${_out}/crossing_interfaces.mesh "MeshVersionFormatted 2\nDimension 2\nVertices\n4\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
                                            "Triangles\n2\n1 2 3 1\n1 3 4 1\nEdges\n2\n1 3 5\n2 4 6\nEnd\n")
ablmg_cli_failure(remesh_crossing_interfaces "crossing_interfaces.mesh: edge \\(2, 4\\) of Edges is a side of no triangle"
                  remesh -in ${_out}/crossing_interfaces.mesh -hsiz 0.2 -out ${_out}/remesh_crossing_interfaces.mesh)
# MMG's -val prints the options in effect and exits without reading -in (none here, or a
# missing file); -nosurf keeps the boundary and interface edges as required edges.
add_test(NAME cli.remesh_val COMMAND ablmg remesh -val -hsiz 0.3)
set_tests_properties(cli.remesh_val PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "\"command\": \"remesh\".*\"hsiz\": 0.3")
add_test(NAME cli.remesh_val_reads_nothing COMMAND ablmg remesh -in ${_data}/no_such.mesh -val)
set_tests_properties(cli.remesh_val_reads_nothing PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "\"in\": \"[^\"]*no_such.mesh\""
                     FAIL_REGULAR_EXPRESSION "cannot open")
add_test(NAME cli.remesh_nosurf COMMAND ablmg remesh -in ${_data}/gmsh_disk_three.mesh -hsiz 0.05 -nosurf
                                        -out ${_out}/remesh_nosurf.mesh)
set_tests_properties(cli.remesh_nosurf PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "\"nosurf\":true.*426 -> [0-9]+ vertices")
ablmg_cli_failure(remesh_nosurf_without_input "missing -in IN.mesh" remesh -nosurf -hsiz 0.1)

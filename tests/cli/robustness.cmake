# Cases found by scripts/robustness_sweep.sh (inputs away from the measured ones), each the
# smallest that failed. Uses ablmg_cli_failure() from io_cli.cmake (included before this file).
set(_rdir ${CMAKE_CURRENT_BINARY_DIR}/cli_out/robustness)
file(MAKE_DIRECTORY ${_rdir})
# A size of 1e-12 asks for ~1e24 nodes: the count is printed, not an overflowed integer.
ablmg_cli_failure(remesh_size_1e-12 "placeNodes: the metric asks for about 1.[0-9]+e\\+24 nodes, more than maxNodes = 50000000"
                  remesh -in ${PROJECT_SOURCE_DIR}/tests/data/square.mesh -hsiz 1e-12 -out ${_rdir}/size_1e-12.mesh)
# --norm h1 keeps the loop's shape blend: with the H1 shape the line singularity's errors
# rose from the first cycle to the second (L2 2.5e-3 -> 5.1e-3) and stayed there.
add_test(NAME cli_adapt_norm_h1_errors_fall
         COMMAND ${CMAKE_COMMAND} -DBIN=$<TARGET_FILE:ablmg> -DMODE=figures -DFALL_FROM=1
                 "-DARGS=--problem linesing --norm h1 --target-vertices 500,1000,2000,4000 --uniform off"
                 -DMAX_H1_RATE=-0.45 -DMAX_L2_RATE=-0.9 -DOUTDIR=${_rdir}/norm_h1
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/adapt.cmake)
set_tests_properties(cli_adapt_norm_h1_errors_fall PROPERTIES LABELS cli)
# One size only (--vertices below the first size): the rates are "n/a", not "nan".
add_test(NAME cli_adapt_one_size_rates_na COMMAND ablmg adapt --problem smooth --vertices 200 --vtu off --uniform off
                                                  --out-dir ${_rdir}/one_size)
set_tests_properties(cli_adapt_one_size_rates_na PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "L2 n/a  H1 n/a  L2interp n/a"
                     FAIL_REGULAR_EXPRESSION "nan")
# --vertices 0 or negative names the flag and its value (it read as "--vertices is required").
ablmg_cli_failure(adapt_vertices_zero "adapt: --vertices must be > 0, got 0" adapt --problem peak --vertices 0 --out-dir ${_rdir}/vertices_zero)
# An SPD tensor whose smaller eigenvalue is lost to round-off is named as such, not "not positive definite".
file(WRITE ${_rdir}/aniso_1e10.sol "MeshVersionFormatted 2\nDimension 2\nSolAtVertices\n5\n1 3\n1e10 0 1e-10\n1 0 1\n1 0 1\n1 0 1\n1 0 1\nEnd\n")
ablmg_cli_failure(remesh_tensor_too_anisotropic "aniso_1e10.sol:6: tensor of vertex 1: tensor \\(1e\\+10, 0, 1e-10\\) is too anisotropic"
                  remesh -in ${PROJECT_SOURCE_DIR}/tests/data/square.mesh -sol ${_rdir}/aniso_1e10.sol -out ${_rdir}/aniso_1e10.mesh)
# A load that is NaN somewhere (sqrt of a negative) is named at its point, not as a failed
# CHOLMOD solve.
file(WRITE ${_rdir}/nan_load.json "{\"mesh\": {\"structured\": {\"nx\": 8, \"ny\": 8}, \"domain\": [0, 0, 1, 1]}, \"problem\": {\"f\": \"sqrt(x-0.5)\", \"dirichlet\": {\"default\": \"0\"}}, \"output\": {\"vtu\": \"${_rdir}/nan_load.vtu\", \"report\": \"${_rdir}/nan_load.report.json\"}}")
ablmg_cli_failure(solve_nan_load "assemble: f = -?nan at \\([0-9.]+, [0-9.]+\\) in triangle [0-9]+" solve ${_rdir}/nan_load.json)
# A time step 10⁹ times too small ran for days (and overflowed the step counter past 2·10⁹).
ablmg_cli_failure(transient_too_many_steps "transient options: \\(tEnd - tStart\\) / dt = .* = 5e\\+08 steps, more than 1e\\+06"
                  transient --problem movingpeak --dt 1e-9 --vertices 400 --out-dir ${_rdir}/too_many_steps)
# A hole whose corners lie off the uniform grids (x = 0.3 of [0, 2]): the uniform comparison is
# skipped with a note; it failed the whole run after its last cycle.
file(WRITE ${_rdir}/hole_off_grid.json "{\"domain\": {\"loops\": [[[0,0],[2,0],[2,1],[0,1]], [[0.3,0.3],[0.6,0.3],[0.6,0.6],[0.3,0.6]]]}, \"problem\": {\"f\": \"2*pi^2*sin(pi*x)*sin(pi*y)\", \"dirichlet\": {\"default\": \"sin(pi*x)*sin(pi*y)\"}, \"exact\": {\"u\": \"sin(pi*x)*sin(pi*y)\", \"ux\": \"pi*cos(pi*x)*sin(pi*y)\", \"uy\": \"pi*sin(pi*x)*cos(pi*y)\"}}}")
add_test(NAME cli_adapt_uniform_off_grid COMMAND ablmg adapt ${_rdir}/hole_off_grid.json --target-vertices 300,600 --vtu off
                                                 --out-dir ${_rdir}/hole_off_grid)
set_tests_properties(cli_adapt_uniform_off_grid PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "Uniform: skipped from N=300 on \\(structuredMesh: .* is not a node")
# A gmsh .msh passed as medit: the error names the format and the export.
file(WRITE ${_rdir}/gmsh.msh "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n")
ablmg_cli_failure(remesh_gmsh_msh "gmsh.msh:1: expected MeshVersionFormatted, got '.meshformat' \\(a gmsh .msh file: write medit with gmsh -format mesh\\)"
                  remesh -in ${_rdir}/gmsh.msh -hsiz 0.1 -out ${_rdir}/gmsh_msh.mesh)
# A multi-material medit mesh 10⁹ from the origin: its loops' areas (which loop is outer, the
# area to cover) are summed about a loop point; about the origin they lost every digit.
file(WRITE ${_rdir}/far.mesh "MeshVersionFormatted 2\nDimension 2\nVertices\n8\n"
     "1e9 1e9 0\n1000000002 1e9 0\n1000000002 1000000001 0\n1e9 1000000001 0\n1000000001 1e9 0\n1000000001 1000000001 0\n"
     "1000000000.5 1000000000.5 0\n1000000001.5 1000000000.5 0\n"
     "Triangles\n8\n1 5 7 1\n5 6 7 1\n6 4 7 1\n4 1 7 1\n5 2 8 2\n2 3 8 2\n3 6 8 2\n6 5 8 2\nEnd\n")
add_test(NAME cli.remesh_far_from_the_origin COMMAND ablmg remesh -in ${_rdir}/far.mesh -hsiz 0.1 -out ${_rdir}/far.o.mesh -v 0)
set_tests_properties(cli.remesh_far_from_the_origin PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "8 -> [0-9]+ vertices")
# --png off (timed and batch runs): the run writes its tables and no picture.
file(WRITE ${_rdir}/check_png_off.cmake [=[
file(REMOVE_RECURSE ${OUT})
execute_process(COMMAND ${BIN} adapt --problem peak --vertices 600 --uniform off --vtu off --png off --out-dir ${OUT}
                RESULT_VARIABLE rc OUTPUT_QUIET)
file(GLOB pictures ${OUT}/*.png)
if(NOT rc EQUAL 0 OR NOT EXISTS ${OUT}/convergence.csv OR pictures)
  message(FATAL_ERROR "adapt --png off: exit ${rc}, pictures '${pictures}'")
endif()
]=])
add_test(NAME cli_adapt_png_off_writes_no_picture
         COMMAND ${CMAKE_COMMAND} -DBIN=$<TARGET_FILE:ablmg> -DOUT=${_rdir}/png_off -P ${_rdir}/check_png_off.cmake)
set_tests_properties(cli_adapt_png_off_writes_no_picture PROPERTIES LABELS cli)

# Byte-identical outputs: the paper's four cases (`ablmg mesh`), a remesh of one of them
# (`ablmg remesh`) and the second mesh of a small adaptive loop (`ablmg adapt`, its metric
# options pinned: the mesher's are the command's defaults), each with the command's default
# mesher options, must hash (SHA-256 of the .mesh file: vertices, edges, triangles)
# to the values in tests/data/golden_mesh_hashes.txt. A change that is meant to change the
# meshes regenerates that file with
#   cmake -DABLMG=build/bin/ablmg -DSRC=. -DOUT=/tmp/golden -DUPDATE=ON -P tests/cli/check_golden.cmake.in
# and says so in its commit. The hashes hold for this toolchain (Debian's GCC, Release flags).
add_test(NAME cli.golden_mesh_hashes
         COMMAND ${CMAKE_COMMAND} -DABLMG=$<TARGET_FILE:ablmg> -DSRC=${PROJECT_SOURCE_DIR}
                 -DOUT=${CMAKE_CURRENT_BINARY_DIR}/cli_out/golden -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/check_golden.cmake.in)
set_tests_properties(cli.golden_mesh_hashes PROPERTIES LABELS cli TIMEOUT 600)

# io/config tests: cli/config.cpp is not in a library, so test_io compiles it in.
if(TARGET test_io)
  target_sources(test_io PRIVATE ${PROJECT_SOURCE_DIR}/cli/config.cpp)
endif()

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
if(EXISTS ${PROJECT_SOURCE_DIR}/cli/cmd_remesh.cpp)
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
endif()
if(EXISTS ${PROJECT_SOURCE_DIR}/cli/cmd_mesh.cpp)
  file(WRITE ${_out}/bad_type.json "{\"domain\": {\"rectangle\": [0,0,1,1]}, \"metric\": {\"h1\": 0.1}}\n")
  ablmg_cli_failure(mesh_bad_type "bad_type.json: metric.h1: expected string, got number" mesh ${_out}/bad_type.json -o ${_out}/mesh_bad_type.mesh)
  file(WRITE ${_out}/bad_poly.json "{\"domain\": {\"poly\": \"${_data}/open_loop.poly\"}, \"metric\": {\"h\": \"0.1\"}}\n")
  ablmg_cli_failure(mesh_open_loop "open_loop.poly:[0-9]+: boundary is not closed at vertex" mesh ${_out}/bad_poly.json -o ${_out}/mesh_open_loop.mesh)
endif()

# Successful runs (once meshing works end to end): output files exist afterwards.
if(EXISTS ${PROJECT_SOURCE_DIR}/cli/cmd_remesh.cpp)
  add_test(NAME cli.remesh_square
           COMMAND ablmg remesh -in ${_data}/square.mesh -sol ${_data}/square_scalar.sol -out ${_out}/remesh_square.mesh -hmax 0.2 -hgrad 1.5)
  set_tests_properties(cli.remesh_square PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "-> .*remesh_square.mesh")
endif()
if(EXISTS ${PROJECT_SOURCE_DIR}/cli/cmd_mesh.cpp)
  file(WRITE ${_out}/disk.json "{\"domain\": {\"disk\": {\"center\": [0, 0], \"radius\": 1, \"samples\": 256}}, \"metric\": {\"h1\": \"0.3\", \"h2\": \"0.1\", \"theta\": \"atan2(y, x)\"}}\n")
  add_test(NAME cli.mesh_disk_bubbles COMMAND ablmg mesh ${_out}/disk.json --bubbles-only -o ${_out}/disk_bubbles.png -o ${_out}/disk_bubbles.vtu --seed 2)
  set_tests_properties(cli.mesh_disk_bubbles PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "vertices, 0 triangles")
  add_test(NAME cli.mesh_disk COMMAND ablmg mesh ${_out}/disk.json -o ${_out}/disk.mesh -o ${_out}/disk.png --report ${_out}/disk_report.json)
  set_tests_properties(cli.mesh_disk PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "triangles in")
endif()

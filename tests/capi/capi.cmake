# The C interface against `ablmg remesh` on the paper's disks (examples/configs/paper_disk_*.json
# as mesh + metric pairs, as in tests/cli/stats.cmake's remesh_pair tests), with the default
# gradation and without: the same bytes (check_capi_files.cmake.in).
add_executable(capi_remesh_files ${CMAKE_CURRENT_SOURCE_DIR}/capi/capi_remesh_files.cpp)
target_link_libraries(capi_remesh_files PRIVATE ablmg_capi ablmg_medit)
set(_capi_dir ${CMAKE_CURRENT_BINARY_DIR}/capi_out)
file(MAKE_DIRECTORY ${_capi_dir})
foreach(case constant line ring)
  foreach(hgrad 1.3 -1)
    add_test(NAME capi.same_bytes_as_remesh_${case}_hgrad${hgrad}
             COMMAND ${CMAKE_COMMAND} -DABLMG=$<TARGET_FILE:ablmg> -DCAPI=$<TARGET_FILE:capi_remesh_files>
                     -DCONFIG=${PROJECT_SOURCE_DIR}/examples/configs/paper_disk_${case}.json
                     -DOUT=${_capi_dir}/${case}_hgrad${hgrad} -DHGRAD=${hgrad}
                     -P ${CMAKE_CURRENT_SOURCE_DIR}/capi/check_capi_files.cmake.in)
    set_tests_properties(capi.same_bytes_as_remesh_${case}_hgrad${hgrad} PROPERTIES LABELS cli)
  endforeach()
endforeach()

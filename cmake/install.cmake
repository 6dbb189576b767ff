# `cmake --install <build> --prefix P` installs:
#   P/lib/libablmg_*.a, P/include/ablmg/<folder>/*.hpp (+ ablmg/capi/ablmg.h), P/bin/ablmg,
#   P/lib/cmake/ablmg/ (ablmgConfig.cmake, its version file, the exported targets ablmg::<name>,
#   FindCHOLMOD.cmake) and P/lib/pkgconfig/ablmg.pc.
# Two export sets: ablmgRemeshTargets (the light libraries: Eigen, OpenMP, C++ runtime) and
# ablmgTargets (the ones linking muparser, VTK, cairo, CHOLMOD, nlohmann_json, and the
# umbrella ablmg::ablmg), so that find_package(ablmg COMPONENTS remesh) looks for nothing heavy.
include(CMakePackageConfigHelpers)
set(ABLMG_LIGHT_LIBRARIES ablmg_core ablmg_medit ablmg_mesher ablmg_p1 ablmg_remesh)
if(TARGET ablmg_capi)
  list(APPEND ABLMG_LIGHT_LIBRARIES ablmg_capi)
endif()
set(ABLMG_HEAVY_LIBRARIES ${ABLMG_LIBRARIES})
list(REMOVE_ITEM ABLMG_HEAVY_LIBRARIES ${ABLMG_LIGHT_LIBRARIES})
set(_cmakedir ${CMAKE_INSTALL_LIBDIR}/cmake/ablmg)

install(TARGETS ${ABLMG_LIGHT_LIBRARIES} EXPORT ablmgRemeshTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS ${ABLMG_HEAVY_LIBRARIES} ablmg_ablmg EXPORT ablmgTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS ablmg RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
foreach(_folder ${ABLMG_HEADER_FOLDERS})
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${_folder}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/ablmg/${_folder}
          FILES_MATCHING PATTERN "*.hpp" PATTERN "*.h")
endforeach()
install(EXPORT ablmgRemeshTargets NAMESPACE ablmg:: DESTINATION ${_cmakedir})
install(EXPORT ablmgTargets NAMESPACE ablmg:: DESTINATION ${_cmakedir})

set(ABLMG_LIGHT_COMPONENTS)
foreach(_lib ${ABLMG_LIGHT_LIBRARIES})
  string(REGEX REPLACE "^ablmg_" "" _name ${_lib})
  list(APPEND ABLMG_LIGHT_COMPONENTS ${_name})
endforeach()
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/ablmgConfig.cmake.in ${PROJECT_BINARY_DIR}/ablmgConfig.cmake
                              INSTALL_DESTINATION ${_cmakedir})
# 0.x: a minor version may change the interface, so 0.2 accepts 0.2.* only.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/ablmgConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/ablmgConfig.cmake ${PROJECT_BINARY_DIR}/ablmgConfigVersion.cmake
              ${CMAKE_CURRENT_LIST_DIR}/FindCHOLMOD.cmake DESTINATION ${_cmakedir})

# pkg-config: the light libraries (what a remeshing solver links), last-needed last.
set(ABLMG_PC_LIBS)
foreach(_lib ablmg_capi ablmg_remesh ablmg_mesher ablmg_p1 ablmg_medit ablmg_core)
  if(_lib IN_LIST ABLMG_LIGHT_LIBRARIES)
    string(APPEND ABLMG_PC_LIBS " -l${_lib}")
  endif()
endforeach()
string(REPLACE ";" " " ABLMG_PC_OPENMP "${OpenMP_CXX_FLAGS}")
# The prefix relative to the .pc file, so that `cmake --install --prefix P` gives a working file.
file(RELATIVE_PATH ABLMG_PC_PREFIX /root/${CMAKE_INSTALL_LIBDIR}/pkgconfig /root)
string(REGEX REPLACE "/$" "" ABLMG_PC_PREFIX "${ABLMG_PC_PREFIX}")
configure_file(${CMAKE_CURRENT_LIST_DIR}/ablmg.pc.in ${PROJECT_BINARY_DIR}/ablmg.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/ablmg.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

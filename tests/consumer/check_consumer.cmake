# Run by CTest through `cmake -P` (label consumer): installs the build BUILD into a fresh
# temporary prefix, configures and builds tests/consumer against it with find_package(ablmg),
# runs both programs, and checks with ldd that neither links VTK, cairo or CHOLMOD (nor
# muparser, OpenBLAS: the remesh path needs only the C++ runtime and OpenMP).
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
endfunction()
file(REMOVE_RECURSE ${WORK})
run(${CMAKE_COMMAND} --install ${BUILD} --prefix ${WORK}/prefix)
run(${CMAKE_COMMAND} -S ${SOURCE} -B ${WORK}/build -DCMAKE_PREFIX_PATH=${WORK}/prefix -DCMAKE_BUILD_TYPE=Release
    -DCMAKE_C_COMPILER=${CC} -DCMAKE_CXX_COMPILER=${CXX})
run(${CMAKE_COMMAND} --build ${WORK}/build)
foreach(program remesh_cpp remesh_c)
  run(${WORK}/build/${program})
  message(STATUS "${program}:\n${out}")
  run(ldd ${WORK}/build/${program})
  if(out MATCHES "(vtk|cairo|cholmod|muparser|openblas|blas)[^\n]*")
    message(FATAL_ERROR "${program} links ${CMAKE_MATCH_0}:\n${out}")
  endif()
  if(NOT out MATCHES "libstdc\\+\\+")
    message(FATAL_ERROR "unexpected ldd output for ${program}:\n${out}")
  endif()
endforeach()

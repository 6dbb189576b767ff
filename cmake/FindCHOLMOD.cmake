# SuiteSparse 5.12 (Debian 12) ships no CMake or pkg-config file for CHOLMOD:
# find suitesparse/cholmod.h and libcholmod (+ the SuiteSparse libraries it needs) here, and
# METIS (fem/ordering.cpp calls METIS_NodeND directly, for comparison).
find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
find_library(CHOLMOD_LIBRARY cholmod)
find_library(SUITESPARSECONFIG_LIBRARY suitesparseconfig)
find_library(AMD_LIBRARY amd)
find_library(COLAMD_LIBRARY colamd)
find_library(CAMD_LIBRARY camd)
find_library(CCOLAMD_LIBRARY ccolamd)
# LAPACK and BLAS: fem/split_cholesky.cpp calls dpotrf, dsyrk, dtrmv and dtrsv itself (the
# libraries CHOLMOD runs on; Debian's alternatives pick OpenBLAS when it is installed).
find_library(LAPACK_LIBRARY lapack)
find_library(BLAS_LIBRARY blas)
find_path(METIS_INCLUDE_DIR metis.h)
find_library(METIS_LIBRARY metis)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(CHOLMOD REQUIRED_VARS CHOLMOD_LIBRARY CHOLMOD_INCLUDE_DIR
                                  SUITESPARSECONFIG_LIBRARY AMD_LIBRARY COLAMD_LIBRARY METIS_LIBRARY METIS_INCLUDE_DIR
                                  LAPACK_LIBRARY BLAS_LIBRARY)
if(CHOLMOD_FOUND AND NOT TARGET CHOLMOD::CHOLMOD)
  add_library(CHOLMOD::CHOLMOD INTERFACE IMPORTED)
  set_target_properties(CHOLMOD::CHOLMOD PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${CHOLMOD_INCLUDE_DIR};${METIS_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${CHOLMOD_LIBRARY};${AMD_LIBRARY};${COLAMD_LIBRARY};${CAMD_LIBRARY};${CCOLAMD_LIBRARY};${SUITESPARSECONFIG_LIBRARY};${METIS_LIBRARY};${LAPACK_LIBRARY};${BLAS_LIBRARY}")
endif()

# examples/compare_freefem/: FreeFem++ vs ablmg on the wave front (run.sh). Only the table/picture
# program is built here; it is not a CTest test (the suite must not need FreeFem++).
add_executable(compare_freefem_plot ${CMAKE_CURRENT_SOURCE_DIR}/compare_freefem/compare_plot.cpp)
target_link_libraries(compare_freefem_plot PRIVATE ablmg_adapt ablmg_io)
set_target_properties(compare_freefem_plot PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/examples)

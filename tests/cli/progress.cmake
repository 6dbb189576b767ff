# The progress line on stderr (cli/progress_line.hpp): off when piped, the same outputs with
# and without it, shown in place on a pseudo-terminal (check_progress.cmake.in).
add_test(NAME cli.progress_line_piped_identical_and_on_a_terminal
         COMMAND ${CMAKE_COMMAND} -DABLMG=$<TARGET_FILE:ablmg>
                 -DCONFIG=${PROJECT_SOURCE_DIR}/examples/configs/paper_disk_constant.json
                 -DOUT=${CMAKE_CURRENT_BINARY_DIR}/cli_out/progress -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/check_progress.cmake.in)
set_tests_properties(cli.progress_line_piped_identical_and_on_a_terminal PROPERTIES LABELS cli TIMEOUT 300)

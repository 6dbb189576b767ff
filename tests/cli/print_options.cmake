# `ablmg remesh|adapt|mesh|surface --print-options`: the presets, the flags applied, and a round trip
# through an `ablmg mesh` config (check_print_options.cmake.in).
add_test(NAME cli.print_options
         COMMAND ${CMAKE_COMMAND} -DABLMG=$<TARGET_FILE:ablmg> -DOUT=${CMAKE_CURRENT_BINARY_DIR}/cli_out/print_options
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/check_print_options.cmake.in)
set_tests_properties(cli.print_options PROPERTIES LABELS cli)

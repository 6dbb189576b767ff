# Example 06 as a CTest test at a small size: 3 cycles from 1000 vertices; the errors must
# decrease and the fitted rates must be printed as numbers.
add_test(NAME example_06_adaptive_wave_front COMMAND ex06_adaptive_wave_front --cycles 3 --n0 1000)
set_tests_properties(example_06_adaptive_wave_front PROPERTIES
  LABELS example
  PASS_REGULAR_EXPRESSION "Errors decrease: yes"
  FAIL_REGULAR_EXPRESSION "nan|inf")
add_test(NAME example_06_adaptive_wave_front_bad_option COMMAND ex06_adaptive_wave_front --beta 3)
set_tests_properties(example_06_adaptive_wave_front_bad_option PROPERTIES LABELS example WILL_FAIL TRUE)
# Example 07 (the loop driven step by step, no exact solution): 3 cycles from 500 vertices;
# the estimated interpolation error must fall at least like N^-0.8.
add_test(NAME example_07_solver_in_the_loop COMMAND ex07_solver_in_the_loop --cycles 3 --pictures 0)
set_tests_properties(example_07_solver_in_the_loop PROPERTIES
  LABELS example
  PASS_REGULAR_EXPRESSION "Falls at least like N\\^-0.8: yes"
  FAIL_REGULAR_EXPRESSION "nan|inf")

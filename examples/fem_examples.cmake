# Example 05 as a CTest test at a small size: the smooth problem on 4 perturbed levels must
# report rates near 2 (L2) and 1 (H1); the regular expression checks the printed slopes.
add_test(NAME example_05_poisson_convergence
         COMMAND ex05_poisson_convergence --levels 4 --n0 8)
set_tests_properties(example_05_poisson_convergence PROPERTIES
  LABELS example
  PASS_REGULAR_EXPRESSION "Fitted rates \\(all levels\\): L2 (1\\.9|2\\.0|2\\.1)[0-9]*  H1 (0\\.9|1\\.0)[0-9]*"
  FAIL_REGULAR_EXPRESSION "nan|inf")
add_test(NAME example_05_poisson_convergence_bad_problem
         COMMAND ex05_poisson_convergence --problem nosuch)
set_tests_properties(example_05_poisson_convergence_bad_problem PROPERTIES
  LABELS example WILL_FAIL TRUE)

# cli/main.cpp: when other tasks keep the cores busy and the user set no OpenMP wait policy,
# ablmg runs itself again with OMP_WAIT_POLICY=PASSIVE (libgomp then reports a spin count of
# 0); a policy the user set is left alone. The busy loop runs beside the command for ~3 s.
if(EXISTS /proc/stat)
  set(_busy "( end=$((SECONDS+3)); while [ $SECONDS -lt $end ]; do :; done ) & b=$!; sleep 0.3")
  add_test(NAME cli.openmp_passive_under_load
           COMMAND bash -c "${_busy}; env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT OMP_DISPLAY_ENV=verbose $<TARGET_FILE:ablmg> stats ${PROJECT_SOURCE_DIR}/tests/data/square.mesh 2>&1; kill $b")
  set_tests_properties(cli.openmp_passive_under_load PROPERTIES LABELS cli
                       PASS_REGULAR_EXPRESSION "GOMP_SPINCOUNT = '0'.*valid: yes")
  add_test(NAME cli.openmp_policy_of_the_user_kept
           COMMAND bash -c "${_busy}; env -u GOMP_SPINCOUNT OMP_WAIT_POLICY=active OMP_DISPLAY_ENV=verbose $<TARGET_FILE:ablmg> stats ${PROJECT_SOURCE_DIR}/tests/data/square.mesh 2>&1; kill $b")
  set_tests_properties(cli.openmp_policy_of_the_user_kept PROPERTIES LABELS cli
                       PASS_REGULAR_EXPRESSION "OMP_WAIT_POLICY = 'ACTIVE'.*valid: yes" FAIL_REGULAR_EXPRESSION "GOMP_SPINCOUNT = '0'")
endif()

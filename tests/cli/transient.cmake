# CLI tests of `ablmg transient`: bad options exit non-zero with one error line naming the
# option and leave no output directory behind; a small good run writes every output; 1 and 2
# threads give byte-identical steps.csv and frames. Included by tests/CMakeLists.txt; run as a
# script (cmake -P) it performs one check.
if(CMAKE_SCRIPT_MODE_FILE AND MODE STREQUAL "success")
  file(REMOVE_RECURSE "${OUTDIR}")
  separate_arguments(_args UNIX_COMMAND "${ARGS}")
  execute_process(COMMAND "${BIN}" transient ${_args} --out-dir "${OUTDIR}" RESULT_VARIABLE rc OUTPUT_VARIABLE out
                  ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "exit ${rc}\n${out}${err}")
  endif()
  file(STRINGS "${OUTDIR}/intervals.csv" _lines)
  list(GET _lines 0 _header)
  if(NOT _header STREQUAL "interval,time,vertices,l2_at_remesh,l2_at_end,space_time_l2,space_time_h1,mass_defect,t_remesh,t_transfer,t_solve,t_metric")
    message(FATAL_ERROR "bad intervals.csv header: ${_header}")
  endif()
  list(LENGTH _lines _n)
  if(NOT _n EQUAL 3)
    message(FATAL_ERROR "expected 2 interval rows, got ${_n} lines")
  endif()
  foreach(f steps.csv report.json error_vs_time.png series.pvd frames/interval_0000.vtu frames/interval_0001.png)
    if(NOT EXISTS "${OUTDIR}/${f}")
      message(FATAL_ERROR "missing ${OUTDIR}/${f}")
    endif()
  endforeach()
  file(READ "${OUTDIR}/report.json" _j)
  string(JSON _defect GET "${_j}" max_mass_defect)
  if(_defect GREATER 1e-12)
    message(FATAL_ERROR "mass defect ${_defect} > 1e-12")
  endif()
  if(NOT out MATCHES "Interval 1: t=[0-9.e-]+\\.\\.[0-9.e-]+ N=[0-9]+ L2\\(t\\)=")
    message(FATAL_ERROR "no interval line in the output:\n${out}")
  endif()
  return()
endif()
if(CMAKE_SCRIPT_MODE_FILE AND MODE STREQUAL "threads")
  foreach(t 1 2)
    set(ENV{OMP_NUM_THREADS} ${t})
    file(REMOVE_RECURSE "${OUTDIR}_${t}")
    separate_arguments(_args UNIX_COMMAND "${ARGS}")
    execute_process(COMMAND "${BIN}" transient ${_args} --out-dir "${OUTDIR}_${t}" RESULT_VARIABLE rc OUTPUT_QUIET
                    ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "${t} threads: exit ${rc}\n${err}")
    endif()
  endforeach()
  foreach(f steps.csv frames/interval_0000.vtu frames/interval_0001.vtu series.pvd)
    file(SHA256 "${OUTDIR}_1/${f}" a)
    file(SHA256 "${OUTDIR}_2/${f}" b)
    if(NOT a STREQUAL b)
      message(FATAL_ERROR "${f} differs between 1 and 2 threads")
    endif()
  endforeach()
  return()
endif()
if(CMAKE_SCRIPT_MODE_FILE)
  file(REMOVE_RECURSE "${OUTDIR}")
  separate_arguments(_args UNIX_COMMAND "${ARGS}")
  execute_process(COMMAND "${BIN}" transient ${_args} --out-dir "${OUTDIR}" RESULT_VARIABLE rc OUTPUT_VARIABLE out
                  ERROR_VARIABLE err)
  if(rc EQUAL 0)
    message(FATAL_ERROR "expected failure, got exit 0\n${out}${err}")
  endif()
  string(STRIP "${err}" err)
  string(FIND "${err}" "\n" nl)
  if(NOT nl EQUAL -1)
    message(FATAL_ERROR "expected one error line, got:\n${err}")
  endif()
  if(NOT err MATCHES "${EXPECT}")
    message(FATAL_ERROR "stderr does not match '${EXPECT}':\n${err}")
  endif()
  if(EXISTS "${OUTDIR}")
    message(FATAL_ERROR "a failed run left ${OUTDIR}")
  endif()
  return()
endif()

set(_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_transient)
file(MAKE_DIRECTORY ${_dir})
foreach(
  case
  "k_zero|--problem movingpeak --remesh-every 0|--remesh-every: expected an integer in \\[1, 1000000\\], got '0'"
  "k_fraction|--problem movingpeak --remesh-every 2.5|--remesh-every: expected an integer"
  "dt_zero|--problem movingpeak --dt 0|--dt must be > 0, got 0"
  "dt_negative|--problem movingpeak --dt -0.01|--dt must be > 0, got -0.01"
  "t_end_before_start|--problem movingpeak --t-end -0.5|the final time -0.5 must be after the start time 0"
  "t_end_at_start|--problem front --t-end 0|the final time 0 must be after the start time 0"
  "no_problem|--dt 0.01|--problem NAME is required"
  "unknown_problem|--problem wave|unknown transient problem 'wave' \\(valid: movingpeak, front\\)"
  "unknown_param|--problem movingpeak --param beta=2|unknown parameter 'beta'"
  "bad_vertices|--problem movingpeak --vertices 3|vertices must be >= 10 \\(got 3\\)"
  "bad_hessian_every|--problem movingpeak --hessian-every 0|--hessian-every: expected an integer in \\[1, 1000000\\], got '0'"
  "bad_fixed_point|--problem movingpeak --fixed-point-iterations 0|--fixed-point-iterations: expected an integer in \\[1, 20\\]"
  "bad_metric|--problem movingpeak --metric future|unknown transient metric 'future'"
  "bad_scheme|--problem movingpeak --scheme rk4|unknown time scheme 'rk4'"
  "bad_transfer|--problem movingpeak --transfer nearest|unknown transfer method 'nearest'"
  "missing_value|--problem movingpeak --dt|--dt needs a value"
  "bad_number|--problem movingpeak --dt abc|--dt: expected a number, got 'abc'"
  "nan_t_end|--problem movingpeak --t-end nan|--t-end: expected a number, got 'nan'"
  "unknown_flag|--problem movingpeak --frobnicate 1|unknown argument '--frobnicate'"
  "plot_with_missing|--problem movingpeak --plot-with uniform=/nonexistent/dir|--plot-with uniform: cannot read /nonexistent/dir/steps.csv")
  string(REPLACE "|" ";" _parts "${case}")
  list(GET _parts 0 _name)
  list(GET _parts 1 _args)
  list(GET _parts 2 _expect)
  add_test(NAME cli_transient_${_name}
           COMMAND ${CMAKE_COMMAND} -DBIN=$<TARGET_FILE:ablmg> "-DARGS=${_args}" "-DEXPECT=${_expect}"
                   -DOUTDIR=${_dir}/${_name} -P ${CMAKE_CURRENT_LIST_FILE})
  set_tests_properties(cli_transient_${_name} PROPERTIES LABELS cli)
endforeach()

set(_small "--problem movingpeak --param alpha=300 --dt 0.005 --t-end 0.02 --remesh-every 2 --vertices 400 --fixed-point-iterations 1")
add_test(NAME cli_transient_success
         COMMAND ${CMAKE_COMMAND} -DBIN=$<TARGET_FILE:ablmg> -DMODE=success "-DARGS=${_small}"
                 -DOUTDIR=${_dir}/success -P ${CMAKE_CURRENT_LIST_FILE})
set_tests_properties(cli_transient_success PROPERTIES LABELS cli)
add_test(NAME cli_transient_deterministic_across_threads
         COMMAND ${CMAKE_COMMAND} -DBIN=$<TARGET_FILE:ablmg> -DMODE=threads "-DARGS=${_small}"
                 -DOUTDIR=${_dir}/threads -P ${CMAKE_CURRENT_LIST_FILE})
set_tests_properties(cli_transient_deterministic_across_threads PROPERTIES LABELS cli)
add_test(NAME cli_transient_help COMMAND $<TARGET_FILE:ablmg> transient --help)
set_tests_properties(cli_transient_help PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "usage: ablmg transient --problem NAME")

# CLI tests of `ablmg adapt` on bad inputs: exit non-zero with a one-line error naming the
# problem, and no convergence.csv left behind. Included by tests/CMakeLists.txt; run as a
# script (cmake -P) it performs one check.
if(CMAKE_SCRIPT_MODE_FILE AND MODE STREQUAL "success")
  # A small good run: exit 0, the exact CSV header, one row per cycle, every output present.
  file(REMOVE_RECURSE "${OUTDIR}")
  separate_arguments(_args UNIX_COMMAND "${ARGS}")
  execute_process(COMMAND "${BIN}" adapt ${_args} --out-dir "${OUTDIR}" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "exit ${rc}\n${out}${err}")
  endif()
  file(STRINGS "${OUTDIR}/convergence.csv" _lines)
  list(GET _lines 0 _header)
  if(NOT _header MATCHES "^cycle,vertices,triangles,l2_error,h1_error,l2_interp_error,q_mean,q_min,t_solve,t_recover,t_metric,t_mesh(,|$)")
    message(FATAL_ERROR "bad CSV header: ${_header}")
  endif()
  list(LENGTH _lines _n)
  if(NOT _n EQUAL 3)
    message(FATAL_ERROR "expected 2 cycle rows, got ${_n} lines")
  endif()
  foreach(f convergence.json convergence.png final_mesh.png cycle_0.vtu cycle_1.vtu)
    if(NOT EXISTS "${OUTDIR}/${f}")
      message(FATAL_ERROR "missing ${OUTDIR}/${f}")
    endif()
  endforeach()
  if(NOT out MATCHES "Cycle 1: N=[0-9]+ T=[0-9]+ L2=")
    message(FATAL_ERROR "no cycle line in the output:\n${out}")
  endif()
  return()
endif()
if(CMAKE_SCRIPT_MODE_FILE AND MODE STREQUAL "config_matches_library")
  # A problem written as expressions in a config (examples/configs/adapt_peak_expressions.json)
  # gives the library problem's loop: the same vertices, errors and qualities in every cycle.
  foreach(kind config library)
    file(REMOVE_RECURSE "${OUTDIR}_${kind}")
    if(kind STREQUAL "config")
      set(_what "${CONFIG}")
    else()
      set(_what --problem peak)
    endif()
    execute_process(COMMAND "${BIN}" adapt ${_what} --target-vertices 300,900 --uniform off --vtu off --out-dir "${OUTDIR}_${kind}"
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "${kind}: exit ${rc}\n${out}${err}")
    endif()
    file(STRINGS "${OUTDIR}_${kind}/convergence.csv" _rows)
    set(_${kind} "")
    foreach(_row ${_rows})
      string(REGEX MATCH "^([^,]*,){8}" _head "${_row}")  # cycle … q_min: no times
      list(APPEND _${kind} "${_head}")
    endforeach()
  endforeach()
  if(NOT _config STREQUAL _library)
    message(FATAL_ERROR "config and library loops differ:\n${_config}\n${_library}")
  endif()
  return()
endif()
if(CMAKE_SCRIPT_MODE_FILE AND MODE STREQUAL "no_exact")
  # A config without an exact solution: meshes and reports, errors NaN, the estimate (est=) plotted.
  file(REMOVE_RECURSE "${OUTDIR}")
  execute_process(COMMAND "${BIN}" adapt "${CONFIG}" --target-vertices 300,600 --vtu off --out-dir "${OUTDIR}"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "exit ${rc}\n${out}${err}")
  endif()
  file(STRINGS "${OUTDIR}/convergence.csv" _lines)
  list(LENGTH _lines _n)
  list(GET _lines 2 _row)
  if(NOT _n EQUAL 3 OR NOT _row MATCHES "^1,[0-9]+,[0-9]+,nan,nan,nan,0\\.9")
    message(FATAL_ERROR "unexpected CSV:\n${_lines}")
  endif()
  if(NOT EXISTS "${OUTDIR}/final_mesh.png" OR NOT EXISTS "${OUTDIR}/convergence.png" OR NOT out MATCHES "no exact solution"
     OR NOT out MATCHES "Cycle 1: N=[0-9]+ T=[0-9]+ est=[0-9.e+-]+ q=")
    message(FATAL_ERROR "outputs or message wrong:\n${out}")
  endif()
  return()
endif()
if(CMAKE_SCRIPT_MODE_FILE AND MODE STREQUAL "figures")
  # The per-problem figures from convergence.json: every cycle's mesh valid (the run
  # fails otherwise) with q mean >= 0.9; the fitted rates over the last 4 cycles at most
  # MAX_H1_RATE / MAX_L2_RATE; and, if MIN_UNIFORM_RATIO is set, the finest uniform mesh's H1
  # error reached by the adaptive curve with at least that many times fewer vertices.
  file(REMOVE_RECURSE "${OUTDIR}")
  separate_arguments(_args UNIX_COMMAND "${ARGS}")
  execute_process(COMMAND "${BIN}" adapt ${_args} --vtu off --out-dir "${OUTDIR}" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "exit ${rc}\n${out}${err}")
  endif()
  file(READ "${OUTDIR}/convergence.json" _j)
  string(JSON _n LENGTH "${_j}" cycles)
  math(EXPR _last "${_n} - 1")
  if(NOT DEFINED MIN_Q_MEAN)
    set(MIN_Q_MEAN 0.9)
  endif()
  if(NOT DEFINED FALL_FROM)
    set(FALL_FROM 1000000)  # no check
  endif()
  foreach(_i RANGE ${_last})
    string(JSON _q GET "${_j}" cycles ${_i} q_mean)
    if(_q LESS ${MIN_Q_MEAN})
      message(FATAL_ERROR "cycle ${_i}: q mean ${_q} < ${MIN_Q_MEAN}")
    endif()
    # Whenever the target size grows, both errors fall (FALL_FROM: from that cycle on).
    if(_i GREATER 0 AND _i GREATER_EQUAL ${FALL_FROM})
      math(EXPR _p "${_i} - 1")
      string(JSON _n1 GET "${_j}" cycles ${_i} target_vertices)
      string(JSON _n0 GET "${_j}" cycles ${_p} target_vertices)
      if(_n1 GREATER _n0)
        foreach(_e l2_error h1_error)
          string(JSON _e1 GET "${_j}" cycles ${_i} ${_e})
          string(JSON _e0 GET "${_j}" cycles ${_p} ${_e})
          if(NOT _e1 LESS _e0)
            message(FATAL_ERROR "cycle ${_i}: N ${_n0} -> ${_n1} but ${_e} ${_e0} -> ${_e1}")
          endif()
        endforeach()
      endif()
    endif()
  endforeach()
  string(JSON _h1 GET "${_j}" rates h1)
  if(NOT DEFINED L2_KEY)
    set(L2_KEY l2)
  endif()
  string(JSON _l2 GET "${_j}" rates ${L2_KEY})
  message(STATUS "rates: H1 ${_h1}, L2 ${_l2}")
  if(_h1 GREATER ${MAX_H1_RATE} OR _l2 GREATER ${MAX_L2_RATE})
    message(FATAL_ERROR "rates H1 ${_h1} (need <= ${MAX_H1_RATE}), L2 ${_l2} (need <= ${MAX_L2_RATE})")
  endif()
  if(DEFINED CHECK_INTERFACES)  # subdomains: the final mesh's interfaces cover the input's
    string(JSON _unc GET "${_j}" interfaces uncovered)
    string(JSON _len GET "${_j}" interfaces length)
    message(STATUS "interfaces: ${_unc} of ${_len} uncovered")
    if(_unc GREATER 1e-9 OR NOT _len GREATER 0)
      message(FATAL_ERROR "interfaces not resolved: ${_unc} of their length ${_len} uncovered")
    endif()
  endif()
  if(DEFINED MIN_UNIFORM_RATIO)
    string(JSON _ratio GET "${_j}" uniform_match h1 ratio)
    message(STATUS "finest uniform H1 error reached with ${_ratio}x fewer vertices")
    if(NOT _ratio GREATER_EQUAL ${MIN_UNIFORM_RATIO})
      message(FATAL_ERROR "uniform ratio ${_ratio} < ${MIN_UNIFORM_RATIO}")
    endif()
  endif()
  return()
endif()
if(CMAKE_SCRIPT_MODE_FILE)
  file(REMOVE_RECURSE "${OUTDIR}")
  separate_arguments(_args UNIX_COMMAND "${ARGS}")
  execute_process(COMMAND "${BIN}" adapt ${_args} --out-dir "${OUTDIR}" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc EQUAL 0)
    message(FATAL_ERROR "expected failure, got exit 0\n${out}${err}")
  endif()
  if(NOT err MATCHES "${EXPECT}")
    message(FATAL_ERROR "stderr does not match '${EXPECT}':\n${err}")
  endif()
  if(EXISTS "${OUTDIR}/convergence.csv")
    message(FATAL_ERROR "a failed run left ${OUTDIR}/convergence.csv")
  endif()
  return()
endif()

set(_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_adapt)
file(MAKE_DIRECTORY ${_dir})
file(WRITE ${_dir}/bad_f.json "{\"domain\": {\"rectangle\": [0,0,1,1]}, \"problem\": {\"f\": \"1 +* x\", \"dirichlet\": {\"default\": \"0\"}}}\n")
file(WRITE ${_dir}/no_domain.json "{\"problem\": {\"f\": \"1\", \"dirichlet\": {\"default\": \"0\"}}}\n")
file(WRITE ${_dir}/library_domain.json "{\"domain\": {\"rectangle\": [0,0,1,1]}, \"problem\": \"peak\"}\n")
foreach(case
    "no_problem|--target-vertices 100|give either --problem NAME or CONFIG.json"
    "problem_and_config|--problem peak ${PROJECT_SOURCE_DIR}/examples/configs/adapt_lshape_load.json --target-vertices 100|give either --problem NAME or CONFIG.json"
    "config_stop_without_exact|${PROJECT_SOURCE_DIR}/examples/configs/adapt_lshape_load.json --target-vertices 300 --stop-l2 1e-3|stopL2/stopH1 need the exact solution"
    "config_missing|${_dir}/nonexistent.json --target-vertices 300|nonexistent.json: cannot open"
    "config_bad_expression|${_dir}/bad_f.json --target-vertices 300|bad_f.json: problem.f: bad expression"
    "config_no_domain|${_dir}/no_domain.json --target-vertices 300|no_domain.json: domain: missing"
    "config_library_domain|${_dir}/library_domain.json --target-vertices 300|library_domain.json: domain: a library problem has its own domain"
    "no_targets|--problem wavefront|--vertices N \\(the default schedule\\) or --target-vertices N1,N2,... is required"
    "vertices_and_targets|--problem wavefront --vertices 1000 --target-vertices 500|give --vertices N or --target-vertices, not both"
    "bad_vertices|--problem wavefront --vertices 5|final vertices must be in \\[10, 1e9\\] \\(got 5\\)"
    "bad_growth|--problem wavefront --vertices 1000 --growth 1|growth must be in \\(1.01, 100\\]"
    "bad_passes|--problem wavefront --vertices 1000 --passes 0|--passes must be an integer in 1..20"
    "unknown_problem|--problem wavefrnt --target-vertices 500|unknown problem 'wavefrnt'"
    "unknown_param|--problem wavefront --param beta=1 --target-vertices 500|unknown parameter 'beta'"
    "bad_param|--problem wavefront --param alpha --target-vertices 500|--param expects KEY=VALUE"
    "bad_number|--problem wavefront --target-vertices 500,abc|expected a number, got 'abc'"
    "nan_number|--problem wavefront --target-vertices 500 --hgrad nan|adapt: --hgrad: expected a number, got 'nan'"
    "inf_number|--problem wavefront --target-vertices 500 --hgrad inf|adapt: --hgrad: expected a number, got 'inf'"
    "small_target|--problem wavefront --target-vertices 500,3|must be >= 10 \\(got 3\\)"
    "bad_p|--problem wavefront --target-vertices 500 --p 0.5|p must be >= 1"
    "bad_hgrad|--problem wavefront --target-vertices 500 --hgrad 0.9|hgrad must be > 1"
    "bad_hessian|--problem wavefront --target-vertices 500 --hessian cubic|unknown Hessian recovery method 'cubic'"
    "unknown_flag|--problem wavefront --target-vertices 500 --frobnicate 1|unknown argument '--frobnicate'"
    "bad_norm|--problem wavefront --target-vertices 500 --norm h2|norm"
    "bad_shape_blend|--problem wavefront --target-vertices 500 --shape-blend 2|shape"
    "bad_plateau_gain|--problem wavefront --target-vertices 500 --plateau-gain 1|--plateau-gain must be in \\[0, 1\\), got 1"
    "bad_repeat_min_change|--problem wavefront --vertices 1000 --repeat-min-change -1|--repeat-min-change must be in \\[0, 10\\]"
    "bad_stop_h1|--problem wavefront --vertices 1000 --stop-h1 0|--stop-h1 must be a positive error, got 0"
    "bad_stop_l2|--problem wavefront --vertices 1000 --stop-l2 -1e-3|--stop-l2 must be a positive error, got -0.001"
    "bad_stop_aim|--problem wavefront --vertices 1000 --stop-h1 0.1 --stop-aim 1.5|--stop-aim must be in \\[0, 1\\] \\(0: off\\), got 1.5"
    "bad_stop_jump|--problem wavefront --vertices 1000 --stop-h1 0.1 --stop-jump 200|--stop-jump must be in \\[0, 100\\], got 200"
    "bad_saddle_shape|--problem wavefront --vertices 1000 --saddle-shape 2|--saddle-shape must be in \\[0, 1\\], got 2"
    "bad_lattice|--problem wavefront --target-vertices 500 --lattice diagonal|lattice orientation: expected axes, short, long or auto, got 'diagonal'")
  string(REPLACE "|" ";" _parts "${case}")
  list(GET _parts 0 _name)
  list(GET _parts 1 _args)
  list(GET _parts 2 _expect)
  add_test(NAME cli_adapt_${_name}
           COMMAND ${CMAKE_COMMAND} -DBIN=$<TARGET_FILE:ablmg> "-DARGS=${_args}" "-DEXPECT=${_expect}"
                   -DOUTDIR=${_dir}/${_name} -P ${CMAKE_CURRENT_LIST_FILE})
  set_tests_properties(cli_adapt_${_name} PROPERTIES LABELS cli)
endforeach()

add_test(NAME cli_adapt_success
         COMMAND ${CMAKE_COMMAND} -DBIN=$<TARGET_FILE:ablmg> -DMODE=success
                 "-DARGS=--problem wavefront --target-vertices 300,600" -DOUTDIR=${_dir}/success
                 -P ${CMAKE_CURRENT_LIST_FILE})
set_tests_properties(cli_adapt_success PROPERTIES LABELS cli)

add_test(NAME cli_adapt_help COMMAND $<TARGET_FILE:ablmg> adapt --help)
set_tests_properties(cli_adapt_help PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "usage: ablmg adapt \\(--problem NAME .* \\| CONFIG.json\\)")

# Determinism of the whole loop (lattice, plateau stop, post-pass included): 1 and 2 threads give
# byte-identical meshes and metrics in every cycle.
add_test(NAME cli_adapt_deterministic_across_threads
         COMMAND ${CMAKE_COMMAND} -DABLMG=$<TARGET_FILE:ablmg> -DOUT=${_dir}/determinism
                 -P ${CMAKE_CURRENT_LIST_DIR}/check_identical_adapt.cmake.in)
set_tests_properties(cli_adapt_deterministic_across_threads PROPERTIES LABELS cli)

add_test(NAME cli_adapt_config_matches_library
         COMMAND ${CMAKE_COMMAND} -DBIN=$<TARGET_FILE:ablmg> -DMODE=config_matches_library
                 -DCONFIG=${PROJECT_SOURCE_DIR}/examples/configs/adapt_peak_expressions.json -DOUTDIR=${_dir}/peak
                 -P ${CMAKE_CURRENT_LIST_FILE})
set_tests_properties(cli_adapt_config_matches_library PROPERTIES LABELS cli)
add_test(NAME cli_adapt_config_no_exact
         COMMAND ${CMAKE_COMMAND} -DBIN=$<TARGET_FILE:ablmg> -DMODE=no_exact
                 -DCONFIG=${PROJECT_SOURCE_DIR}/examples/configs/adapt_lshape_load.json -DOUTDIR=${_dir}/no_exact
                 -P ${CMAKE_CURRENT_LIST_FILE})
set_tests_properties(cli_adapt_config_no_exact PROPERTIES LABELS cli)

# The figures per problem (docs/benchmarks.md, adaptive loop): the layer at
# optimal rates and the finest uniform mesh's H1 error (16k vertices) reached with >= 10x fewer
# vertices; the reentrant corner's H1 rate <= -0.45 (uniform refinement: about -1/3). The
# layer's L2 rate is that of the nodal interpolant: its FE L2 error is dominated by a smooth
# global discrete error and moves by 3x with small changes of the mesh (1.5e-4 to 2.7e-4 at
# 7.7k vertices), its rate with it (-0.7 to -1.1).
add_test(NAME cli_adapt_layer_figures
         COMMAND ${CMAKE_COMMAND} -DBIN=$<TARGET_FILE:ablmg> -DMODE=figures
                 "-DARGS=--problem tanhlayer --target-vertices 250,500,1000,2000,4000,8000,16000"
                 -DMAX_H1_RATE=-0.45 -DMAX_L2_RATE=-0.9 -DL2_KEY=l2_interp -DMIN_UNIFORM_RATIO=10 -DOUTDIR=${_dir}/layer
                 -P ${CMAKE_CURRENT_LIST_FILE})
add_test(NAME cli_adapt_lshape_figures
         COMMAND ${CMAKE_COMMAND} -DBIN=$<TARGET_FILE:ablmg> -DMODE=figures
                 "-DARGS=--problem lshape --target-vertices 500,1000,2000,4000,8000 --uniform off"
                 -DMAX_H1_RATE=-0.45 -DMAX_L2_RATE=-0.9 -DOUTDIR=${_dir}/lshape
                 -P ${CMAKE_CURRENT_LIST_FILE})
set_tests_properties(cli_adapt_layer_figures cli_adapt_lshape_figures PROPERTIES LABELS cli)

# A small loop per library problem with the default schedule (--vertices N): every cycle's mesh
# valid with q mean >= 0.95, both errors falling whenever the size grows, and the rates over the
# last sizes at least the optimal ones (L2 -1, H1 -1/2, with the acceptance margins -0.9, -0.45).
foreach(case
    "wavefront|--problem wavefront"
    "wavefront_steep|--problem wavefront --param alpha=1000"
    "peak|--problem peak"
    "lshape|--problem lshape"
    "tanhlayer|--problem tanhlayer"
    "reentrant_5pi4|--problem reentrant --param omega=3.9269908169872414"
    "reentrant_7pi4|--problem reentrant"
    "slit|--problem reentrant --param omega=6.283185307179586"
    "linesing|--problem linesing"
    "multiple|--problem multiple")
  string(REPLACE "|" ";" _parts "${case}")
  list(GET _parts 0 _name)
  list(GET _parts 1 _args)
  # 3000 vertices: at 2000 the wave front's L2 fit (sizes 250-2000) is pre-asymptotic (-0.88).
  # Two problems are held to what they do at every size from 3000 to 6000 vertices:
  # - the steep front (width 10⁻³) is unresolved on the first sizes (≈ 750 and 1500 vertices),
  #   where its L2 error stays ≈ 3 and may rise by a few % between them (2.93 → 2.95, or 6.6 →
  #   13.6 at --vertices 4000): errors must fall from cycle 4 on;
  # - the line singularity's L2 rate is −0.72 to −0.91 over those sizes (pollution from the
  #   under-resolved dual, docs/limitations.md), so its bar is −0.65; its interpolant and H1
  #   errors keep the optimal rates.
  set(_fall 1)
  set(_l2 -0.9)
  if(_name STREQUAL "wavefront_steep")
    set(_fall 4)
  elseif(_name STREQUAL "linesing")
    set(_l2 -0.65)
  endif()
  add_test(NAME cli_adapt_schedule_${_name}
           COMMAND ${CMAKE_COMMAND} -DBIN=$<TARGET_FILE:ablmg> -DMODE=figures "-DARGS=${_args} --vertices 3000 --uniform off"
                   -DMAX_H1_RATE=-0.45 -DMAX_L2_RATE=${_l2} -DMIN_Q_MEAN=0.95 -DFALL_FROM=${_fall}
                   -DOUTDIR=${_dir}/schedule_${_name} -P ${CMAKE_CURRENT_LIST_FILE})
  set_tests_properties(cli_adapt_schedule_${_name} PROPERTIES LABELS cli)
endforeach()

# Mitchell's battery (five materials, no exact solution): errors against the loop's own
# solution at 4000 vertices fall whenever the size grows, and the final mesh resolves every
# interface of the materials.
add_test(NAME cli_adapt_battery
         COMMAND ${CMAKE_COMMAND} -DBIN=$<TARGET_FILE:ablmg> -DMODE=figures
                 "-DARGS=--problem battery --target-vertices 250,500,1000 --reference-vertices 4000"
                 -DMAX_H1_RATE=-0.45 -DMAX_L2_RATE=-0.9 -DFALL_FROM=1 -DCHECK_INTERFACES=1
                 -DOUTDIR=${_dir}/battery -P ${CMAKE_CURRENT_LIST_FILE})
set_tests_properties(cli_adapt_battery PROPERTIES LABELS cli)

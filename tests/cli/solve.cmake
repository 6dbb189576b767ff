# CLI tests of `ablmg solve` on bad inputs (and one good run). Included by tests/CMakeLists.txt;
# the same file, run as a script (cmake -P), performs one check: the command must exit non-zero,
# print the expected one-line error on stderr, and leave no output file behind.
if(CMAKE_SCRIPT_MODE_FILE)
  file(REMOVE "${NOFILE}")
  execute_process(COMMAND "${BIN}" solve "${CONFIG}" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc EQUAL 0)
    message(FATAL_ERROR "expected failure, got exit 0\n${out}${err}")
  endif()
  if(NOT err MATCHES "${EXPECT}")
    message(FATAL_ERROR "stderr does not match '${EXPECT}':\n${err}")
  endif()
  if(EXISTS "${NOFILE}")
    message(FATAL_ERROR "a failed run left ${NOFILE}")
  endif()
  return()
endif()

set(_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_solve)
file(MAKE_DIRECTORY ${_dir})
function(ablmg_solve_bad name json expect)
  file(WRITE ${_dir}/${name}.json "${json}")
  add_test(NAME cli_solve_${name}
           COMMAND ${CMAKE_COMMAND} -DBIN=$<TARGET_FILE:ablmg> -DCONFIG=${_dir}/${name}.json
                   -DEXPECT=${expect} -DNOFILE=${_dir}/${name}_report.json -P ${CMAKE_CURRENT_LIST_FILE})
  set_tests_properties(cli_solve_${name} PROPERTIES LABELS cli)
endfunction()

set(_out "\"output\": {\"vtu\": \"NAME.vtu\", \"report\": \"NAME_report.json\"}")
foreach(case
    "bad_expression|{\"mesh\": {\"structured\": {\"nx\": 8}}, \"problem\": {\"f\": \"sin(\", \"dirichlet\": {\"default\": 0}}, OUT}|problem.f: bad expression"
    "unknown_key|{\"mesh\": {\"structured\": {\"nx\": 8, \"nz\": 3}}, \"problem\": \"peak\", OUT}|mesh.structured: unknown key 'nz'"
    "unknown_problem|{\"mesh\": {\"structured\": {\"nx\": 8}}, \"problem\": \"wavefrnt\", OUT}|unknown_problem.json: unknown problem 'wavefrnt' \\(valid: wavefront"
    "unknown_param|{\"mesh\": {\"structured\": {\"nx\": 8}}, \"problem\": \"wavefront\", \"params\": {\"beta\": 1}, OUT}|unknown_param.json: problem 'wavefront': unknown parameter 'beta' \\(valid: alpha"
    "pure_neumann|{\"mesh\": {\"structured\": {\"nx\": 8}, \"domain\": [0, 0, 1, 1]}, \"problem\": {\"f\": \"1\"}, OUT}|singular"
    "negative_kappa|{\"mesh\": {\"structured\": {\"nx\": 8}, \"domain\": [0, 0, 1, 1]}, \"problem\": {\"kappa\": \"x-0.5\", \"dirichlet\": {\"default\": 0}}, OUT}|kappa = -"
    "missing_mesh_file|{\"mesh\": \"no_such.mesh\", \"problem\": \"peak\", OUT}|no_such.mesh"
    "domain_not_numbers|{\"mesh\": {\"structured\": {\"nx\": 8}, \"domain\": [\"a\", 0, 1, 1]}, \"problem\": \"peak\", OUT}|mesh.domain: expected \\[x0, y0, x1, y1\\] \\(numbers\\)"
    "domain_inverted|{\"mesh\": {\"structured\": {\"nx\": 8}, \"domain\": [1, 0, 0, 1]}, \"problem\": \"peak\", OUT}|mesh.domain: need x0 < x1"
    "nx_not_integer|{\"mesh\": {\"structured\": {\"nx\": 2.5}}, \"problem\": \"peak\", OUT}|mesh.structured.nx: expected an integer"
    "absurd_size|{\"mesh\": {\"structured\": {\"nx\": 100000}}, \"problem\": \"peak\", OUT}|mesh.structured: nx × ny"
    "ordering_not_string|{\"mesh\": {\"structured\": {\"nx\": 8}}, \"problem\": \"peak\", \"solver\": {\"ordering\": 1}, OUT}|solver.ordering: expected a string"
    "invalid_json|{\"mesh\": |invalid JSON")
  string(REPLACE "|" ";" _parts "${case}")
  list(GET _parts 0 _name)
  list(GET _parts 1 _json)
  list(GET _parts 2 _expect)
  string(REPLACE "NAME" "${_name}" _o "${_out}")
  string(REPLACE "OUT" "${_o}" _json "${_json}")
  ablmg_solve_bad(${_name} "${_json}" "${_expect}")
endforeach()

# One good run: a library problem on a small perturbed mesh writes the .vtu and the report.
file(WRITE ${_dir}/good.json
     "{\"mesh\": {\"structured\": {\"nx\": 16, \"perturbation\": 0.2}}, \"problem\": \"smooth\", \"output\": {\"vtu\": \"good.vtu\", \"report\": \"good_report.json\"}}")
add_test(NAME cli_solve_good COMMAND ablmg solve ${_dir}/good.json)
set_tests_properties(cli_solve_good PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "L2=[0-9.e+-]+ .*H1=")

# The report of a solve large enough for the split factorisation (fem/split_cholesky.hpp):
# CHOLMOD's counts and the phase times, which add up to no more than the whole solve.
file(WRITE ${_dir}/phases.json
     "{\"mesh\": {\"structured\": {\"nx\": 160}}, \"problem\": \"peak\", \"output\": {\"vtu\": \"phases.vtu\", \"report\": \"phases_report.json\"}}")
add_test(NAME cli_solve_phases COMMAND ablmg solve ${_dir}/phases.json)
set_tests_properties(cli_solve_phases PROPERTIES LABELS cli FIXTURES_SETUP solve_phases
                     PASS_REGULAR_EXPRESSION "ordering [0-9.]+, factorisation [0-9.]+, [0-9.e+]+ GFlop")
add_test(NAME cli_solve_phases_report
         COMMAND ${CMAKE_COMMAND} -DREPORT=${_dir}/phases_report.json -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/check_solve_report.cmake.in)
set_tests_properties(cli_solve_phases_report PROPERTIES LABELS cli FIXTURES_REQUIRED solve_phases)

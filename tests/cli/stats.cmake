# CLI tests of `ablmg stats` (cli/cmd_stats.cpp). Included by tests/CMakeLists.txt.
# Good runs check a hand-computed figure in the output; bad runs go through check_failure.cmake.in
# (non-zero exit, exactly one stderr line matching, no output file left).
set(_data ${CMAKE_CURRENT_SOURCE_DIR}/data)
set(_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_stats)
file(MAKE_DIRECTORY ${_dir})

# square.mesh: four right isosceles triangles around the centre, q = √3/2 each in the identity.
add_test(NAME cli.stats_square COMMAND ablmg stats ${_data}/square.mesh --json ${_dir}/square.json)
set_tests_properties(cli.stats_square PROPERTIES LABELS cli
  PASS_REGULAR_EXPRESSION "8 edges; valid: yes.*min 0.866 +mean 0.866 +max 0.866.*wrote .*square.json")
add_test(NAME cli.stats_square_sol COMMAND ablmg stats ${_data}/square.mesh --sol ${_data}/square.sol)
set_tests_properties(cli.stats_square_sol PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "tensors from .*square.sol")

# A regular tetrahedron (edge 2√2) as a closed surface: Lee's α = 1; with --h 2√2 every l = 1.
file(WRITE ${_dir}/tetra.mesh "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n1 1 1 0\n1 -1 -1 0\n-1 1 -1 0\n-1 -1 1 0\n"
                              "Triangles\n4\n1 2 3 0\n1 4 2 0\n1 3 4 0\n2 4 3 0\nEnd\n")
add_test(NAME cli.stats_surface COMMAND ablmg stats ${_dir}/tetra.mesh --h 2.8284271247461903)
set_tests_properties(cli.stats_surface PROPERTIES LABELS cli
  PASS_REGULAR_EXPRESSION "3D mesh: 4 vertices, 4 triangles, 6 edges; valid: yes.*min 1 +mean 1 +max 1.*alpha \\(Lee\\): +min 1 ")

set(_cf ${CMAKE_CURRENT_SOURCE_DIR}/cli/check_failure.cmake.in)
function(ablmg_stats_failure name expect)
  add_test(NAME cli.${name}
           COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:ablmg>;stats;${ARGN}" "-DEXPECT=${expect}"
                   "-DOUT=${_dir}/${name}.json" -P ${_cf})
  set_tests_properties(cli.${name} PROPERTIES LABELS cli)
endfunction()
ablmg_stats_failure(stats_missing_file "^ablmg stats: error: .*no_such.mesh: cannot open" ${_data}/no_such.mesh --json ${_dir}/stats_missing_file.json)
ablmg_stats_failure(stats_sol_mismatch "mismatch.sol:4: 3 solution values but the mesh has 5 vertices"
                    ${_data}/square.mesh --sol ${_data}/mismatch.sol --json ${_dir}/stats_sol_mismatch.json)
ablmg_stats_failure(stats_bad_flag "unknown option '--foo'" ${_data}/square.mesh --foo --json ${_dir}/stats_bad_flag.json)
ablmg_stats_failure(stats_surface_sol "3D surface mesh takes only --h" ${_dir}/tetra.mesh --sol ${_data}/square.sol)

# --json alone: the report as JSON on stdout; --metric: the metric of a mesh config.
add_test(NAME cli.stats_json_stdout COMMAND ablmg stats ${_data}/square.mesh --json)
set_tests_properties(cli.stats_json_stdout PROPERTIES LABELS cli
  PASS_REGULAR_EXPRESSION "^{\n  \"e\": 0.05,\n  \"mesh\": .*\"min\": 0.866" FAIL_REGULAR_EXPRESSION "ablmg stats:")
file(WRITE ${_dir}/square_h.json "{\"domain\": {\"rectangle\": [0, 0, 1, 1]}, \"metric\": {\"h\": \"0.5\"}}")
# square.mesh's edges: four sides of length 1 (2 in the metric) and four half-diagonals (√2).
add_test(NAME cli.stats_metric_config COMMAND ablmg stats ${_data}/square.mesh --metric ${_dir}/square_h.json)
set_tests_properties(cli.stats_metric_config PROPERTIES LABELS cli
  PASS_REGULAR_EXPRESSION "isotropic h=0.5 \\(from .*square_h.json\\).*edge length l: +min 1.414 +mean 1.707 +max 2")
file(WRITE ${_dir}/bad_metric.json "{\"h1\": 3}")
ablmg_stats_failure(stats_bad_metric_config "bad_metric.json: h1: expected string, got number"
                    ${_data}/square.mesh --metric ${_dir}/bad_metric.json --json ${_dir}/stats_bad_metric_config.json)
ablmg_stats_failure(stats_two_metrics "give at most one of --sol, --metric, --metric-expr, --h"
                    ${_data}/square.mesh --h 1 --metric ${_dir}/square_h.json --json ${_dir}/stats_two_metrics.json)

# The paper's four cases given as a mesh + metric pair keep their figures (the remesh starts from
# the input's vertices where they fit: adapt/remesh.hpp, RemeshOptions::warmStart).
foreach(case_within disk_constant:0.95 disk_line:0.90 disk_ring:0.90 eq4_square_hole:0.90)
  string(REPLACE ":" ";" cw ${case_within})
  list(GET cw 0 case)
  list(GET cw 1 within)
  string(REGEX REPLACE "^disk_|_square_hole$" "" short ${case})
  add_test(NAME cli.remesh_pair_${short}
           COMMAND ${CMAKE_COMMAND} -DABLMG=$<TARGET_FILE:ablmg> -DCONFIG=${PROJECT_SOURCE_DIR}/examples/configs/paper_${case}.json
                   -DOUT=${_dir}/pair_${short} -DWITHIN10=${within} -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/check_pair_figures.cmake.in)
  set_tests_properties(cli.remesh_pair_${short} PROPERTIES LABELS cli)
endforeach()

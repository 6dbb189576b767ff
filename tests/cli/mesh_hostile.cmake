# Hostile and extreme inputs to `ablmg mesh` (the table is docs/hostile_inputs.md):
# each gets one clear error line and a non-zero exit with no output left, or a valid mesh.
# Uses ablmg_cli_failure() from io_cli.cmake (included before this file: tests/CMakeLists.txt includes them in name order).
set(_hdir ${CMAKE_CURRENT_BINARY_DIR}/cli_out/hostile)
file(MAKE_DIRECTORY ${_hdir})
function(ablmg_hostile_config name json)
  file(WRITE ${_hdir}/${name}.json "${json}\n")
endfunction()
ablmg_hostile_config(tiny "{\"domain\": {\"rectangle\": [0,0,1,1]}, \"metric\": {\"h\": \"1e-6\"}}")
ablmg_cli_failure(hostile_tiny_size "asks for about [0-9]+ nodes, more than maxNodes = 50000000" mesh ${_hdir}/tiny.json -o ${_hdir}/tiny.mesh)
ablmg_hostile_config(bad_lattice "{\"domain\": {\"rectangle\": [0,0,1,1]}, \"metric\": {\"h\": \"0.1\"}, \"options\": {\"placement\": {\"latticeOrientation\": \"diagonal\"}}}")
ablmg_cli_failure(config_bad_lattice "bad_lattice.json: options.placement.latticeOrientation: .*expected axes, short, long or auto, got 'diagonal'"
                  mesh ${_hdir}/bad_lattice.json -o ${_hdir}/bad_lattice.mesh)
ablmg_hostile_config(lattice_number "{\"domain\": {\"rectangle\": [0,0,1,1]}, \"metric\": {\"h\": \"0.1\"}, \"options\": {\"placement\": {\"latticeOrientation\": 2}}}")
ablmg_cli_failure(config_lattice_number "lattice_number.json: options.placement.latticeOrientation: expected string, got number"
                  mesh ${_hdir}/lattice_number.json -o ${_hdir}/lattice_number.mesh)
ablmg_hostile_config(bad_improve "{\"domain\": {\"rectangle\": [0,0,1,1]}, \"metric\": {\"h\": \"0.1\"}, \"options\": {\"improve\": {\"qThreshold\": 1.5}}}")
ablmg_cli_failure(config_bad_improve "bad_improve.json: options.improve: improve options: qThreshold must be in \\(0, 1\\], got 1.5"
                  mesh ${_hdir}/bad_improve.json -o ${_hdir}/bad_improve.mesh)
# Placement options are validated when the config is read, naming the file and the key.
foreach(bad "k0;0;> 0" "threads;-1;>= 0" "tolerance;-1e-3;>= 0" "defectShake;0.7;in \\[0, 0.5\\]")
  list(GET bad 0 _key)
  list(GET bad 1 _val)
  list(GET bad 2 _rule)
  ablmg_hostile_config(bad_${_key} "{\"domain\": {\"rectangle\": [0,0,1,1]}, \"metric\": {\"h\": \"0.1\"}, \"options\": {\"placement\": {\"${_key}\": ${_val}}}}")
  ablmg_cli_failure(config_bad_placement_${_key} "bad_${_key}.json: options.placement: placement options: ${_key} must be ${_rule}"
                    mesh ${_hdir}/bad_${_key}.json -o ${_hdir}/bad_${_key}.mesh)
endforeach()
ablmg_cli_failure(hostile_max_nodes "more than maxNodes = 1000" mesh ${_hdir}/tiny.json --max-nodes 1000 -o ${_hdir}/tiny_max_nodes.mesh)
ablmg_hostile_config(selfx "{\"domain\": {\"loops\": [[[0,0],[1,1],[1,0],[0,1]]]}, \"metric\": {\"h\": \"0.1\"}}")
ablmg_cli_failure(hostile_self_intersecting "selfx.json: domain.loops: .*self-intersecting or touching boundary" mesh ${_hdir}/selfx.json -o ${_hdir}/selfx.mesh)
ablmg_hostile_config(touching "{\"domain\": {\"loops\": [[[0,0],[2,0],[2,2],[0,2]], [[1,0],[1.5,0.5],[0.5,0.5]]]}, \"metric\": {\"h\": \"0.1\"}}")
ablmg_cli_failure(hostile_touching_hole "touching.json: domain.loops: .*(intersect|touch)" mesh ${_hdir}/touching.json -o ${_hdir}/touching.mesh)
ablmg_hostile_config(dup "{\"domain\": {\"loops\": [[[0,0],[1,0],[1,0],[1,1],[0,1]]]}, \"metric\": {\"h\": \"0.1\"}}")
ablmg_cli_failure(hostile_duplicate_vertex "dup.json: domain.loops: .*zero length" mesh ${_hdir}/dup.json -o ${_hdir}/dup.mesh)
ablmg_hostile_config(nan "{\"domain\": {\"rectangle\": [0,0,1,1]}, \"metric\": {\"h\": \"sqrt(x-0.5)\"}}")
ablmg_cli_failure(hostile_nan_metric "nan.json: metric at .*non-finite" mesh ${_hdir}/nan.json -o ${_hdir}/nan.mesh)
ablmg_hostile_config(nonspd "{\"domain\": {\"rectangle\": [0,0,1,1]}, \"metric\": {\"m11\": \"1\", \"m12\": \"2\", \"m22\": \"1\"}}")
ablmg_cli_failure(hostile_non_spd_metric "nonspd.json: metric.*positive definite" mesh ${_hdir}/nonspd.json -o ${_hdir}/nonspd.mesh)
ablmg_hostile_config(infcoord "{\"domain\": {\"rectangle\": [0,0,1e400,1]}, \"metric\": {\"h\": \"0.1\"}}")
ablmg_cli_failure(hostile_inf_coordinate "infcoord.json" mesh ${_hdir}/infcoord.json -o ${_hdir}/infcoord.mesh)
file(WRITE ${_hdir}/empty.json "")
ablmg_cli_failure(hostile_empty_config "empty.json" mesh ${_hdir}/empty.json -o ${_hdir}/empty.mesh)
# Corners closer than the metric size: a valid mesh and a note pointing to "smooth".
ablmg_hostile_config(crowded "{\"domain\": {\"loops\": [[[0,0],[1,0],[1,1],[0,1]], [[0.5,0.5],[0.52,0.5],[0.52,0.52],[0.5,0.52]]]}, \"metric\": {\"h\": \"0.1\"}}")
add_test(NAME cli.mesh_crowded_corners_note COMMAND ablmg mesh ${_hdir}/crowded.json -o ${_hdir}/crowded.mesh)
set_tests_properties(cli.mesh_crowded_corners_note PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "note: loop 1 has 4 of 4 segments shorter than half the metric size.*\"smooth\": true")
# A size that changes by more than itself within one element: a valid mesh and a note (38.8 %
# of the sides); a size graded by 0.1 per unit: no note.
ablmg_hostile_config(fast_varying "{\"domain\": {\"rectangle\": [0,0,1,1]}, \"metric\": {\"h\": \"0.01 + 0.05*(1 + sin(60*x)*sin(60*y))\"}}")
add_test(NAME cli.mesh_fast_varying_metric_note COMMAND ablmg mesh ${_hdir}/fast_varying.json -o ${_hdir}/fast_varying.mesh)
set_tests_properties(cli.mesh_fast_varying_metric_note PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "triangles in.*note: on [0-9.]+ % of the triangles' sides the metric length")
ablmg_hostile_config(graded "{\"domain\": {\"rectangle\": [0,0,1,1]}, \"metric\": {\"h\": \"0.02 + 0.1*x\"}}")
add_test(NAME cli.mesh_graded_metric_no_note COMMAND ablmg mesh ${_hdir}/graded.json -o ${_hdir}/graded.mesh)
set_tests_properties(cli.mesh_graded_metric_no_note PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "triangles in"
                     FAIL_REGULAR_EXPRESSION "note:")
# Valid meshes: a size a million times the domain (2 triangles), anisotropy 1e5.
ablmg_hostile_config(huge "{\"domain\": {\"rectangle\": [0,0,1,1]}, \"metric\": {\"h\": \"1e6\"}}")
add_test(NAME cli.hostile_huge_size COMMAND ablmg mesh ${_hdir}/huge.json -o ${_hdir}/huge.mesh)
set_tests_properties(cli.hostile_huge_size PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "4 vertices, 2 triangles")
ablmg_hostile_config(aniso "{\"domain\": {\"rectangle\": [0,0,1,1]}, \"metric\": {\"h1\": \"100\", \"h2\": \"1e-3\", \"theta\": \"0.3\"}}")
add_test(NAME cli.hostile_anisotropy_1e5 COMMAND ablmg mesh ${_hdir}/aniso.json -o ${_hdir}/aniso.mesh)
set_tests_properties(cli.hostile_anisotropy_1e5 PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "triangles in" TIMEOUT 300)
# Near-singular SPD tensors: det/trace² ≈ 2.5e-9 (sizes 0.007 and 100) and ≈ 2.5e-14 (the
# long size far beyond the domain): valid meshes.
ablmg_hostile_config(near_singular "{\"domain\": {\"rectangle\": [0,0,1,1]}, \"metric\": {\"m11\": \"1e4\", \"m12\": \"0.99999999e4\", \"m22\": \"1e4\"}}")
add_test(NAME cli.hostile_near_singular_metric COMMAND ablmg mesh ${_hdir}/near_singular.json -o ${_hdir}/near_singular.mesh)
set_tests_properties(cli.hostile_near_singular_metric PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "[0-9]+ vertices, [0-9]+ triangles in" TIMEOUT 120)
ablmg_hostile_config(nearer_singular "{\"domain\": {\"rectangle\": [0,0,1,1]}, \"metric\": {\"m11\": \"1\", \"m12\": \"0.9999999999999\", \"m22\": \"1\"}}")
add_test(NAME cli.hostile_nearer_singular_metric COMMAND ablmg mesh ${_hdir}/nearer_singular.json -o ${_hdir}/nearer_singular.mesh)
set_tests_properties(cli.hostile_nearer_singular_metric PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "4 vertices, 2 triangles in" TIMEOUT 120)
# A metric whose long size jumps 16x every 0.075 along a 2e-4-thin layer pushes two boundary
# nodes into the same corner in one step; they must not land on the same point. A valid mesh
# (most of it repaired: the metric is far from smooth).
ablmg_hostile_config(corner_push "{\"domain\": {\"rectangle\": [0,0,1,1]}, \"metric\": {\"h1\": \"0.1*4^sin(2*pi*x/0.15)\", \"h2\": \"2e-4+0.05*abs(y-0.5)\", \"theta\": \"0\"}}")
add_test(NAME cli.hostile_boundary_nodes_pushed_into_a_corner COMMAND ablmg mesh ${_hdir}/corner_push.json -o ${_hdir}/corner_push.mesh)
set_tests_properties(cli.hostile_boundary_nodes_pushed_into_a_corner PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "[0-9]+ vertices, [0-9]+ triangles in" TIMEOUT 300)
# Sizes graded to 1e-7 at a corner (the reentrant corner of an L, and a convex one): the
# first boundary nodes of each edge lie within 1e-4 of the length of the edge from the corner.
# Each must keep its own point (the adaptive L-shape under --p inf reaches 1e-4 there).
ablmg_hostile_config(graded_corner "{\"domain\": {\"rectangle\": [0,0,1,1]}, \"metric\": {\"h\": \"1e-7+0.2*sqrt(x^2+y^2)\"}}")
add_test(NAME cli.hostile_sizes_graded_to_1e-7_at_a_corner COMMAND ablmg mesh ${_hdir}/graded_corner.json -o ${_hdir}/graded_corner.mesh)
set_tests_properties(cli.hostile_sizes_graded_to_1e-7_at_a_corner PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "[0-9]+ vertices, [0-9]+ triangles in" TIMEOUT 120)
ablmg_hostile_config(graded_reentrant "{\"domain\": {\"loops\": [[[-1,-1],[0,-1],[0,0],[1,0],[1,1],[-1,1]]]}, \"metric\": {\"h\": \"1e-7+0.2*sqrt(x^2+y^2)\"}}")
add_test(NAME cli.hostile_sizes_graded_to_1e-7_at_a_reentrant_corner COMMAND ablmg mesh ${_hdir}/graded_reentrant.json -o ${_hdir}/graded_reentrant.mesh)
set_tests_properties(cli.hostile_sizes_graded_to_1e-7_at_a_reentrant_corner PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "[0-9]+ vertices, [0-9]+ triangles in" TIMEOUT 120)
# Non-finite values in a .sol (NaN, ±Inf, overflow), tensor and scalar: one error line naming file:line.
foreach(v nan inf -inf 1e400)
  string(MAKE_C_IDENTIFIER "${v}" _id)
  file(WRITE ${_hdir}/sol_${_id}.sol "MeshVersionFormatted 2\nDimension 2\nSolAtVertices\n5\n1 3\n${v} 0 1\n1 0 1\n1 0 1\n1 0 1\n1 0 1\nEnd\n")
  ablmg_cli_failure(hostile_sol_${_id} "sol_${_id}.sol:6: tensor entry is not finite: '${v}'"
                    remesh -in ${PROJECT_SOURCE_DIR}/tests/data/square.mesh -sol ${_hdir}/sol_${_id}.sol -out ${_hdir}/sol_${_id}.mesh)
endforeach()
file(WRITE ${_hdir}/sol_size_nan.sol "MeshVersionFormatted 2\nDimension 2\nSolAtVertices\n5\n1 1\n1\n1\nnan\n1\n1\nEnd\n")
ablmg_cli_failure(hostile_sol_size_nan "sol_size_nan.sol:8: size value is not finite: 'nan'"
                  remesh -in ${PROJECT_SOURCE_DIR}/tests/data/square.mesh -sol ${_hdir}/sol_size_nan.sol -out ${_hdir}/sol_size_nan.mesh)

# Determinism: same config, 1 or 2 threads → byte-identical .mesh and .sol.
ablmg_hostile_config(determinism "{\"domain\": {\"loops\": [[[0,0],[2,0],[2,1],[1,1.5],[0,1]], [[0.5,0.3],[0.8,0.3],[0.7,0.6]]]}, \"metric\": {\"h1\": \"0.05+0.1*x\", \"h2\": \"0.03\", \"theta\": \"y\"}}")
add_test(NAME cli.mesh_deterministic_across_threads
         COMMAND ${CMAKE_COMMAND} -DABLMG=$<TARGET_FILE:ablmg> -DCONFIG=${_hdir}/determinism.json -DOUT=${_hdir}/determinism
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/check_identical.cmake.in)
set_tests_properties(cli.mesh_deterministic_across_threads PROPERTIES LABELS cli)

# A run killed mid-way leaves the previous outputs intact and no temporary file.
ablmg_hostile_config(kill_small "{\"domain\": {\"rectangle\": [0,0,1,1]}, \"metric\": {\"h\": \"0.1\"}}")
ablmg_hostile_config(kill_large "{\"domain\": {\"rectangle\": [0,0,1,1]}, \"metric\": {\"h\": \"0.0007\"}}")
add_test(NAME cli.mesh_killed_run_leaves_outputs_intact
         COMMAND ${CMAKE_COMMAND} -DABLMG=$<TARGET_FILE:ablmg> -DSMALL=${_hdir}/kill_small.json
                 -DLARGE=${_hdir}/kill_large.json -DOUT=${_hdir}/killed -DKILL_AFTER=1
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/check_killed.cmake.in)
set_tests_properties(cli.mesh_killed_run_leaves_outputs_intact PROPERTIES LABELS cli)
# Hostile medit inputs to `ablmg remesh` in the sections read for subdomains and features.
set(_sq "MeshVersionFormatted 2\nDimension 2\nVertices\n5\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n0.5 0.5 0\n")
set(_tri "Triangles\n4\n1 2 5 1\n2 3 5 1\n3 4 5 1\n4 1 5 1\n")
set(_edges "Edges\n4\n1 2 1\n2 3 2\n3 4 3\n4 1 4\n")
file(WRITE ${_hdir}/req_inside.mesh "${_sq}${_edges}${_tri}RequiredVertices\n1\n5\nEnd\n")
ablmg_cli_failure(hostile_required_vertex_inside "req_inside.mesh: required vertex 5 lies inside a subdomain"
                  remesh -in ${_hdir}/req_inside.mesh -hsiz 0.2 -out ${_hdir}/req_inside.o.mesh)
file(WRITE ${_hdir}/dangling.mesh "${_sq}Edges\n5\n1 2 1\n2 3 2\n3 4 3\n4 1 4\n1 5 9\n${_tri}End\n")
ablmg_cli_failure(hostile_interface_separates_nothing "dangling.mesh: interface edge \\([0-9], [0-9]\\) has the same subdomain on both sides"
                  remesh -in ${_hdir}/dangling.mesh -hsiz 0.2 -out ${_hdir}/dangling.o.mesh)
file(WRITE ${_hdir}/bad_corner.mesh "${_sq}${_edges}${_tri}Corners\n1\n9\nEnd\n")
ablmg_cli_failure(hostile_corner_out_of_range "bad_corner.mesh:[0-9]+: Corners entry 1: index 9 out of range \\[1, 5\\]"
                  remesh -in ${_hdir}/bad_corner.mesh -hsiz 0.2 -out ${_hdir}/bad_corner.o.mesh)
file(WRITE ${_hdir}/bad_ridge.mesh "${_sq}${_edges}${_tri}Ridges\n1\n7\nEnd\n")
ablmg_cli_failure(hostile_ridge_out_of_range "bad_ridge.mesh:[0-9]+: Ridges names edge 7 but Edges has 4"
                  remesh -in ${_hdir}/bad_ridge.mesh -hsiz 0.2 -out ${_hdir}/bad_ridge.o.mesh)
file(WRITE ${_hdir}/lonely_edge.mesh "${_sq}Edges\n1\n1 3 1\nTriangles\n2\n1 2 5 1\n2 3 5 1\nEnd\n")
ablmg_cli_failure(hostile_edge_in_no_triangle "lonely_edge.mesh: edge \\(1, 3\\) of Edges is a side of no triangle"
                  remesh -in ${_hdir}/lonely_edge.mesh -hsiz 0.2 -out ${_hdir}/lonely_edge.o.mesh)
# Boundary-only medit inputs (Edges, no Triangles): loops that cross, an open chain, a branch,
# a corner on no edge; and a good one meshed.
set(_two_sq "MeshVersionFormatted 2\nDimension 2\nVertices\n8\n0 0 0\n2 0 0\n2 2 0\n0 2 0\n1 1 0\n3 1 0\n3 3 0\n1 3 0\n")
file(WRITE ${_hdir}/bo_cross.mesh "${_two_sq}Edges\n8\n1 2 1\n2 3 1\n3 4 1\n4 1 1\n5 6 2\n6 7 2\n7 8 2\n8 5 2\nEnd\n")
ablmg_cli_failure(hostile_boundary_loops_cross "bo_cross.mesh: edges \\([0-9], [0-9]\\) and \\([0-9], [0-9]\\) cross"
                  remesh -in ${_hdir}/bo_cross.mesh -hsiz 0.2 -out ${_hdir}/bo_cross.o.mesh)
file(WRITE ${_hdir}/bo_open.mesh "${_two_sq}Edges\n3\n1 2 1\n2 3 1\n3 4 1\nEnd\n")
ablmg_cli_failure(hostile_boundary_open_chain "bo_open.mesh: open chain of edges: vertex [14] .* is on one edge"
                  remesh -in ${_hdir}/bo_open.mesh -hsiz 0.2 -out ${_hdir}/bo_open.o.mesh)
file(WRITE ${_hdir}/bo_branch.mesh "${_two_sq}Edges\n5\n1 2 1\n2 3 1\n3 4 1\n4 1 1\n1 3 1\nEnd\n")
ablmg_cli_failure(hostile_boundary_branch "bo_branch.mesh: vertex [13] .* is on 3 edges"
                  remesh -in ${_hdir}/bo_branch.mesh -hsiz 0.2 -out ${_hdir}/bo_branch.o.mesh)
file(WRITE ${_hdir}/bo_corner.mesh "${_two_sq}Edges\n4\n1 2 1\n2 3 2\n3 4 3\n4 1 4\nCorners\n1\n7\nEnd\n")
ablmg_cli_failure(hostile_boundary_corner_on_no_edge "bo_corner.mesh: corner 7 is on no edge"
                  remesh -in ${_hdir}/bo_corner.mesh -hsiz 0.2 -out ${_hdir}/bo_corner.o.mesh)
file(WRITE ${_hdir}/bo_good.mesh "${_two_sq}Edges\n4\n1 2 1\n2 3 2\n3 4 3\n4 1 4\nEnd\n")
add_test(NAME cli.remesh_boundary_only COMMAND ablmg remesh -in ${_hdir}/bo_good.mesh -hsiz 0.2 -out ${_hdir}/bo_good.o.mesh)
set_tests_properties(cli.remesh_boundary_only PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "8 -> [0-9]+ vertices")
# Bad refs in medit files: not an integer, out of int range, the remesher's reserved cut ref.
file(WRITE ${_hdir}/ref_float.mesh "${_sq}${_edges}Triangles\n4\n1 2 5 1.5\n2 3 5 1\n3 4 5 1\n4 1 5 1\nEnd\n")
ablmg_cli_failure(hostile_ref_not_integer "ref_float.mesh:[0-9]+: expected reference \\(an integer\\), got '1.5'"
                  remesh -in ${_hdir}/ref_float.mesh -hsiz 0.2 -out ${_hdir}/ref_float.o.mesh)
file(WRITE ${_hdir}/ref_huge.mesh "${_sq}Edges\n4\n1 2 1\n2 3 99999999999\n3 4 3\n4 1 4\n${_tri}End\n")
ablmg_cli_failure(hostile_ref_out_of_range "ref_huge.mesh:[0-9]+: reference 99999999999 is out of range"
                  remesh -in ${_hdir}/ref_huge.mesh -hsiz 0.2 -out ${_hdir}/ref_huge.o.mesh)
file(WRITE ${_hdir}/ref_reserved.mesh "${_sq}Edges\n7\n1 2 1\n2 3 2\n3 4 3\n4 1 4\n1 5 -2147483647\n2 5 8\n4 5 8\nTriangles\n4\n1 2 5 1\n2 3 5 2\n3 4 5 2\n4 1 5 1\nEnd\n")
ablmg_cli_failure(hostile_ref_reserved "ref_reserved.mesh: edge \\([0-9], [0-9]\\) has ref -2147483647, which is reserved"
                  remesh -in ${_hdir}/ref_reserved.mesh -hsiz 0.2 -out ${_hdir}/ref_reserved.o.mesh)
# Tagged regions in an `ablmg mesh` config: a tag of 0, a region leaving the domain, two that cross.
ablmg_hostile_config(region_tag0 "{\"domain\": {\"rectangle\": [0,0,1,1]}, \"regions\": [{\"points\": [[0.2,0.2],[0.8,0.2],[0.5,0.8]], \"tag\": 0}], \"metric\": {\"h\": \"0.1\"}}")
ablmg_cli_failure(config_region_tag0 "region_tag0.json: regions\\[0\\].tag: expected integer >= 1"
                  mesh ${_hdir}/region_tag0.json -o ${_hdir}/region_tag0.mesh)
ablmg_hostile_config(region_outside "{\"domain\": {\"rectangle\": [0,0,1,1]}, \"regions\": [{\"points\": [[0.2,0.2],[1.8,0.2],[0.5,0.8]], \"tag\": 2}], \"metric\": {\"h\": \"0.1\"}}")
ablmg_cli_failure(config_region_outside "region_outside.json: regions\\[0\\]: point 1 \\(1.8, 0.2\\) is not inside the domain"
                  mesh ${_hdir}/region_outside.json -o ${_hdir}/region_outside.mesh)
ablmg_hostile_config(region_cross "{\"domain\": {\"rectangle\": [0,0,1,1]}, \"regions\": [{\"points\": [[0.2,0.2],[0.6,0.2],[0.4,0.6]], \"tag\": 2}, {\"points\": [[0.4,0.1],[0.8,0.1],[0.6,0.5]], \"tag\": 3}], \"metric\": {\"h\": \"0.1\"}}")
ablmg_cli_failure(config_regions_cross "region_cross.json: edges \\([0-9]+, [0-9]+\\) and \\([0-9]+, [0-9]+\\) cross"
                  mesh ${_hdir}/region_cross.json -o ${_hdir}/region_cross.mesh)
ablmg_cli_failure(hostile_bad_met_field "-met-field" remesh -in ${_hdir}/req_inside.mesh -met-field 0 -out ${_hdir}/x.o.mesh)
ablmg_hostile_config(bad_preset "{\"domain\": {\"rectangle\": [0,0,1,1]}, \"metric\": {\"h\": \"0.1\"}, \"options\": {\"preset\": \"fast\"}}")
ablmg_cli_failure(config_bad_preset "bad_preset.json: options.preset: .*expected mesh, remesh or adapt, got 'fast'"
                  mesh ${_hdir}/bad_preset.json -o ${_hdir}/bad_preset.mesh)

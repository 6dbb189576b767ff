# `ablmg surface`: the list of built-ins, small runs that must report a manifold
# mesh and write their files (a built-in, and an expression surface from a config with the
# shaded 3D picture), and failures — a bad surface name, a bad size, a degenerate
# parametrisation, a wrong output extension, an unknown config key — each one error line,
# exit 1, no output left (tests/cli/check_failure.cmake.in).
set(_sdir ${CMAKE_CURRENT_BINARY_DIR}/cli_out/surface)
file(MAKE_DIRECTORY ${_sdir})
add_test(NAME cli.surface_list COMMAND ablmg surface --list)
set_tests_properties(cli.surface_list PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "paper-fig16.*sphere-patch.*torus.*cylinder.*saddle.*torus-closed")
add_test(NAME cli.surface_sphere COMMAND ablmg surface --surface sphere-patch --h 0.2 -o ${_sdir}/sphere.mesh --stl ${_sdir}/sphere.stl --vtu ${_sdir}/sphere.vtu)
set_tests_properties(cli.surface_sphere PROPERTIES LABELS cli ENVIRONMENT OMP_WAIT_POLICY=passive
                     PASS_REGULAR_EXPRESSION "manifold: yes.*-> .*sphere.mesh")

# An expression surface (a bump) from a config; the outputs include the shaded view.
file(WRITE ${_sdir}/bump.json
     "{\"surface\": {\"x\": \"u\", \"y\": \"v\", \"z\": \"0.5*exp(-4*(u^2+v^2))\", \"u\": [-1, 1], \"v\": [-1, 1]},\n \"h\": 0.15}\n")
add_test(NAME cli.surface_config COMMAND ablmg surface ${_sdir}/bump.json -o ${_sdir}/bump.mesh
         --png-3d ${_sdir}/bump_3d.png --png-param ${_sdir}/bump_param.png --json ${_sdir}/bump_report.json)
set_tests_properties(cli.surface_config PROPERTIES LABELS cli ENVIRONMENT OMP_WAIT_POLICY=passive
                     PASS_REGULAR_EXPRESSION "bump, h = 0.15: [0-9]+ vertices.*manifold: yes.*-> .*bump_3d.png.*-> .*bump_report.json")

# A full tube from expressions with "weld": the seam u = 0 / 2π is welded (the summary says how
# many vertices were merged; without the weld it says nothing and the tube has a seam boundary).
file(WRITE ${_sdir}/tube.json
     "{\"surface\": {\"x\": \"cos(u)\", \"y\": \"sin(u)\", \"z\": \"v\", \"u\": [0, 6.283185307179586], \"v\": [0, 2], \"weld\": true}, \"h\": 0.2}\n")
add_test(NAME cli.surface_weld COMMAND ablmg surface ${_sdir}/tube.json -o ${_sdir}/tube.mesh --json ${_sdir}/tube_report.json)
set_tests_properties(cli.surface_weld PROPERTIES LABELS cli ENVIRONMENT OMP_WAIT_POLICY=passive
                     PASS_REGULAR_EXPRESSION "manifold: yes; boundary edges: [0-9]+; seams welded: [1-9][0-9]* vertices merged")
file(WRITE ${_sdir}/bad_weld.json
     "{\"surface\": {\"x\": \"u\", \"y\": \"v\", \"z\": \"0\", \"u\": [0, 1], \"v\": [0, 1], \"weld\": \"yes\"}, \"h\": 0.2}\n")

# A polar parametrisation of the disk: r_v = 0 at u = 0, so the induced metric is singular.
file(WRITE ${_sdir}/polar.json
     "{\"surface\": {\"x\": \"u*cos(v)\", \"y\": \"u*sin(v)\", \"z\": \"0\", \"u\": [0, 1], \"v\": [0, 6]}, \"h\": 0.1}\n")
file(WRITE ${_sdir}/unknown_key.json "{\"surface\": \"torus\", \"h\": 0.1, \"hgrad\": 1.3}\n")
set(_out ${_sdir})  # ablmg_cli_failure checks that ${_out}/<name>.mesh is not left behind
ablmg_cli_failure(surface_unknown_name "unknown built-in 'klein-bottle'" surface --surface klein-bottle --h 0.1 -o ${_sdir}/surface_unknown_name.mesh)
ablmg_cli_failure(surface_bad_h "--h: expected a positive number" surface --surface torus --h -1 -o ${_sdir}/surface_bad_h.mesh)
ablmg_cli_failure(surface_degenerate "rank-deficient at \\(u, v\\)" surface ${_sdir}/polar.json -o ${_sdir}/surface_degenerate.mesh)
ablmg_cli_failure(surface_bad_weld "bad_weld.json: surface.weld: expected true or false" surface ${_sdir}/bad_weld.json -o ${_sdir}/surface_bad_weld.mesh)
ablmg_cli_failure(surface_bad_extension "--png-3d .*must end in .png" surface --surface torus --h 0.1 -o ${_sdir}/surface_bad_extension.mesh --png-3d ${_sdir}/x.jpg)
ablmg_cli_failure(surface_unknown_key "unknown_key.json: unknown key 'hgrad'" surface ${_sdir}/unknown_key.json -o ${_sdir}/surface_unknown_key.mesh)

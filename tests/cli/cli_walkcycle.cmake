# legwork walkcycle: the shipped walks straight, along paths, pictures and reports; bad input fails.
set(W ${PROJECT_SOURCE_DIR}/data/walks)
legwork_cli_test(walkcycle_help walkcycle --help)
legwork_cli_test(walkcycle_cycle walkcycle --keys ${W}/normal.json --out ${O}/wc_cycle.bvh)
legwork_cli_test(walkcycle_straight walkcycle --keys ${W}/normal.json --straight 6 --out ${O}/wc_normal.glb
                 --sheet ${O}/wc_normal_sheet.png --arc LeftHand,LeftToeBase --report ${O}/wc_normal.json --top ${O}/wc_normal_top.svg)
legwork_cli_test(walkcycle_path walkcycle --keys ${W}/sneak.json --path ${W}/paths/quarter-turn.json --out ${O}/wc_sneak.bvh --fps 30
                 --report ${O}/wc_sneak.json)
legwork_cli_test(walkcycle_svg walkcycle --keys ${W}/double-bounce.json --svg-path "M 0 0 C 0 2 2 2 2 4" --out ${O}/wc_db.bvh
                 --shift LeftShoulder=0,LeftArm=1,LeftForeArm=2 --frames 32)
legwork_cli_test(walkcycle_steps walkcycle --keys ${W}/normal.json --steps 4 --out ${O}/wc_steps.bvh)
legwork_cli_test(walkcycle_from_bvh walkcycle --from-bvh ${D}/walking/07_01.bvh --keys 53,60,100,101 --frames 24 --out ${O}/wc_from_bvh.bvh
                 --straight 3)
legwork_cli_test(walkcycle_extract walkcycle extract ${D}/walking/16_15.bvh --out ${O}/wc_16_15.json --report ${O}/wc_16_15_report.json)
# Bad input fails with its message.
legwork_cli_error(walkcycle_no_keys "error: walkcycle: --keys walk.json is required" walkcycle --straight 3 --out ${O}/x.bvh)
legwork_cli_error(walkcycle_bad_joint "error: --shift: unknown joint 'NoSuchJoint'"
                   walkcycle --keys ${W}/normal.json --shift NoSuchJoint=1 --out ${O}/x.bvh)
legwork_cli_error(walkcycle_bad_ext "error: --out '[^']*x.txt' must end in .bvh or .glb" walkcycle --keys ${W}/normal.json --out ${O}/x.txt)
legwork_cli_error(walkcycle_bad_path "error: --svg-path: svg path: flattened points: point 1 repeats point 0"
                   walkcycle --keys ${W}/normal.json --svg-path "M 0 0 L 0 0" --out ${O}/x.bvh)
legwork_cli_error(walkcycle_not_json "error: [^ ]*walking/07_01.bvh: not valid JSON" walkcycle --keys ${D}/walking/07_01.bvh --out ${O}/x.bvh)
legwork_cli_error(walkcycle_extract_not_walk "error: extract: found 0 steady steps"
                   walkcycle extract ${PROJECT_SOURCE_DIR}/data/cmu/bvh/swimming/79_02.bvh --out ${O}/x.json)
# Same input, same bytes: two runs of a curved walk (BVH and report) compared.
foreach(run a b)
  legwork_cli_test(walkcycle_repro_${run} walkcycle --keys ${W}/double-bounce.json --path ${W}/paths/s-curve.json
                   --out ${O}/wc_repro_${run}.bvh --report ${O}/wc_repro_${run}.json)
  set_tests_properties(cli.walkcycle_repro_${run} PROPERTIES FIXTURES_SETUP wc_repro)
endforeach()
add_test(NAME cli.walkcycle_repro_same_bvh COMMAND ${CMAKE_COMMAND} -E compare_files ${O}/wc_repro_a.bvh ${O}/wc_repro_b.bvh)
add_test(NAME cli.walkcycle_repro_same_report COMMAND ${CMAKE_COMMAND} -E compare_files ${O}/wc_repro_a.json ${O}/wc_repro_b.json)
set_tests_properties(cli.walkcycle_repro_same_bvh cli.walkcycle_repro_same_report PROPERTIES FIXTURES_REQUIRED wc_repro)
# Option ranges (issue 14): named option, range, no silent fallback.
legwork_cli_error(walkcycle_steps_zero "--steps: Value 0 not in range 1 to 100000" walkcycle --keys ${W}/normal.json --steps 0 --out ${O}/x.bvh)
legwork_cli_error(walkcycle_frames_negative "error: --frames -2: expected an even number of frames per cycle from 8 to 10000"
                  walkcycle --keys ${W}/normal.json --frames -2 --out ${O}/x.bvh)
legwork_cli_error(walkcycle_frames_zero "error: --frames 0: expected an even number of frames per cycle from 8 to 10000"
                  walkcycle --keys ${W}/normal.json --frames 0 --out ${O}/x.bvh)
# A run is not a walk: extract says so (the keys are still written).
legwork_cli_error(walkcycle_extract_run "warning: [^ ]*09_01.bvh: this does not look like a walk: both feet are off the floor in [0-9]+ %"
                  walkcycle extract ${PROJECT_SOURCE_DIR}/data/cmu/bvh/running/09_01.bvh --out ${O}/wc_run.json)
# What the walk reports is true: --steps 5 gives 5 steps and the length walked (not a 1000 km placeholder);
# --straight 0.3 walks 0.3 m; walks end on the path's end facing along it (printed as in the --report).
legwork_cli_error(walkcycle_report_steps "walk: 5 steps, [0-9]+ frames at 24 fps \\([0-9.]+ ms\\), path [2-4]\\.[0-9][0-9] m"
                  walkcycle --keys ${W}/normal.json --steps 5 --report ${O}/wc_steps5.json)
legwork_cli_error(walkcycle_report_short "path 0\\.30 m, .*end 0\\.0[0-4][0-9] m from the path's end, facing -?[01]\\.[0-9] deg off its end tangent; travelled 0\\.[23][0-9][0-9] m"
                  walkcycle --keys ${W}/normal.json --straight 0.3 --report ${O}/wc_short.json)
legwork_cli_error(walkcycle_report_curve "end 0\\.0[0-4][0-9] m from the path's end, facing -?[01]\\.[0-9] deg off its end tangent"
                  walkcycle --keys ${W}/sneak.json --path ${W}/paths/s-curve.json --report ${O}/wc_scurve.json)
# Root motion (issue 14, item 1): smooth by default, document 001's pivoting root on request; both printed.
legwork_cli_error(walkcycle_root_smooth "root: smooth \\(legs by IK\\), speed [0-9.]+-1\\.[34][0-9] m/s \\(mean 1\\.[34][0-9]\\), peak acceleration [0-9]\\.[0-9] m/s\\^2"
                  walkcycle --keys ${W}/normal.json --steps 10 --report ${O}/wc_root_smooth.json)
legwork_cli_error(walkcycle_root_pivot "root: pivoting \\(document 001\\), speed 0\\.[0-9]+-[23]\\.[0-9]+ m/s \\(mean [0-9.]+\\), peak acceleration [1-9][0-9]\\.[0-9] m/s\\^2"
                  walkcycle --keys ${W}/normal.json --steps 10 --root pivot --report ${O}/wc_root_pivot.json)
legwork_cli_error(walkcycle_root_bad "--root: bogus not in \\{smooth,pivot\\}" walkcycle --keys ${W}/normal.json --steps 3 --root bogus --out ${O}/x.bvh)
# Uneven ground (issue 14, item 3): the hill's height field is named in the report, no foot goes below it;
# the pivoting root is refused on it.
legwork_cli_error(walkcycle_ground_hill "ground: height field 5 x 20, 0\\.50 m cells, 0\\.000-0\\.300 m; feet at most 0\\.00 mm below it"
                  walkcycle --keys ${W}/normal.json --path ${W}/paths/hill.json --report ${O}/wc_hill.json)
legwork_cli_error(walkcycle_ground_pivot "error: walk: uneven ground \\(slope 12\\.0 % over 4\\.00 m\\) needs the smooth root"
                  walkcycle --keys ${W}/normal.json --path ${W}/paths/ramp.json --root pivot --out ${O}/x.bvh)
legwork_cli_error(walkcycle_ground_stairs "ground: stairs up, 5 steps of 0\\.150 m rise, 0\\.360 m run; feet at most 0\\.00 mm below it"
                  walkcycle --keys ${W}/normal.json --path ${W}/paths/stairs.json --report ${O}/wc_stairs.json)
legwork_cli_error(walkcycle_stance_turn "stance foot \\(heel / ball down within 5 mm of the ground\\): heel slips up to 0\\.[0-9]+ mm, ball 0\\.[0-9]+ mm; a flat foot twists up to 0\\.00 deg"
                  walkcycle --keys ${W}/normal.json --path ${W}/paths/quarter-turn.json --report ${O}/wc_turn.json)
legwork_cli_error(walkcycle_stance_turn_bad "--stance-turn: nope not in \\{ball,twist\\}"
                  walkcycle --keys ${W}/normal.json --path ${W}/paths/quarter-turn.json --stance-turn nope --out ${O}/x.bvh)
# A walk is made in memory: one longer than the frame limit is refused before any work, naming the option.
legwork_cli_error(walkcycle_steps_over_frame_limit
                  "error: --steps 100000 makes a walk of about 1200036 frames at 24 fps; the limit is 500000 frames"
                  walkcycle --keys ${W}/normal.json --steps 100000 --out ${O}/x.bvh)

# legwork wip / wip eval smoke tests (outputs in ${O}, sample data in ${D}).
legwork_cli_test(wip_help wip --help)
legwork_cli_test(wip_synthetic wip --synthetic --duration 12 --out ${O}/wip_synthetic.glb --csv ${O}/wip_synthetic.csv
                 --plot ${O}/wip_synthetic.png --tracker-out ${O}/wip_synthetic_tracker.csv)
legwork_cli_test(wip_bvh wip --input ${D}/walking/16_15.bvh --out ${O}/wip_16_15.bvh --plot ${O}/wip_16_15.png)
legwork_cli_test(wip_keyframe wip --input ${D}/walking/07_02.bvh --out ${O}/wip_07_02_keyframe.glb --baseline keyframe
                 --avatar ${D}/walking/07_01.bvh)
legwork_cli_test(wip_eval wip eval --data ${D}/walking --out ${O}/wip_eval --limit 3)
legwork_cli_test(wip_frequency wip --synthetic --duration 8 --speed-model frequency --rate 90 --out ${O}/wip_90hz.bvh)
# The synthetic tracker CSV written above, read back (runs after wip_synthetic).
legwork_cli_test(wip_csv wip --input ${O}/wip_synthetic_tracker.csv --out ${O}/wip_from_csv.bvh)
set_tests_properties(cli.wip_csv PROPERTIES DEPENDS cli.wip_synthetic)
# Bad input.
legwork_cli_fail(wip_no_input wip --out ${O}/x.glb)
legwork_cli_fail(wip_bad_out wip --synthetic --out ${O}/x.txt)
legwork_cli_fail(wip_not_still wip --synthetic --duration 6 --stand-time 0.5 --calibrate on --out ${O}/x.glb)
legwork_cli_fail(wip_csv_missing_columns wip --input ${PROJECT_SOURCE_DIR}/tests/wip/data/no_ankles.csv --out ${O}/x.bvh)
legwork_cli_fail(wip_csv_time_backwards wip --input ${PROJECT_SOURCE_DIR}/tests/wip/data/time_backwards.csv --out ${O}/x.bvh)
legwork_cli_fail(wip_avatar_without_legs wip --synthetic --avatar ${PROJECT_SOURCE_DIR}/tests/wip/data/no_legs.bvh --out ${O}/x.bvh)
legwork_cli_fail(wip_eval_no_data wip eval --data ${O}/does-not-exist --out ${O}/wip_eval_x)
# Run from the repository root, as a user would: the default avatar and walk
# cycle (data/cmu/bvh/walking/07_01.bvh) are found from there.
set_tests_properties(cli.wip_help cli.wip_synthetic cli.wip_bvh cli.wip_keyframe cli.wip_eval cli.wip_frequency
                     cli.wip_csv cli.wip_no_input cli.wip_bad_out cli.wip_not_still cli.wip_csv_missing_columns
                     cli.wip_csv_time_backwards cli.wip_avatar_without_legs cli.wip_eval_no_data
                     PROPERTIES WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})

# legwork accent: build a database from the sample data, accentuate a held-out trial, speed figures; bad input fails with its message.
set(ACC_DB ${O}/accent_sample.lwdb)
legwork_cli_test(accent_build accent build --data ${PROJECT_SOURCE_DIR}/data/cmu --exclude bvh/walking/07_02.bvh
                 --out ${ACC_DB} --json ${O}/accent_build.json)
set_tests_properties(cli.accent_build PROPERTIES FIXTURES_SETUP accent_db)
legwork_cli_test(accent_build_classes accent build --data ${PROJECT_SOURCE_DIR}/data/cmu --classes boxing,walking --mirror
                 --hop 2 --speeds 4 --out ${O}/accent_box_walk.lwdb)
legwork_cli_test(accent_run accent run --db ${ACC_DB} --input ${D}/walking/07_02.bvh --drop-first
                 --out ${O}/accent_07_02.bvh --json ${O}/accent_07_02.json --compare-ik
                 --save-session ${O}/accent_07_02_session.csv)
set_tests_properties(cli.accent_run PROPERTIES FIXTURES_SETUP accent_session)
legwork_cli_test(accent_run_csv accent run --db ${ACC_DB} --input ${O}/accent_07_02_session.csv --height 1.7
                 --out ${O}/accent_07_02_from_csv.bvh)
set_tests_properties(cli.accent_run_csv PROPERTIES FIXTURES_REQUIRED "accent_db;accent_session")
legwork_cli_test(accent_run_glb_exact accent run --db ${ACC_DB} --input ${D}/walking/07_02.bvh --drop-first
                 --out ${O}/accent_07_02.glb --mode exact --k 3 --no-align --no-smooth --exaggerate 1.3)
legwork_cli_test(accent_run_target accent run --db ${ACC_DB} --input ${D}/walking/07_02.bvh --drop-first
                 --out ${O}/accent_07_02_daz.bvh --target ${PROJECT_SOURCE_DIR}/data/cmu/bvh_daz/climbing_ladder/14_33.bvh)
set_tests_properties(cli.accent_run cli.accent_run_glb_exact cli.accent_run_target PROPERTIES FIXTURES_REQUIRED accent_db)
# Every runtime setting of the engine is an option: the released feet's lift (accent::Settings::foot_lift_height).
legwork_cli_test(accent_run_foot_lift accent run --db ${ACC_DB} --input ${D}/walking/07_02.bvh --drop-first
                 --foot-lift-height 0.08 --out ${O}/accent_07_02_lift.bvh)
legwork_cli_error(accent_run_foot_slack_range "--foot-lock-slack: Value 2 not in range 0\\.0+ to 1\\.0*"
                 accent run --db ${ACC_DB} --input ${D}/walking/07_02.bvh --foot-lock-slack 2 --out ${O}/x.bvh)
legwork_cli_error(accent_run_foot_hold_range "--foot-lock-hold: Value 11 not in range 0\\.0+ to 10\\.0*"
                 accent run --db ${ACC_DB} --input ${D}/walking/07_02.bvh --foot-lock-hold 11 --out ${O}/x.bvh)
legwork_cli_error(accent_run_swing_speed_range "--foot-swing-speed: Value -1 not in range 0\\.0+ to 10\\.0*"
                 accent run --db ${ACC_DB} --input ${D}/walking/07_02.bvh --foot-swing-speed -1 --out ${O}/x.bvh)
legwork_cli_error(accent_run_travel_weight_range "--travel-weight: Value -1 not in range 0\\.0+ to 100\\.0*"
                 accent run --db ${ACC_DB} --input ${D}/walking/07_02.bvh --travel-weight -1 --out ${O}/x.bvh)
legwork_cli_error(accent_run_foot_lift_range "--foot-lift-height: Value 0.9 not in range 0\\.0+ to 0\\.50*"
                 accent run --db ${ACC_DB} --input ${D}/walking/07_02.bvh --foot-lift-height 0.9 --out ${O}/x.bvh)
legwork_cli_error(accent_run_head_height_range "--max-head-height-diff: Value 3 not in range 0\\.0+ to 2\\.0*"
                 accent run --db ${ACC_DB} --input ${D}/walking/07_02.bvh --max-head-height-diff 3 --out ${O}/x.bvh)
legwork_cli_error(accent_run_lying_root_range "--lying-root-smoothing: Value 0.5 not in range 1\\.0+ to 20\\.0*"
                 accent run --db ${ACC_DB} --input ${D}/walking/07_02.bvh --lying-root-smoothing 0.5 --out ${O}/x.bvh)
legwork_cli_error(accent_run_feedforward_range "--smooth-feedforward: Value 2 not in range 0\\.0+ to 1\\.0*"
                 accent run --db ${ACC_DB} --input ${D}/walking/07_02.bvh --smooth-feedforward 2 --out ${O}/x.bvh)
# Other classes at a cost (no class given): 0, or a factor of at least 1.
legwork_cli_error(accent_run_other_class_cost_range "--other-class-cost: Value 0.5 must be 0 \\(off\\) or a factor from 1 to 1000000"
                 accent run --db ${ACC_DB} --input ${D}/walking/07_02.bvh --other-class-cost 0.5 --out ${O}/x.bvh)
legwork_cli_test(accent_run_other_class_cost accent run --db ${ACC_DB} --input ${D}/walking/07_02.bvh --drop-first
                 --other-class-cost 1 --out ${O}/accent_07_02_other_classes.bvh)
set_tests_properties(cli.accent_run_other_class_cost cli.accent_run_other_class_cost_range PROPERTIES FIXTURES_REQUIRED accent_db)
set_tests_properties(cli.accent_run_foot_lift cli.accent_run_foot_lift_range cli.accent_run_foot_slack_range cli.accent_run_swing_speed_range cli.accent_run_travel_weight_range cli.accent_run_head_height_range cli.accent_run_feedforward_range cli.accent_run_lying_root_range
                     PROPERTIES FIXTURES_REQUIRED accent_db)
# accent_speed: the figures program of bench/ (built with the tests too).
add_test(NAME cli.accent_speed COMMAND accent_speed --db ${ACC_DB} --input ${D}/walking/07_02.bvh --drop-first --repeat 1
         --json ${O}/accent_speed.json)
set_tests_properties(cli.accent_speed PROPERTIES FIXTURES_REQUIRED accent_db)
# --modes / --no-recall: only the fast path is timed (what a profiler is pointed at).
add_test(NAME cli.accent_speed_fast_only COMMAND accent_speed --db ${ACC_DB} --input ${D}/walking/07_02.bvh --drop-first --repeat 1
         --modes fast --no-recall)
set_tests_properties(cli.accent_speed_fast_only PROPERTIES FIXTURES_REQUIRED accent_db
                     PASS_REGULAR_EXPRESSION "fast +wall: mean" FAIL_REGULAR_EXPRESSION "brute|exact +wall|recall@")
# --avatars: several avatars, each its own state, timed round robin (a server's sessions).
add_test(NAME cli.accent_speed_avatars COMMAND accent_speed --db ${ACC_DB} --input ${D}/walking/07_02.bvh --drop-first --repeat 1
         --modes fast --no-recall --avatars 3)
set_tests_properties(cli.accent_speed_avatars PROPERTIES FIXTURES_REQUIRED accent_db
                     PASS_REGULAR_EXPRESSION "fast +wall: mean .*, 3 avatars round robin")
add_test(NAME cli.accent_speed_bad_avatars COMMAND accent_speed --db ${ACC_DB} --input ${D}/walking/07_02.bvh --avatars 0)
set_tests_properties(cli.accent_speed_bad_avatars PROPERTIES FIXTURES_REQUIRED accent_db
                     PASS_REGULAR_EXPRESSION "--avatars: Value 0 not in range 1 to 5000" FAIL_REGULAR_EXPRESSION "database:")
add_test(NAME cli.accent_speed_bad_mode COMMAND accent_speed --db ${ACC_DB} --input ${D}/walking/07_02.bvh --modes fast,quick)
set_tests_properties(cli.accent_speed_bad_mode PROPERTIES FIXTURES_REQUIRED accent_db
                     PASS_REGULAR_EXPRESSION "error: --modes: unknown search mode 'quick' \\(expected brute, exact or fast\\)"
                     FAIL_REGULAR_EXPRESSION "database:")
legwork_cli_error(accent_build_unknown_class "error: .*no class 'dancing' \\(classes present: basketball, boxing" accent build --data ${PROJECT_SOURCE_DIR}/data/cmu --classes dancing
                 --out ${O}/x.lwdb)
legwork_cli_error(accent_build_bad_ext "error: --out '.*x.db' must end in .lwdb" accent build --data ${PROJECT_SOURCE_DIR}/data/cmu --out ${O}/x.db)
legwork_cli_error(accent_build_all_filtered "error: accent build: no windows: every trial was dropped" accent build --data ${PROJECT_SOURCE_DIR}/data/cmu --classes walking
                 --correlation 1.5 --out ${O}/x.lwdb)
legwork_cli_error(accent_run_not_a_db "error: accent database '.*MANIFEST.tsv': not a legwork accent database \\(bad magic\\)" accent run --db ${PROJECT_SOURCE_DIR}/data/cmu/MANIFEST.tsv
                 --input ${D}/walking/07_02.bvh --out ${O}/x.bvh)
legwork_cli_error(accent_run_unknown_class "error: accent: class 'dancing' is not in the database \\(it has: " accent run --db ${ACC_DB} --input ${D}/walking/07_02.bvh --classes dancing
                 --out ${O}/x.bvh)
set_tests_properties(cli.accent_run_unknown_class PROPERTIES FIXTURES_REQUIRED accent_db)
# Bad options name the option and what was expected; silent nonsense is an error or a warning.
legwork_cli_error(accent_build_bad_weights "error: --weights 'a,b,c': 'a' is not a number; expected position,velocity,acceleration weights such as 1,1,0.5"
                 accent build --data ${PROJECT_SOURCE_DIR}/data/cmu --weights a,b,c --out ${O}/x.lwdb)
legwork_cli_error(accent_build_exclude_nothing "error: exclude 'nothere.bvh' matches no trial of '.*data/cmu' \\(name a file as in the manifest"
                 accent build --data ${PROJECT_SOURCE_DIR}/data/cmu --exclude nothere.bvh --out ${O}/x.lwdb)
legwork_cli_error(accent_run_height_implausible "error: accent: user height 0.1 m is outside the plausible range \\[0.5, 2.5\\] m"
                 accent run --db ${ACC_DB} --input ${D}/walking/07_02.bvh --height 0.1 --out ${O}/x.bvh)
legwork_cli_error(accent_run_nothing_matched "warning: no frame matched the database \\([0-9]+ of [0-9]+ frames unmatched\\)"
                 accent run --db ${ACC_DB} --input ${D}/walking/07_02.bvh --drop-first --exaggerate 100 --out ${O}/accent_unmatched.bvh)
set_tests_properties(cli.accent_run_height_implausible cli.accent_run_nothing_matched PROPERTIES FIXTURES_REQUIRED accent_db)
# Options with no maximum name their bound in plain digits (CLI11's own checks print a 300-digit maximum).
legwork_cli_error(accent_run_height_positive "--height: Value -1 must be > 0\n"
                 accent run --db ${ACC_DB} --input ${D}/walking/07_02.bvh --height -1 --out ${O}/x.bvh)
legwork_cli_error(accent_run_threshold_nan "--threshold: Value nan is not a number"
                 accent run --db ${ACC_DB} --input ${D}/walking/07_02.bvh --threshold nan --out ${O}/x.bvh)
# `legwork info` on a database describes it (by its magic, whatever its name);
# a database given where a motion or a CSV is read is named as one.
add_test(NAME cli.info_accent_db COMMAND legwork info ${ACC_DB})
set_tests_properties(cli.info_accent_db PROPERTIES FIXTURES_REQUIRED accent_db PASS_REGULAR_EXPRESSION
  "format: +legwork accent database, version [0-9]+.*windows of: 9 samples 2 apart at 90 Hz \\(178 ms\\).*classes: .*walking \\([0-9]+ trials, [0-9]+ windows\\).*index: +KD-trees stored in the file")
add_test(NAME cli.info_accent_db_json COMMAND legwork info ${ACC_DB} --json)
set_tests_properties(cli.info_accent_db_json PROPERTIES FIXTURES_REQUIRED accent_db PASS_REGULAR_EXPRESSION
  "\"window_stride\": 2,.*\"windows\": [1-9][0-9]*")
# A damaged database is named, not described: truncated (the header's size
# against the file's) and one byte changed (the checksum), text and --json alike.
add_test(NAME cli.info_truncated_db COMMAND sh -c
  "head -c 4096 '${ACC_DB}' > '${O}/truncated.lwdb' && exec '$<TARGET_FILE:legwork>' info '${O}/truncated.lwdb'")
add_test(NAME cli.info_corrupted_db_json COMMAND sh -c
  "cp '${ACC_DB}' '${O}/corrupted.lwdb' && printf '\\377' | dd of='${O}/corrupted.lwdb' bs=1 seek=200000 conv=notrunc 2>/dev/null && exec '$<TARGET_FILE:legwork>' info '${O}/corrupted.lwdb' --json")
set_tests_properties(cli.info_truncated_db PROPERTIES FIXTURES_REQUIRED accent_db PASS_REGULAR_EXPRESSION
  "legwork: error: accent database '.*truncated.lwdb': header says [0-9]+ bytes but the file has 4096 \\(truncated\\)")
set_tests_properties(cli.info_corrupted_db_json PROPERTIES FIXTURES_REQUIRED accent_db PASS_REGULAR_EXPRESSION
  "legwork: error: accent database '.*corrupted.lwdb': checksum mismatch: the file is corrupted")
legwork_cli_error(convert_accent_db_as_motion
  "error: .*accent_sample.lwdb: a legwork accent database \\(binary .lwdb\\), not a text file; 'legwork info .*accent_sample.lwdb' describes it"
  convert ${ACC_DB} ${O}/from_db.bvh)
legwork_cli_error(accent_run_db_as_input
  "error: --input '.*accent_sample.lwdb' must be a .bvh trial or a .csv headset session"
  accent run --db ${ACC_DB} --input ${ACC_DB} --out ${O}/from_db.bvh)
set_tests_properties(cli.convert_accent_db_as_motion cli.accent_run_db_as_input PROPERTIES FIXTURES_REQUIRED accent_db)

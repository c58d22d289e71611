# legwork eval accent: the --quick run on the repo's sample data (CI), its
# report checked by check_eval_report.cmake, and bad input.
legwork_cli_test(eval_quick eval accent --data ${PROJECT_SOURCE_DIR}/data/cmu --quick --out ${O}/eval-quick)
set_tests_properties(cli.eval_quick PROPERTIES FIXTURES_SETUP eval_quick TIMEOUT 180)
add_test(NAME cli.eval_quick_report
         COMMAND ${CMAKE_COMMAND} -DREPORT_DIR=${O}/eval-quick -P ${CMAKE_CURRENT_LIST_DIR}/check_eval_report.cmake)
set_tests_properties(cli.eval_quick_report PROPERTIES FIXTURES_REQUIRED eval_quick)
legwork_cli_test(eval_help eval accent --help)
legwork_cli_error(eval_other_class_cost_range "--other-class-cost: Value 0.5 must be 0 \\(off\\) or a factor from 1 to 1000000" eval accent --data ${PROJECT_SOURCE_DIR}/data/cmu --quick --other-class-cost 0.5)
legwork_cli_error(eval_foot_lift_range "--foot-lift-height: Value -1 not in range 0\\.0+ to 0\\.50*" eval accent --data ${PROJECT_SOURCE_DIR}/data/cmu --quick --foot-lift-height -1)
legwork_cli_error(eval_foot_slack_range "--foot-lock-slack: Value 3 not in range 0\\.0+ to 1\\.0*" eval accent --data ${PROJECT_SOURCE_DIR}/data/cmu --quick --foot-lock-slack 3)
legwork_cli_error(eval_foot_hold_range "--foot-lock-hold: Value -1 not in range 0\\.0+ to 10\\.0*" eval accent --data ${PROJECT_SOURCE_DIR}/data/cmu --quick --foot-lock-hold -1)
legwork_cli_test(eval_foot_lift eval accent --data ${PROJECT_SOURCE_DIR}/data/cmu --quick --quick-trials 2 --max-seconds 3 --no-ablation --skip-no-class --foot-lift-height 0.08)
set_tests_properties(cli.eval_foot_lift PROPERTIES TIMEOUT 180)
# The IK blend, contact thresholds and lock creep as evaluation options (issue 12's "where IK wins" runs).
legwork_cli_test(eval_ik_blend eval accent --data ${PROJECT_SOURCE_DIR}/data/cmu --quick --quick-trials 2 --max-seconds 3 --no-ablation
                 --skip-no-class --ik-blend-min 0.3 --ik-blend-near 1 --ik-blend-far 2 --contact-on 0.5 --contact-off 0.3 --foot-lock-follow 0.2)
set_tests_properties(cli.eval_ik_blend PROPERTIES TIMEOUT 180)
legwork_cli_error(eval_ik_blend_min_range "--ik-blend-min: Value 1.5 not in range 0\\.0+ to 1\\.0*" eval accent --data ${PROJECT_SOURCE_DIR}/data/cmu --quick --ik-blend-min 1.5)
legwork_cli_error(eval_contact_order "error: accent: foot contact thresholds need 0 <= contact_off <= contact_on <= 1"
                 eval accent --data ${PROJECT_SOURCE_DIR}/data/cmu --quick --quick-trials 2 --max-seconds 3 --no-ablation --skip-no-class --contact-on 0.2)
legwork_cli_error(eval_missing_data "error: .*no-such-folder: not a directory" eval accent --data ${O}/no-such-folder --quick)
legwork_cli_error(eval_unknown_class "error: .*no class 'dancing' \\(classes present: basketball" eval accent --data ${PROJECT_SOURCE_DIR}/data/cmu --classes dancing --quick)
legwork_cli_error(eval_bad_protocol "error: --protocols: unknown protocol 'leave_one_out' \\(cross_subject, cross_trial, cross_dataset\\)" eval accent --data ${PROJECT_SOURCE_DIR}/data/cmu --protocols leave_one_out --quick)
legwork_cli_error(eval_cross_dataset_needs_test "error: --protocols cross_dataset needs --test DIR" eval accent --data ${PROJECT_SOURCE_DIR}/data/cmu --protocols cross_dataset)
# --out is checked before the evaluation runs (it used to fail with a raw "filesystem error" at the end).
legwork_cli_error(eval_out_is_a_file "error: --out '.*README.md': is a file, not a folder"
                 eval accent --data ${PROJECT_SOURCE_DIR}/data/cmu --quick --out ${PROJECT_SOURCE_DIR}/README.md)
legwork_cli_error(eval_out_under_a_file "error: --out '.*README.md/report': cannot write in '.*README.md' \\(it is a file, not a folder\\)"
                 eval accent --data ${PROJECT_SOURCE_DIR}/data/cmu --quick --out ${PROJECT_SOURCE_DIR}/README.md/report)
set_tests_properties(cli.eval_out_is_a_file cli.eval_out_under_a_file PROPERTIES TIMEOUT 20)
legwork_cli_error(eval_bad_manifest "error: .*07_01.bvh:1: no 'file' column \\(need file, class, subject, trial; tab-separated\\)" eval accent --data ${PROJECT_SOURCE_DIR}/data/cmu --manifest ${PROJECT_SOURCE_DIR}/data/cmu/bvh/walking/07_01.bvh)
# Cross-dataset: a fixed database (manifest subset) scoring other subjects' trials;
# boxing has no database trial and is listed as not evaluable.
legwork_cli_test(eval_cross_dataset eval accent --data ${PROJECT_SOURCE_DIR}/data/cmu
                 --manifest ${CMAKE_CURRENT_LIST_DIR}/eval_database.tsv --test ${PROJECT_SOURCE_DIR}/data/cmu
                 --test-manifest ${CMAKE_CURRENT_LIST_DIR}/eval_test.tsv --max-seconds 10 --out ${O}/eval-cross-dataset)

# One avatar, two sources on two sample walks: the table names every method.
add_test(NAME cli.eval_combined COMMAND legwork eval combined --data ${D}/walking --limit 2)
set_tests_properties(cli.eval_combined PROPERTIES PASS_REGULAR_EXPRESSION
  "2 trials at 30 Hz \\(0 skipped\\)\n.*\\| IK avatar alone \\| [0-9.]+ \\|.*\\| combined: IK upper body \\+ walking-in-place legs \\(document's mapping\\) \\| [0-9.]+ \\|.*\\| combined: IK upper body \\+ walking-in-place legs \\(learned mapping, without the trial's subject\\) \\| [0-9.]+ \\|")
# A given learned table scores the learned legs even where --data holds one subject only (no held-out table).
add_test(NAME cli.eval_combined_wip_table COMMAND legwork eval combined --data ${D}/walking --limit 1
         --wip-table ${PROJECT_SOURCE_DIR}/data/wip/learned_mapping.txt)
set_tests_properties(cli.eval_combined_wip_table PROPERTIES PASS_REGULAR_EXPRESSION
  "1 trials at 30 Hz \\(0 skipped\\)\n.*\\| combined: IK upper body \\+ walking-in-place legs \\(learned mapping, the given table\\) \\| [0-9.]+ \\|")
legwork_cli_error(eval_combined_bad_wip_table
                  "error: .*CMakeLists.txt:1: not a learned walking-in-place mapping \\(expected the header 'legwork-wip-learned-mapping 2', or 1\\)"
                  eval combined --data ${D}/walking --limit 1 --wip-table ${PROJECT_SOURCE_DIR}/CMakeLists.txt)
legwork_cli_error(eval_combined_not_a_folder "error: --data '${D}/walking/07_01.bvh' is not a directory"
                  eval combined --data ${D}/walking/07_01.bvh)
legwork_cli_test(eval_prints_help eval)
set_tests_properties(cli.eval_prints_help PROPERTIES PASS_REGULAR_EXPRESSION "Evaluate methods against motion-capture ground truth.*accent.*combined")
add_test(NAME cli.bare_legwork_prints_help COMMAND legwork)
set_tests_properties(cli.bare_legwork_prints_help PROPERTIES PASS_REGULAR_EXPRESSION "Usage: legwork \\[OPTIONS\\] \\[SUBCOMMAND\\].*walkcycle")
# The engine options (one table in cmd_eval.cpp): each is range-checked and reaches the engine.
legwork_cli_error(eval_threshold_negative "--threshold: Value -2 must be >= 0\n" eval accent --data ${PROJECT_SOURCE_DIR}/data/cmu --quick --threshold -2)
legwork_cli_error(eval_hand_ik_range "--hand-ik: Value 2 not in range 0\\.0+ to 1\\.0*" eval accent --data ${PROJECT_SOURCE_DIR}/data/cmu --quick --hand-ik 2)

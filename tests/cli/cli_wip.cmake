# legwork wip / wip eval smoke tests (outputs in ${O}, sample data in ${D}).
legwork_cli_test(wip_help wip --help)
legwork_cli_test(wip_synthetic wip --synthetic --duration 12 --out ${O}/wip_synthetic.glb --csv ${O}/wip_synthetic.csv
                 --plot ${O}/wip_synthetic.png --tracker-out ${O}/wip_synthetic_tracker.csv)
legwork_cli_test(wip_bvh wip --input ${D}/walking/16_15.bvh --out ${O}/wip_16_15.bvh --plot ${O}/wip_16_15.png)
legwork_cli_test(wip_keyframe wip --input ${D}/walking/07_02.bvh --out ${O}/wip_07_02_keyframe.glb --baseline keyframe
                 --avatar ${D}/walking/07_01.bvh)
legwork_cli_test(wip_eval wip eval --data ${D}/walking --out ${O}/wip_eval --limit 3)
# The step detector: the adaptive one on a real walk, and its parameters chosen by subject over the sample walks.
legwork_cli_test(wip_adaptive wip --input ${D}/walking/16_15.bvh --detector adaptive --out ${O}/wip_16_15_adaptive.bvh)
# (three trials, subjects 05 and 07: two folds; the full grid, 2,916 sets. All seven took 152 s under ASan;
# tests/eval/wip_tune_test.cpp cross-validates all seven.)
legwork_cli_test(wip_tune wip tune --data ${D}/walking --out ${O}/wip_tune --limit 3)
set_tests_properties(cli.wip_tune PROPERTIES PASS_REGULAR_EXPRESSION
  "3 trials, 2916 parameter sets[;] held out by subject: F1 [01]\\.[0-9]+.*wrote report: [^\n]*wip_tune/report\\.json")
legwork_cli_test(wip_frequency wip --synthetic --duration 8 --speed-model frequency --rate 90 --out ${O}/wip_90hz.bvh)
# The learned depth mapping: the shipped table, and a table learned from the sample walks.
legwork_cli_test(wip_learned wip --input ${D}/walking/16_15.bvh --mapping learned --out ${O}/wip_16_15_learned.bvh)
legwork_cli_test(wip_learn wip learn --data ${D}/walking --exclude-subjects 16 --out ${O}/wip_learned_mapping.txt)
legwork_cli_test(wip_learned_table wip --input ${D}/walking/16_15.bvh --mapping learned --table ${O}/wip_learned_mapping.txt
                 --out ${O}/wip_16_15_learned_table.bvh)
set_tests_properties(cli.wip_learned_table PROPERTIES DEPENDS cli.wip_learn)
# The synthetic tracker CSV written above, read back (runs after wip_synthetic).
legwork_cli_test(wip_csv wip --input ${O}/wip_synthetic_tracker.csv --out ${O}/wip_from_csv.bvh)
set_tests_properties(cli.wip_csv PROPERTIES DEPENDS cli.wip_synthetic)

# Bad input: each must fail with its own message (main prints "legwork: error: <message>"
# only when a command fails, so matching it checks both the failure and the text).
legwork_cli_error(wip_no_input "error: [^\n]*give exactly one of --input FILE \\(.csv or .bvh\\) and --synthetic" wip --out ${O}/x.glb)
legwork_cli_error(wip_speed_gain_range "--speed-gain: Value -1 not in range 0\\.0+ to 20\\.0+" wip --synthetic --speed-gain -1 --out ${O}/x.glb)
legwork_cli_error(wip_max_speed_range "--max-speed: Value 50 not in range 0\\.0+ to 12\\.0+" wip --synthetic --max-speed 50 --out ${O}/x.glb)
# Every numeric wip option is checked against a plain range named in the message (CLI11's non-negative and
# positive checks printed a 300-digit maximum). Each spec: where (wip = `wip --synthetic`, eval = `wip eval`);
# option; bad value; the message's range as a regex.
set(r0 "0\\.0+ to")
set(rp "0 \\(exclusive\\) to")
foreach(spec IN ITEMS "wip;--noise-factor;-1;${r0} 20\\.0+" "wip;--rise-noise-factor;500;${r0} 200\\.0+"
                      "wip;--lift-fraction;1.5;${r0} 1\\.0+" "wip;--rise-fraction;-0.1;${r0} 1\\.0+"
                      "wip;--min-lift;0.5;${r0} 0\\.10*" "wip;--min-rise;3;${r0} 2\\.0+" "wip;--stand-time;-2;${r0} 600\\.0+"
                      "wip;--noise;0.5;${r0} 0\\.20*" "eval;--noise;-0.01;${r0} 0\\.20*" "wip;--cutoff;-1;${rp} 50"
                      "wip;--h1;0;${rp} 1" "wip;--detect-cutoff;80;${rp} 50" "wip;--step-length;-0.6;${rp} 2"
                      "wip;--cadence;0;${rp} 10" "eval;--limit;0;1 to 1000000"
                      "wip;--rest-time;-1;${r0} 60\\.0+" "wip;--rest-lift;0.5;${r0} 0\\.10*" "eval;--rest-rise;3;${r0} 2\\.0+"
                      "wip;--rest-noise-factor;-2;${r0} 20\\.0+" "wip;--settle-time;11;${r0} 10\\.0+"
                      "wip;--min-swing-time;2;${r0} 1\\.0+")
  list(GET spec 0 where)
  list(GET spec 1 opt)
  list(GET spec 2 value)
  list(GET spec 3 range)
  string(REGEX REPLACE "^--" "_" name "${opt}")
  string(REPLACE "-" "_" name "${where}${name}")
  string(REPLACE "." "\\." value_re "${value}")
  if(where STREQUAL "eval")
    set(run wip eval --data ${D}/walking --out ${O}/wip_eval_range)
  else()
    set(run wip --synthetic --out ${O}/x.glb)
  endif()
  legwork_cli_error(${name}_range "${opt}: Value ${value_re} not in range ${range}" ${run} ${opt} ${value})
endforeach()
legwork_cli_error(wip_bad_out "error: [^\n]*--out '[^']*x.txt' must end in .glb or .bvh" wip --synthetic --out ${O}/x.txt)
legwork_cli_error(wip_bad_plot "error: [^\n]*--plot '[^']*x.jpg' must end in .png" wip --synthetic --out ${O}/x.glb --plot ${O}/x.jpg)
legwork_cli_error(wip_bad_calibrate "error: [^\n]*--calibrate 'maybe': expected auto, on or off" wip --synthetic --out ${O}/x.glb
             --calibrate maybe)
legwork_cli_error(wip_bad_speed_model "error: [^\n]*--speed-model 'fast': expected 'step'" wip --synthetic --out ${O}/x.glb
             --speed-model fast)
legwork_cli_error(wip_bad_baseline "error: [^\n]*--baseline 'canned': the only baseline is 'keyframe'" wip --synthetic --out ${O}/x.glb
             --baseline canned)
legwork_cli_error(wip_input_not_a_tracker "error: [^\n]*--input '[^']*tests/wip/data' must be a tracker .csv or a .bvh motion"
             wip --input ${PROJECT_SOURCE_DIR}/tests/wip/data --out ${O}/x.glb)
# A run is made in memory: a longer one is refused before any work, naming the options and the limit.
legwork_cli_error(wip_synthetic_too_long "error: [^\n]*--duration 100000 s at --rate 30 Hz makes 3000001 tracker frames; the limit is 500000 frames \\(a run is made in memory\\)"
             wip --synthetic --duration 100000 --out ${O}/x.glb)
legwork_cli_error(wip_not_still "error: [^\n]*cannot calibrate the floor: the user is not standing still during the first 3.0 s.*--calibrate off"
             wip --synthetic --duration 6 --stand-time 0.5 --calibrate on --out ${O}/x.glb)
legwork_cli_error(wip_csv_missing_columns "error: [^\n]*no_ankles.csv: no column for the left_foot .*points present: head, left_hand"
             wip --input ${PROJECT_SOURCE_DIR}/tests/wip/data/no_ankles.csv --out ${O}/x.bvh)
legwork_cli_error(wip_csv_time_backwards "error: [^\n]*time_backwards.csv:4:1: time 0.025 is not after the previous row's time"
             wip --input ${PROJECT_SOURCE_DIR}/tests/wip/data/time_backwards.csv --out ${O}/x.bvh)
legwork_cli_error(wip_avatar_without_legs "error: [^\n]*--avatar [^ ]*no_legs.bvh: avatar skeleton has no usable legs: joint roles left_hip"
             wip --synthetic --avatar ${PROJECT_SOURCE_DIR}/tests/wip/data/no_legs.bvh --out ${O}/x.bvh)
legwork_cli_error(wip_bad_mapping "--mapping: fancy not in \\{document,learned\\}" wip --synthetic --out ${O}/x.glb
             --mapping fancy)
legwork_cli_error(wip_bad_detector "--detector: psychic not in \\{document,adaptive\\}" wip --synthetic --out ${O}/x.glb
             --detector psychic)
legwork_cli_error(wip_bad_detect_cutoff "error: [^\n]*--detect-cutoff 20.000000 Hz must be between 0 and half the sample rate"
             wip --synthetic --out ${O}/x.glb --detect-cutoff 20)
legwork_cli_error(wip_missing_table "error: [^\n]*--table '[^']*nope.txt' does not exist \\(make one with `legwork wip learn`\\)"
             wip --synthetic --out ${O}/x.glb --mapping learned --table ${O}/nope.txt)
legwork_cli_error(wip_bad_table "error: [^\n]*CMakeLists.txt:1: not a learned walking-in-place mapping"
             wip --synthetic --out ${O}/x.glb --mapping learned --table ${PROJECT_SOURCE_DIR}/CMakeLists.txt)
legwork_cli_error(wip_eval_no_data "error: [^\n]*--data '[^']*does-not-exist' is not a directory"
             wip eval --data ${O}/does-not-exist --out ${O}/wip_eval_x)
legwork_cli_error(wip_eval_no_trials "error: [^\n]*--data '[^']*tests/wip' holds no .bvh files"
             wip eval --data ${PROJECT_SOURCE_DIR}/tests/wip --out ${O}/wip_eval_y)
legwork_cli_error(wip_eval_out_is_a_file "error: [^\n]*--out '[^']*CMakeLists.txt' is not a folder"
             wip eval --data ${D}/walking --out ${PROJECT_SOURCE_DIR}/CMakeLists.txt --limit 1)
# Run from the repository root, as a user would: the default avatar and walk
# cycle (data/cmu/bvh/walking/07_01.bvh) are found from there.
set_tests_properties(cli.wip_help cli.wip_synthetic cli.wip_bvh cli.wip_keyframe cli.wip_eval cli.wip_frequency
                     cli.wip_csv cli.wip_no_input cli.wip_bad_out cli.wip_bad_plot cli.wip_bad_calibrate
                     cli.wip_bad_speed_model cli.wip_bad_baseline cli.wip_input_not_a_tracker cli.wip_synthetic_too_long
                     cli.wip_not_still cli.wip_csv_missing_columns cli.wip_csv_time_backwards
                     cli.wip_avatar_without_legs cli.wip_eval_no_data cli.wip_eval_no_trials cli.wip_eval_out_is_a_file
                     cli.wip_learned cli.wip_learn cli.wip_learned_table cli.wip_bad_mapping cli.wip_missing_table
                     cli.wip_bad_table cli.wip_adaptive cli.wip_tune cli.wip_bad_detector cli.wip_bad_detect_cutoff
                     PROPERTIES WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
legwork_cli_error(serve_bad_wip_table "error: .*MANIFEST.tsv:1: not a learned walking-in-place mapping \\(expected the header 'legwork-wip-learned-mapping 2', or 1\\)" serve --port 0 --wip-table ${PROJECT_SOURCE_DIR}/data/cmu/MANIFEST.tsv)

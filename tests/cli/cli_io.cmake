# I/O smoke tests: GLB export of both skeleton layouts, BVH round trip of the
# DAZ layout (Z X Y channels), and bad output paths.
legwork_cli_test(convert_glb_daz convert ${PROJECT_SOURCE_DIR}/data/cmu/bvh_daz/climbing_ladder/14_33.bvh ${O}/14_33.glb)
legwork_cli_test(convert_glb_rate_mirror convert ${D}/running/09_01.bvh ${O}/09_01_30hz_mirror.glb --frames 1: --rate 30 --mirror)
legwork_cli_test(convert_bvh_daz convert ${PROJECT_SOURCE_DIR}/data/cmu/bvh_daz/climbing_ladder/14_33.bvh ${O}/14_33_copy.bvh)
legwork_cli_error(convert_glb_unwritable "error: output '.*no-such-dir/x.glb': folder '.*no-such-dir' does not exist and is outside the working folder; create it first" convert ${D}/walking/07_01.bvh ${O}/no-such-dir/x.glb)

# Bad input must fail with a message a user can act on: each test below checks
# the message (never a raw "std::bad_alloc", "stod" or "filesystem error").
# "legwork: error: " is printed only on the failing exit path.
set(IOD ${PROJECT_SOURCE_DIR}/tests/io/data)
# A directory given as a file (was: "error: std::bad_alloc" where no option
# validator catches it first; io::read_text_file now says so, see Text.*).
add_test(NAME cli.info_directory COMMAND legwork info ${O})
set_tests_properties(cli.info_directory PROPERTIES PASS_REGULAR_EXPRESSION "File is actually a directory: ${O}")
file(MAKE_DIRECTORY ${O}/folder.bvh ${O}/folder.glb)
legwork_cli_error(convert_output_is_directory "error: ${O}/folder.bvh: is a directory, not a file"
                  convert ${D}/walking/07_01.bvh ${O}/folder.bvh)
legwork_cli_error(convert_glb_output_is_directory "error: ${O}/folder.glb: is a directory, not a file"
                  convert ${D}/walking/07_01.bvh ${O}/folder.glb)
# A UTF-16 file (was: "found '??H?I?E?R?'").
legwork_cli_error(info_utf16 "error: ${IOD}/utf16.bvh: UTF-16 text; save it as UTF-8" info ${IOD}/utf16.bvh)
# A Latin-1 joint name (was: "[json.exception.type_error.316]" from --json or GLB output, naming no file).
legwork_cli_error(info_json_latin1_joint "error: ${IOD}/latin1_joint.bvh:10: joint name 'LeftUpLeg\\?' is not UTF-8 text"
                  info ${IOD}/latin1_joint.bvh --json)
legwork_cli_error(convert_latin1_joint "error: .*/latin1_joint.bvh:10: joint name" convert ${IOD}/latin1_joint.bvh ${O}/x.glb)
# Frame Time: 1e300 (was: a SIGSEGV in 'wip --input' after the sample count overflowed).
legwork_cli_error(info_frame_time_1e300 "error: ${IOD}/frame_time_1e300.bvh:187: 'Frame Time: 1e\\+300' is outside 0.0001 to 10 seconds"
                  info ${IOD}/frame_time_1e300.bvh)
# Resampling is bounded before any work (was: a 2.4 GB file using 6.9 GB).
legwork_cli_error(convert_rate_too_high "error: --rate 1e\\+06 Hz is above the limit of 1000 Hz"
                  convert ${D}/walking/07_01.bvh ${O}/x.bvh --rate 1000000)
# Output folders: made when under the working folder, refused (never made) outside it.
legwork_cli_error(convert_missing_output_folder
                  "error: output '${O}/no-such-dir/x.bvh': folder '${O}/no-such-dir' does not exist and is outside the working folder; create it first"
                  convert ${D}/walking/07_01.bvh ${O}/no-such-dir/x.bvh)
file(MAKE_DIRECTORY ${O}/workdir)
add_test(NAME cli.convert_makes_output_folder_in_working_folder
         COMMAND legwork convert ${D}/walking/07_01.bvh made/here/x.bvh --frames 1:10 WORKING_DIRECTORY ${O}/workdir)
set_tests_properties(cli.convert_makes_output_folder_in_working_folder PROPERTIES
                     PASS_REGULAR_EXPRESSION "10 frames at 120 Hz, 31 joints\nwrote motion: made/here/x.bvh")
# A std::filesystem error reaches the user as "<path>: <reason>", not
# "filesystem error: cannot create directories: Not a directory [...]".
# (the raw std::filesystem_error mapping itself: tests/io/errors_test.cpp)
legwork_cli_error(filesystem_error_is_mapped "error: --out '[^']*MANIFEST.tsv/report': cannot write in '[^']*MANIFEST.tsv' \\(it is a file, not a folder\\)\n"
                  eval accent --data ${PROJECT_SOURCE_DIR}/data/cmu --classes walking --quick
                  --out ${PROJECT_SOURCE_DIR}/data/cmu/MANIFEST.tsv/report)

# A GLB converts back with the clip's own frames and rate (was: 35 frames at
# 30 Hz from a 138-frame 120 Hz clip), at 120 and 60 Hz.
foreach(clip walking/07_01:317:120 swimming/79_02:301:60)
  string(REPLACE ":" ";" parts ${clip})
  list(GET parts 0 trial)
  list(GET parts 1 frames)
  list(GET parts 2 hz)
  get_filename_component(stem ${trial} NAME)
  legwork_cli_test(convert_${stem}_to_glb convert ${D}/${trial}.bvh ${O}/${stem}_all.glb)
  add_test(NAME cli.convert_${stem}_glb_back COMMAND legwork convert ${O}/${stem}_all.glb ${O}/${stem}_back.bvh)
  set_tests_properties(cli.convert_${stem}_glb_back PROPERTIES DEPENDS cli.convert_${stem}_to_glb
                       PASS_REGULAR_EXPRESSION "${frames} frames at ${hz} Hz, 31 joints")
endforeach()
legwork_cli_error(convert_rate_negative "--rate: Value -1 must be >= 0\n" convert ${D}/walking/07_01.bvh ${O}/x.bvh --rate -1)

# I/O smoke tests: GLB export of both skeleton layouts, BVH round trip of the
# DAZ layout (Z X Y channels), and bad output paths.
legwork_cli_test(convert_glb_daz convert ${PROJECT_SOURCE_DIR}/data/cmu/bvh_daz/climbing_ladder/14_33.bvh ${O}/14_33.glb)
legwork_cli_test(convert_glb_rate_mirror convert ${D}/running/09_01.bvh ${O}/09_01_30hz_mirror.glb --frames 1: --rate 30 --mirror)
legwork_cli_test(convert_bvh_daz convert ${PROJECT_SOURCE_DIR}/data/cmu/bvh_daz/climbing_ladder/14_33.bvh ${O}/14_33_copy.bvh)
legwork_cli_fail(convert_glb_unwritable convert ${D}/walking/07_01.bvh ${O}/no-such-dir/x.glb)

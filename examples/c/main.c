/* legwork from C: load an accentuation database, drive one avatar with a CMU
 * trial's head and hands (as a headset and two controllers would), and write
 * every frame's pose as CSV: frame,status,joint,qw,qx,qy,qz,x,y,z (local
 * rotation, world position; "%.17g", so other bindings can compare exactly).
 *
 *   legwork accent build --data data/cmu --exclude bvh/walking/07_02.bvh --out sample.lwdb
 *   example_c sample.lwdb data/cmu/bvh/walking/07_02.bvh poses.csv
 */
#include <legwork/legwork.h>

#include <stdio.h>
#include <stdlib.h>

static int check(lw_status s, const char* what) {
  if (s < 0) {
    fprintf(stderr, "example_c: %s failed: %s (%s)\n", what, lw_status_name(s), lw_last_error());
    return 0;
  }
  return 1;
}

int main(int argc, char** argv) {
  if (argc != 4) {
    fprintf(stderr, "usage: example_c DATABASE.lwdb TRIAL.bvh OUT.csv\n");
    return 2;
  }
  if (lw_abi_version() != LW_ABI_VERSION) {
    fprintf(stderr, "example_c: liblegwork ABI %u, header %u\n", lw_abi_version(), LW_ABI_VERSION);
    return 1;
  }
  lw_database* db = NULL;
  lw_model* model = NULL;
  lw_avatar* avatar = NULL;
  lw_frame* frames = NULL;
  int32_t count = 0;
  double* rotations = NULL;
  double* positions = NULL;
  FILE* out = NULL;
  int ok = check(lw_database_load(argv[1], &db), "lw_database_load") &&
           check(lw_frames_from_bvh(argv[2], 90.0, 1, &frames, &count), "lw_frames_from_bvh");
  if (ok) {
    lw_accent_settings settings;
    lw_accent_settings_default(&settings);
    settings.user_height = 1.7;
    ok = check(lw_model_create_accent(db, &settings, &model), "lw_model_create_accent") &&
         check(lw_avatar_create(model, &avatar), "lw_avatar_create");
  }
  const int32_t joints = ok ? lw_skeleton_joint_count(lw_model_skeleton(model)) : 0;
  if (ok) {
    rotations = malloc(sizeof(double) * 4 * (size_t)joints);
    positions = malloc(sizeof(double) * 3 * (size_t)joints);
    out = fopen(argv[3], "w");
    if (!rotations || !positions || !out) {
      fprintf(stderr, "example_c: cannot write %s\n", argv[3]);
      ok = 0;
    }
  }
  for (int32_t f = 0; ok && f < count; ++f) {
    const lw_status s = lw_avatar_update(avatar, &frames[f]);
    ok = check(s, "lw_avatar_update") && check(lw_avatar_pose(avatar, rotations, NULL, positions, joints), "lw_avatar_pose");
    for (int32_t j = 0; ok && j < joints; ++j)
      fprintf(out, "%d,%s,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", f, lw_status_name(s), j, rotations[4 * j],
              rotations[4 * j + 1], rotations[4 * j + 2], rotations[4 * j + 3], positions[3 * j], positions[3 * j + 1],
              positions[3 * j + 2]);
  }
  if (ok) printf("example_c: %d frames x %d joints written to %s\n", count, joints, argv[3]);
  if (out) fclose(out);
  free(rotations);
  free(positions);
  lw_frames_free(frames);
  lw_avatar_destroy(avatar);
  lw_model_destroy(model);
  lw_database_destroy(db);
  return ok ? 0 : 1;
}

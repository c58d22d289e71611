// The C API (legwork.h) against the C++ API on real data, its errors, and
// its allocation-free per-frame path.
#include <legwork/legwork.h>

#include <legwork/accent/accent.hpp>
#include <legwork/accent/offline/builder.hpp>
#include <legwork/combined/combined.hpp>
#include <legwork/ik/full_body.hpp>
#include <legwork/io/bvh.hpp>

#include <gtest/gtest.h>

#include <cmu_sample.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <string>

namespace legwork {
namespace {

namespace fs = std::filesystem;

std::string sample(const std::string& rel) { return std::string(LEGWORK_SOURCE_DIR) + "/data/" + rel; }

// This process's database file, removed when the process exits (each test
// runs in its own process: the files of earlier runs piled up in /tmp).
std::string database_path() {
  return (fs::temp_directory_path() / ("legwork_capi_test_" + std::to_string(::getpid()) + ".lwdb")).string();
}
void remove_database_file() {
  std::error_code ec;
  fs::remove(database_path(), ec);
}

// A database over the repo's sample trials without 07_02, built once.
const std::string& database_file() {
  static const std::string path = [] {
    std::vector<accent::TrialInput> trials;
    for (const char* name : {"walking/07_01", "walking/05_01", "running/09_01", "boxing/13_18"}) {
      accent::TrialInput t;
      t.file = std::string(name) + ".bvh";
      t.cls = std::string(name).substr(0, std::string(name).find('/'));
      t.motion = testdata::load_sample(std::string("cmu/bvh/") + name + ".bvh");
      trials.push_back(std::move(t));
    }
    const std::string p = database_path();
    accent::save_database(p, accent::build_database(trials, accent::BuildConfig{}));
    std::atexit(remove_database_file);
    return p;
  }();
  return path;
}

// The joint of the model's skeleton with a Unity humanoid name, -1 if none.
int humanoid_joint(const lw_model* model, const std::string& name) {
  const int32_t n = lw_skeleton_joint_count(lw_model_skeleton(model));
  for (int j = 0; j < n; ++j) {
    const char* h = lw_model_humanoid_name(model, j, 0);
    if (h && name == h) return j;
  }
  return -1;
}

struct Frames {
  lw_frame* data = nullptr;
  int32_t count = 0;
  ~Frames() { lw_frames_free(data); }
};

TEST(CApi, AccentAvatarEqualsTheCppApiBitForBit) {
  lw_database* db = nullptr;
  ASSERT_EQ(lw_database_load(database_file().c_str(), &db), LW_OK) << lw_last_error();
  EXPECT_GE(lw_database_class_count(db), 3);
  Frames f;
  ASSERT_EQ(lw_frames_from_bvh(sample("cmu/bvh/walking/07_02.bvh").c_str(), 90.0, 1, &f.data, &f.count), LW_OK) << lw_last_error();
  ASSERT_GT(f.count, 200);
  lw_accent_settings s;
  lw_accent_settings_default(&s);
  s.user_height = 1.7;
  s.classes = "walking,running";
  lw_model* model = nullptr;
  ASSERT_EQ(lw_model_create_accent(db, &s, &model), LW_OK) << lw_last_error();
  lw_avatar* avatar = nullptr;
  ASSERT_EQ(lw_avatar_create(model, &avatar), LW_OK);

  const accent::Database cdb = accent::load_database(database_file());
  accent::Settings cs;
  cs.user_height = 1.7;
  cs.classes = {"walking", "running"};
  const accent::Model cm = accent::make_model(cdb, cs);
  accent::State st(cm);
  Pose pose(cm.skeleton());
  const int32_t n = lw_skeleton_joint_count(lw_model_skeleton(model));
  ASSERT_EQ(n, cm.skeleton().joint_count());
  std::vector<double> rot(4 * static_cast<std::size_t>(n)), root(3);
  const io::BvhReadOptions o{.drop_first_frame = true};
  const auto frames = tracker_frames_from_motion(io::load_bvh(sample("cmu/bvh/walking/07_02.bvh"), o), 90.0);
  ASSERT_EQ(static_cast<std::size_t>(f.count), frames.size());
  EXPECT_EQ(lw_avatar_info_count(avatar), 0) << "no frame yet";
  int recognised = 0;
  for (int32_t i = 0; i < f.count; ++i) {
    const lw_status a = lw_avatar_update(avatar, &f.data[i]);
    accent::Info info;
    const UpdateStatus b = accent::update(cm, frames[static_cast<std::size_t>(i)], st, pose.ref(), &info);
    ASSERT_EQ(std::string(lw_status_name(a)), status_name(b));
    // The frame's figures: the C++ Info under the server's pose "info" names.
    ASSERT_EQ(lw_avatar_info_count(avatar), 8);
    double number = -1;
    const char* text = nullptr;
    ASSERT_EQ(lw_avatar_info_find(avatar, "match", &number, &text), LW_OK);
    ASSERT_STREQ(text, accent::status_name(info.match));
    ASSERT_EQ(lw_avatar_info_find(avatar, "match_weight", &number, &text), LW_OK);
    ASSERT_EQ(text, nullptr);
    ASSERT_EQ(number, info.match_weight);
    ASSERT_EQ(lw_avatar_info_find(avatar, "active_class", &number, nullptr), LW_OK);
    ASSERT_EQ(number, info.active_class);
    ASSERT_EQ(lw_avatar_info_find(avatar, "classes_searched", &number, nullptr), LW_OK);
    ASSERT_EQ(number, info.classes_searched);
    const char* name = nullptr;
    ASSERT_EQ(lw_avatar_info_field(avatar, 6, &name, &number, &text), LW_OK);
    ASSERT_STREQ(name, "classes_searched");
    ASSERT_EQ(lw_avatar_info_find(avatar, "searched", &number, nullptr), LW_OK);  // search_interval (ABI 13)
    ASSERT_EQ(number, info.searched ? 1 : 0);
    if (info.active_class >= 0) {
      ASSERT_STREQ(lw_database_class_name(db, info.active_class), cdb.classes()[static_cast<std::size_t>(info.active_class)].c_str());
      ++recognised;
    }
    ASSERT_EQ(lw_avatar_pose(avatar, rot.data(), root.data(), nullptr, n), LW_OK);
    for (int j = 0; j < n; ++j) {
      const Quat& q = pose.rotations[static_cast<std::size_t>(j)];
      ASSERT_EQ(rot[4 * static_cast<std::size_t>(j)], q.w()) << "frame " << i << " joint " << j;
      ASSERT_EQ(rot[4 * static_cast<std::size_t>(j) + 3], q.z());
    }
    ASSERT_EQ(root[1], pose.translations[0].y());
  }
  EXPECT_EQ(recognised, f.count) << "two classes allowed: one is recognised on every frame";
  lw_avatar_destroy(avatar);
  lw_model_destroy(model);
  lw_database_destroy(db);
}

TEST(CApi, CombinedAvatarEqualsTheCppApiBitForBit) {
  lw_database* db = nullptr;
  ASSERT_EQ(lw_database_load(database_file().c_str(), &db), LW_OK) << lw_last_error();
  Frames f;
  ASSERT_EQ(lw_frames_from_bvh(sample("cmu/bvh/walking/07_02.bvh").c_str(), 90.0, 1, &f.data, &f.count), LW_OK) << lw_last_error();
  lw_accent_settings s;
  lw_accent_settings_default(&s);
  s.user_height = 1.7;
  lw_model* model = nullptr;
  ASSERT_EQ(lw_model_create_combined(db, &s, nullptr, &model), LW_OK) << lw_last_error();
  EXPECT_EQ(lw_model_method(model), LW_METHOD_COMBINED);
  lw_avatar* avatar = nullptr;
  ASSERT_EQ(lw_avatar_create(model, &avatar), LW_OK);
  ASSERT_EQ(lw_avatar_set_floor(avatar, f.data[0].devices[LW_LEFT_FOOT].position[1], f.data[0].devices[LW_RIGHT_FOOT].position[1]), LW_OK)
      << lw_last_error();

  const accent::Database cdb = accent::load_database(database_file());
  combined::Settings cs;
  cs.accent.user_height = 1.7;
  const combined::Model cm = combined::make_model(cdb, cs);
  combined::State st(cm);
  wip::set_floor(st.wip, f.data[0].devices[LW_LEFT_FOOT].position[1], f.data[0].devices[LW_RIGHT_FOOT].position[1]);
  Pose pose(cm.skeleton());
  const int32_t n = lw_skeleton_joint_count(lw_model_skeleton(model));
  std::vector<double> rot(4 * static_cast<std::size_t>(n));
  const io::BvhReadOptions o{.drop_first_frame = true};
  const auto frames = tracker_frames_from_motion(io::load_bvh(sample("cmu/bvh/walking/07_02.bvh"), o), 90.0);
  for (int32_t i = 0; i < f.count; ++i) {
    const lw_status a = lw_avatar_update(avatar, &f.data[i]);
    const UpdateStatus b = combined::update(cm, frames[static_cast<std::size_t>(i)], st, pose.ref());
    ASSERT_EQ(std::string(lw_status_name(a)), status_name(b));
    ASSERT_EQ(lw_avatar_pose(avatar, rot.data(), nullptr, nullptr, n), LW_OK);
    for (int j = 0; j < n; ++j) ASSERT_EQ(rot[4 * static_cast<std::size_t>(j) + 1], pose.rotations[static_cast<std::size_t>(j)].x());
  }
  EXPECT_EQ(st.legs_weight, 1.0) << "the trial's ankles drive the legs";
  lw_model* none = nullptr;
  EXPECT_EQ(lw_model_create_combined(nullptr, nullptr, nullptr, &none), LW_ERROR_INVALID_ARGUMENT);
  EXPECT_STREQ(lw_last_error(), "lw_model_create_combined: give a database or a skeleton, and out (not NULL)");
  lw_avatar_destroy(avatar);
  lw_model_destroy(model);
  lw_database_destroy(db);
}

TEST(CApi, IkAvatarPutsTheWristsOnTheControllers) {
  lw_skeleton* skel = nullptr;
  ASSERT_EQ(lw_skeleton_load_bvh(sample("cmu/bvh/walking/07_02.bvh").c_str(), &skel), LW_OK) << lw_last_error();
  lw_model* model = nullptr;
  ASSERT_EQ(lw_model_create_ik(skel, &model), LW_OK) << lw_last_error();
  lw_skeleton_destroy(skel);  // the model copied it
  lw_avatar* avatar = nullptr;
  ASSERT_EQ(lw_avatar_create(model, &avatar), LW_OK);
  Frames f;
  ASSERT_EQ(lw_frames_from_bvh(sample("cmu/bvh/walking/07_02.bvh").c_str(), 0, 1, &f.data, &f.count), LW_OK);
  const int32_t n = lw_skeleton_joint_count(lw_model_skeleton(model));
  const int wrist[2] = {humanoid_joint(model, "LeftHand"), humanoid_joint(model, "RightHand")};
  ASSERT_GE(wrist[0], 0);
  ASSERT_GE(wrist[1], 0);
  std::vector<double> world(3 * static_cast<std::size_t>(n));
  double worst = 0;
  for (int32_t i = 0; i < f.count; ++i) {
    ASSERT_GE(lw_avatar_update(avatar, &f.data[i]), 0);
    ASSERT_EQ(lw_avatar_pose(avatar, nullptr, nullptr, world.data(), n), LW_OK);
    for (int h = 0; h < 2; ++h) {
      const double* p = &world[3 * static_cast<std::size_t>(wrist[h])];
      const double* d = f.data[i].devices[1 + h].position;
      worst = std::max(worst, std::hypot(p[0] - d[0], p[1] - d[1], p[2] - d[2]));
    }
  }
  EXPECT_LT(worst, 0.01) << "a wrist missed its controller by " << worst << " m";
  lw_avatar_destroy(avatar);
  lw_model_destroy(model);
}

// Walking-in-place with the shipped learned depth mapping: the legs walk on
// a real walk's ankles, both feet swing in front of and behind the pelvis.
TEST(CApi, WipWithTheLearnedMappingWalksOnARealWalk) {
  lw_skeleton* skel = nullptr;
  ASSERT_EQ(lw_skeleton_load_bvh(sample("cmu/bvh/walking/05_01.bvh").c_str(), &skel), LW_OK) << lw_last_error();
  lw_model* model = nullptr;
  EXPECT_NE(lw_model_create_wip_learned(skel, sample("cmu/MANIFEST.tsv").c_str(), &model), LW_OK);
  EXPECT_NE(std::string(lw_last_error()).find("MANIFEST.tsv:1: not a learned walking-in-place mapping"), std::string::npos)
      << lw_last_error();
  EXPECT_EQ(lw_model_create_wip_learned(skel, nullptr, &model), LW_ERROR_INVALID_ARGUMENT);
  ASSERT_EQ(lw_model_create_wip_learned(skel, sample("wip/learned_mapping.txt").c_str(), &model), LW_OK) << lw_last_error();
  lw_skeleton_destroy(skel);
  lw_avatar* avatar = nullptr;
  ASSERT_EQ(lw_avatar_create(model, &avatar), LW_OK);
  Frames f;
  ASSERT_EQ(lw_frames_from_bvh(sample("cmu/bvh/walking/05_01.bvh").c_str(), 30, 1, &f.data, &f.count), LW_OK);
  const int32_t n = lw_skeleton_joint_count(lw_model_skeleton(model));
  const int foot[2] = {humanoid_joint(model, "LeftFoot"), humanoid_joint(model, "RightFoot")};
  const int hips = humanoid_joint(model, "Hips");
  ASSERT_GE(foot[0], 0);
  ASSERT_GE(foot[1], 0);
  ASSERT_GE(hips, 0);
  std::vector<double> world(3 * static_cast<std::size_t>(n));
  double lo = 0, hi = 0, root[3] = {0, 0, 0}, turn_peak = 0;
  for (int32_t i = 0; i < f.count; ++i) {
    ASSERT_GE(lw_avatar_update(avatar, &f.data[i]), 0);
    ASSERT_EQ(lw_avatar_pose(avatar, nullptr, root, world.data(), n), LW_OK);
    double turn = -1;
    ASSERT_EQ(lw_avatar_info_find(avatar, "turn_rate", &turn, nullptr), LW_OK) << lw_last_error();
    turn_peak = std::max(turn_peak, turn);
    for (int s = 0; s < 2; ++s) {
      // The foot's offset from the hips along the direction the root has travelled so far.
      const double dz = world[3 * static_cast<std::size_t>(foot[s]) + 2] - world[3 * static_cast<std::size_t>(hips) + 2];
      const double dx = world[3 * static_cast<std::size_t>(foot[s])] - world[3 * static_cast<std::size_t>(hips)];
      const double len = std::hypot(root[0], root[2]);
      if (len < 0.5) continue;
      const double along = (dx * root[0] + dz * root[2]) / len;
      lo = std::min(lo, along), hi = std::max(hi, along);
    }
  }
  EXPECT_GT(std::hypot(root[0], root[2]), 1.0);  // it walked
  // Its figures: walking, the distance walked (metres) and each foot's gait phase by name.
  double walked = 0, walking = 0;
  const char* phase = nullptr;
  ASSERT_EQ(lw_avatar_info_find(avatar, "distance", &walked, nullptr), LW_OK) << lw_last_error();
  EXPECT_GT(walked, 1.0);
  ASSERT_EQ(lw_avatar_info_find(avatar, "walking", &walking, nullptr), LW_OK);
  EXPECT_EQ(walking, 1.0);
  ASSERT_EQ(lw_avatar_info_find(avatar, "phase_left", nullptr, &phase), LW_OK);
  ASSERT_NE(phase, nullptr);
  EXPECT_GT(std::string(phase).size(), 3u) << phase;
  EXPECT_GT(turn_peak, 0.5);                     // 05_01 turns round: the head's turn rate (rad/s)
  EXPECT_LT(lo, -0.1);                           // a foot behind the hips
  EXPECT_GT(hi, 0.1);                            // and in front
  lw_avatar_destroy(avatar);
  lw_model_destroy(model);
}

// The combined avatar with the learned legs: its leg joints differ from the
// document's mapping on the same real walk, its upper body does not.
// The step detector through lw_wip_settings: on a real walk the adaptive
// detector lifts the avatar's left foot earlier than the document's
// thresholds; defaults equal lw_model_create_wip; a bad value is refused, named.
TEST(CApi, WipStepDetectorIsASetting) {
  lw_skeleton* skel = nullptr;
  ASSERT_EQ(lw_skeleton_load_bvh(sample("cmu/bvh/walking/05_01.bvh").c_str(), &skel), LW_OK) << lw_last_error();
  Frames f;
  ASSERT_EQ(lw_frames_from_bvh(sample("cmu/bvh/walking/05_01.bvh").c_str(), 30, 1, &f.data, &f.count), LW_OK);
  lw_wip_settings settings;
  lw_wip_settings_default(&settings);
  EXPECT_EQ(settings.detector, LW_WIP_DETECTOR_DEFAULT);
  EXPECT_EQ(settings.table_path, nullptr);
  settings.detector = 7;
  lw_model* model = nullptr;
  EXPECT_EQ(lw_model_create_wip_with(skel, &settings, &model), LW_ERROR_INVALID_ARGUMENT);
  EXPECT_STREQ(lw_last_error(), "lw_model_create_wip_with: detector must be 0 (default), 1 (document) or 2 (adaptive), got 7");
  // First frame where the left foot is 2 cm above where it stood, per model.
  auto first_lift = [&](lw_model* m) {
    lw_avatar* avatar = nullptr;
    EXPECT_EQ(lw_avatar_create(m, &avatar), LW_OK);
    const int32_t n = lw_skeleton_joint_count(lw_model_skeleton(m));
    const int foot = humanoid_joint(m, "LeftFoot");
    std::vector<double> world(3 * static_cast<std::size_t>(n));
    double rest = NAN;
    int lift = -1;
    for (int32_t i = 0; i < f.count && lift < 0; ++i) {
      EXPECT_GE(lw_avatar_update(avatar, &f.data[i]), 0);
      EXPECT_EQ(lw_avatar_pose(avatar, nullptr, nullptr, world.data(), n), LW_OK);
      const double y = world[3 * static_cast<std::size_t>(foot) + 1];
      if (i == 0) rest = y;
      else if (y > rest + 0.02) lift = i;
    }
    lw_avatar_destroy(avatar);
    lw_model_destroy(m);
    return lift;
  };
  int lift[3];
  for (int d = 0; d < 3; ++d) {
    settings.detector = d;
    ASSERT_EQ(lw_model_create_wip_with(skel, &settings, &model), LW_OK) << lw_last_error();
    lift[d] = first_lift(model);
  }
  ASSERT_EQ(lw_model_create_wip(skel, &model), LW_OK);
  EXPECT_EQ(first_lift(model), lift[LW_WIP_DETECTOR_DEFAULT]);
  lw_skeleton_destroy(skel);
  ASSERT_GT(lift[LW_WIP_DETECTOR_DOCUMENT], 0) << "the document's detector never lifted the foot";
  ASSERT_GT(lift[LW_WIP_DETECTOR_ADAPTIVE], 0) << "the adaptive detector never lifted the foot";
  EXPECT_LT(lift[LW_WIP_DETECTOR_ADAPTIVE], lift[LW_WIP_DETECTOR_DOCUMENT]);
}

TEST(CApi, CombinedWithTheLearnedMappingMovesOnlyTheLegsOtherwise) {
  lw_skeleton* skel = nullptr;
  ASSERT_EQ(lw_skeleton_load_bvh(sample("cmu/bvh/walking/05_01.bvh").c_str(), &skel), LW_OK) << lw_last_error();
  lw_model* models[2] = {nullptr, nullptr};
  lw_model* none = nullptr;
  EXPECT_EQ(lw_model_create_combined_learned(nullptr, nullptr, skel, nullptr, &none), LW_ERROR_INVALID_ARGUMENT);
  EXPECT_STREQ(lw_last_error(), "lw_model_create_combined_learned: give a database or a skeleton, table_path and out (not NULL)");
  EXPECT_NE(lw_model_create_combined_learned(nullptr, nullptr, skel, sample("cmu/MANIFEST.tsv").c_str(), &none), LW_OK);
  EXPECT_NE(std::string(lw_last_error()).find("MANIFEST.tsv:1: not a learned walking-in-place mapping"), std::string::npos)
      << lw_last_error();
  ASSERT_EQ(lw_model_create_combined(nullptr, nullptr, skel, &models[0]), LW_OK) << lw_last_error();
  ASSERT_EQ(lw_model_create_combined_learned(nullptr, nullptr, skel, sample("wip/learned_mapping.txt").c_str(), &models[1]), LW_OK)
      << lw_last_error();
  lw_skeleton_destroy(skel);
  Frames f;
  ASSERT_EQ(lw_frames_from_bvh(sample("cmu/bvh/walking/05_01.bvh").c_str(), 30, 1, &f.data, &f.count), LW_OK);
  const int32_t n = lw_skeleton_joint_count(lw_model_skeleton(models[0]));
  const int foot = humanoid_joint(models[0], "LeftFoot"), hand = humanoid_joint(models[0], "LeftHand");
  ASSERT_GE(foot, 0);
  ASSERT_GE(hand, 0);
  std::vector<double> world[2] = {std::vector<double>(3 * static_cast<std::size_t>(n)), std::vector<double>(3 * static_cast<std::size_t>(n))};
  lw_avatar* avatars[2] = {nullptr, nullptr};
  for (int k = 0; k < 2; ++k) ASSERT_EQ(lw_avatar_create(models[k], &avatars[k]), LW_OK);
  double foot_apart = 0, hand_apart = 0;
  for (int32_t i = 0; i < f.count; ++i)
    for (int k = 0; k < 2; ++k) {
      ASSERT_GE(lw_avatar_update(avatars[k], &f.data[i]), 0);
      ASSERT_EQ(lw_avatar_pose(avatars[k], nullptr, nullptr, world[k].data(), n), LW_OK);
      if (k == 1) {
        auto apart = [&](int j) {
          const auto at = 3 * static_cast<std::size_t>(j);
          return std::hypot(world[0][at] - world[1][at], world[0][at + 1] - world[1][at + 1], world[0][at + 2] - world[1][at + 2]);
        };
        foot_apart = std::max(foot_apart, apart(foot));
        hand_apart = std::max(hand_apart, apart(hand));
      }
    }
  EXPECT_GT(foot_apart, 0.02);
  EXPECT_LT(hand_apart, 1e-9);  // the upper body is the IK avatar's in both
  for (int k = 0; k < 2; ++k) {
    lw_avatar_destroy(avatars[k]);
    lw_model_destroy(models[k]);
  }
}

// The walker's root through the C API: smooth by default (even speed), the
// pivoting root on request (lunges and stalls), bad settings named.
TEST(CApi, WalkerRootIsSmoothByDefaultAndPivotOnRequest) {
  const std::string walk = sample("walks/normal.json");
  lw_walker_settings s;
  lw_walker_settings_default(&s);
  EXPECT_EQ(s.root, LW_WALKER_ROOT_SMOOTH);
  lw_model* models[2] = {nullptr, nullptr};
  ASSERT_EQ(lw_model_create_walker_with_settings(walk.c_str(), &s, &models[0]), LW_OK) << lw_last_error();
  s.root = LW_WALKER_ROOT_PIVOT;
  ASSERT_EQ(lw_model_create_walker_with_settings(walk.c_str(), &s, &models[1]), LW_OK) << lw_last_error();
  double spread[2] = {0, 0};  // (max - min) / mean of the root's horizontal speed after the first second
  for (int k = 0; k < 2; ++k) {
    lw_avatar* avatar = nullptr;
    ASSERT_EQ(lw_avatar_create(models[k], &avatar), LW_OK);
    lw_frame f{};
    f.devices[LW_HEAD] = {{0, 1.7, 0}, {1, 0, 0, 0}, 1};
    double prev[3] = {0, 0, 0}, lo = 1e9, hi = 0, sum = 0;
    int n = 0;
    for (int i = 0; i < 180; ++i) {
      f.time = i / 30.0;
      ASSERT_EQ(lw_avatar_update(avatar, &f), LW_OK);
      double root[3];
      ASSERT_EQ(lw_avatar_pose(avatar, nullptr, root, nullptr, 0), LW_OK);
      const double speed = std::hypot(root[0] - prev[0], root[2] - prev[2]) * 30.0;
      if (i > 30) lo = std::min(lo, speed), hi = std::max(hi, speed), sum += speed, ++n;
      std::copy(root, root + 3, prev);
    }
    spread[k] = (hi - lo) / (sum / n);
    lw_avatar_destroy(avatar);
    lw_model_destroy(models[k]);
  }
  std::printf("[capi] walker root speed spread: smooth %.3f, pivot %.3f of the mean\n", spread[0], spread[1]);
  EXPECT_LT(spread[0], 0.4);  // within +-20 %
  EXPECT_GT(spread[1], 0.4);
  lw_model* bad = nullptr;
  s.root = 7;
  EXPECT_EQ(lw_model_create_walker_with_settings(walk.c_str(), &s, &bad), LW_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(lw_last_error()).find("root must be LW_WALKER_ROOT_SMOOTH (0) or LW_WALKER_ROOT_PIVOT (1), got 7"),
            std::string::npos) << lw_last_error();
  lw_walker_settings_default(&s);
  s.soft_reach = 0;
  EXPECT_EQ(lw_model_create_walker_with_settings(walk.c_str(), &s, &bad), LW_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(lw_last_error()).find("soft_reach must be in (0, 1]"), std::string::npos) << lw_last_error();
  EXPECT_EQ(bad, nullptr);
}

// The walker with settings `s` for `frames` frames at 30 Hz (the head still: the walker walks
// straight ahead on its own); the root at the first and the last frame.
struct WalkerRun {
  double first[3] = {0, 0, 0}, last[3] = {0, 0, 0};
};
WalkerRun walk_straight(const std::string& walk, const lw_walker_settings& s, int frames) {
  WalkerRun r;
  lw_model* model = nullptr;
  if (lw_model_create_walker_with_settings(walk.c_str(), &s, &model) != LW_OK) {
    ADD_FAILURE() << lw_last_error();
    return r;
  }
  lw_avatar* avatar = nullptr;
  EXPECT_EQ(lw_avatar_create(model, &avatar), LW_OK);
  lw_frame f{};
  f.devices[LW_HEAD] = {{0, 1.7, 0}, {1, 0, 0, 0}, 1};
  for (int i = 0; i < frames; ++i) {
    f.time = i / 30.0;
    EXPECT_EQ(lw_avatar_update(avatar, &f), LW_OK);
    EXPECT_EQ(lw_avatar_pose(avatar, nullptr, r.last, nullptr, 0), LW_OK);
    if (i == 0) std::copy(r.last, r.last + 3, r.first);
  }
  lw_avatar_destroy(avatar);
  lw_model_destroy(model);
  return r;
}

// The walker on a ground given through the C API (the JSON of a path file's
// "ground"): up a 10 % slope the root rises with the ground (as high above it
// at the end as at the start, within the step's bob); a bad or stairs ground
// is refused naming the field.
TEST(CApi, WalkerWalksTheGroundItIsGiven) {
  const std::string walk = sample("walks/normal.json");
  lw_walker_settings s;
  lw_walker_settings_default(&s);
  EXPECT_EQ(s.ground_json, nullptr);
  s.ground_json = R"({"slope": {"origin": [0, 0.5], "direction": [0, 1], "grade": 0.1}})";
  const WalkerRun run = walk_straight(walk, s, 150);
  const double* first = run.first;
  const double* root = run.last;
  const double ground_end = 0.1 * std::max(0.0, root[2] - 0.5);
  std::printf("[capi] walker up a 10 %% slope: root %.3f m above the ground at the start, %.3f m at the end (z %.2f m)\n", first[1],
              root[1] - ground_end, root[2]);
  EXPECT_GT(root[2], 4.0);  // walked up the slope
  // (The pelvis follows the lower foot: up to half a stride's rise, 36 mm, below the feet's mean.)
  EXPECT_NEAR(root[1] - ground_end, first[1], 0.1 * 0.36 + 0.01);
  lw_model* bad = nullptr;
  s.ground_json = R"({"slope": {"origin": [0, 0.5], "direction": [0, 1], "grade": 0.5}})";
  EXPECT_EQ(lw_model_create_walker_with_settings(walk.c_str(), &s, &bad), LW_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(lw_last_error()).find("lw_walker_settings.ground_json: slope: grade"), std::string::npos) << lw_last_error();
  s.ground_json = R"({"stairs": {"origin": [0, 1], "direction": [0, 1], "rise": 0.15, "run": 0.1, "count": 3}})";
  EXPECT_EQ(lw_model_create_walker_with_settings(walk.c_str(), &s, &bad), LW_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(lw_last_error()).find("lw_walker_settings.ground_json: stairs: run"), std::string::npos) << lw_last_error();
  EXPECT_EQ(bad, nullptr);
}

// Stairs through the C API (the shipped stairs.json's ground: 5 x 0.15 m from
// z = 1.5 m): the walker climbs them, ending on the landing as high above it
// as it started above the floor, no foot joint below a tread.
TEST(CApi, WalkerClimbsStairs) {
  const std::string walk = sample("walks/normal.json");
  lw_walker_settings s;
  lw_walker_settings_default(&s);
  s.ground_json = R"({"stairs": {"origin": [0, 1.5], "direction": [0, 1], "rise": 0.15, "run": 0.36, "count": 5}})";
  const WalkerRun run = walk_straight(walk, s, 150);
  std::printf("[capi] walker up the stairs: root %.3f m above the floor at the start, %.3f m above the landing at z %.2f m\n",
              run.first[1], run.last[1] - 0.75, run.last[2]);
  EXPECT_GT(run.last[2], 1.5 + 5 * 0.36);  // past the last riser
  EXPECT_NEAR(run.last[1] - 0.75, run.first[1], 0.03);
  // The stairs cadence reaches the walker: slower on the flight, less ground covered in the same time.
  EXPECT_EQ(s.stairs_cadence, 0.8);
  s.stairs_cadence = 1.0;
  const double at_1 = walk_straight(walk, s, 150).last[2];
  s.stairs_cadence = 0.5;
  const double at_half = walk_straight(walk, s, 150).last[2];
  std::printf("[capi] 5 s toward the stairs: z %.2f m at cadence 1, %.2f m at 0.5\n", at_1, at_half);
  EXPECT_LT(at_half, at_1 - 0.3);
  s.stairs_cadence = 0;
  lw_model* bad = nullptr;
  EXPECT_EQ(lw_model_create_walker_with_settings(walk.c_str(), &s, &bad), LW_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(lw_last_error()).find("stairs_cadence must be in (0, 1]"), std::string::npos) << lw_last_error();
  EXPECT_EQ(bad, nullptr);
}

TEST(CApi, BadInputGivesAStatusAndAMessage) {
  lw_database* db = nullptr;
  EXPECT_EQ(lw_database_load(nullptr, &db), LW_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(lw_last_error()).find("must not be NULL"), std::string::npos);
  EXPECT_EQ(lw_database_load(sample("cmu/MANIFEST.tsv").c_str(), &db), LW_ERROR_FORMAT);
  EXPECT_NE(std::string(lw_last_error()).find("not a legwork accent database"), std::string::npos) << lw_last_error();
  EXPECT_EQ(db, nullptr);
  EXPECT_EQ(lw_database_load("/nonexistent/x.lwdb", &db), LW_ERROR_IO) << lw_last_error();
  ASSERT_EQ(lw_database_load(database_file().c_str(), &db), LW_OK);
  lw_accent_settings s;
  lw_accent_settings_default(&s);
  s.classes = "dancing";
  lw_model* model = nullptr;
  EXPECT_EQ(lw_model_create_accent(db, &s, &model), LW_ERROR_FORMAT);
  EXPECT_NE(std::string(lw_last_error()).find("class 'dancing' is not in the database"), std::string::npos) << lw_last_error();
  s.classes = nullptr;
  EXPECT_EQ(s.recognize_class, 1);  // the engine's default: recognise the class when several are allowed
  s.recognize_class = 2;
  EXPECT_EQ(lw_model_create_accent(db, &s, &model), LW_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(lw_last_error()).find("recognize_class must be 0 or 1, got 2"), std::string::npos) << lw_last_error();
  s.recognize_class = 0;
  EXPECT_DOUBLE_EQ(s.foot_lift_height, legwork::accent::Settings{}.foot_lift_height);  // ABI 3: the engine's default
  s.foot_lift_height = 0.9;
  EXPECT_NE(lw_model_create_accent(db, &s, &model), LW_OK);
  EXPECT_NE(std::string(lw_last_error()).find("foot_lift_height must be between 0 and 0.5 metres"), std::string::npos) << lw_last_error();
  s.foot_lift_height = 0.1;
  EXPECT_DOUBLE_EQ(s.foot_lock_slack, legwork::accent::Settings{}.foot_lock_slack);  // ABI 4: the engine's defaults
  EXPECT_DOUBLE_EQ(s.foot_swing_speed, legwork::accent::Settings{}.foot_swing_speed);
  s.foot_lock_slack = 2;
  EXPECT_NE(lw_model_create_accent(db, &s, &model), LW_OK);
  EXPECT_NE(std::string(lw_last_error()).find("foot_lock_slack must be between 0 and 1 metre"), std::string::npos) << lw_last_error();
  s.foot_lock_slack = 0.05;
  s.foot_swing_speed = -1;
  EXPECT_NE(lw_model_create_accent(db, &s, &model), LW_OK);
  EXPECT_NE(std::string(lw_last_error()).find("foot_swing_speed must be between 0 and 10 m/s"), std::string::npos) << lw_last_error();
  s.foot_swing_speed = 0.8;
  EXPECT_DOUBLE_EQ(s.travel_weight, legwork::accent::Settings{}.travel_weight);  // ABI 6: the engine's default
  s.travel_weight = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(lw_model_create_accent(db, &s, &model), LW_OK);
  EXPECT_NE(std::string(lw_last_error()).find("travel_weight must be between 0 and 100 (0 = off)"), std::string::npos) << lw_last_error();
  s.travel_weight = 0;
  EXPECT_DOUBLE_EQ(s.max_head_height_diff, legwork::accent::Settings{}.max_head_height_diff);  // ABI 7: the engine's default
  s.max_head_height_diff = 2.5;
  EXPECT_NE(lw_model_create_accent(db, &s, &model), LW_OK);
  EXPECT_NE(std::string(lw_last_error()).find("max_head_height_diff must be between 0 and 2"), std::string::npos) << lw_last_error();
  s.max_head_height_diff = 0.2;
  EXPECT_DOUBLE_EQ(s.smooth_feedforward, legwork::accent::Settings{}.smooth_feedforward);  // ABI 8: the engine's default
  s.smooth_feedforward = -0.5;
  EXPECT_NE(lw_model_create_accent(db, &s, &model), LW_OK);
  EXPECT_NE(std::string(lw_last_error()).find("smooth_feedforward must be between 0 and 1"), std::string::npos) << lw_last_error();
  s.smooth_feedforward = 0.5;
  EXPECT_DOUBLE_EQ(s.lying_root_smoothing, legwork::accent::Settings{}.lying_root_smoothing);  // ABI 9: the engine's default
  s.lying_root_smoothing = 25;
  EXPECT_NE(lw_model_create_accent(db, &s, &model), LW_OK);
  EXPECT_NE(std::string(lw_last_error()).find("lying_root_smoothing must be between 1 and 20"), std::string::npos) << lw_last_error();
  s.lying_root_smoothing = 2;
  EXPECT_DOUBLE_EQ(s.lying_crown, legwork::accent::Settings{}.lying_crown);  // ABI 10: the engine's default
  s.lying_crown = 1.5;
  EXPECT_NE(lw_model_create_accent(db, &s, &model), LW_OK);
  EXPECT_NE(std::string(lw_last_error()).find("lying_crown must be between 0 and 1"), std::string::npos) << lw_last_error();
  s.lying_crown = 0.5;
  EXPECT_DOUBLE_EQ(s.other_class_cost, legwork::accent::Settings{}.other_class_cost);  // ABI 11: the engine's default
  s.other_class_cost = 0.5;
  EXPECT_NE(lw_model_create_accent(db, &s, &model), LW_OK);
  EXPECT_NE(std::string(lw_last_error()).find("other_class_cost must be 0 (search only the classes to match) or a factor from 1 to 1e6"),
            std::string::npos)
      << lw_last_error();
  s.other_class_cost = 0;
  EXPECT_DOUBLE_EQ(s.search_interval, legwork::accent::Settings{}.search_interval);  // ABI 13: the engine's default
  s.search_interval = -0.1;
  EXPECT_NE(lw_model_create_accent(db, &s, &model), LW_OK);
  EXPECT_NE(std::string(lw_last_error()).find("search_interval must be between 0 and 1 second (0 = search every frame)"),
            std::string::npos)
      << lw_last_error();
  s.search_interval = 0;
  EXPECT_EQ(s.floor, 1);  // ABI 14: the engine's defaults
  EXPECT_DOUBLE_EQ(s.floor_height, legwork::accent::Settings{}.floor_height);
  s.floor = 2;
  EXPECT_NE(lw_model_create_accent(db, &s, &model), LW_OK);
  EXPECT_NE(std::string(lw_last_error()).find("floor must be 0 or 1, got 2"), std::string::npos) << lw_last_error();
  s.floor = 0;
  s.floor_height = 11;
  EXPECT_NE(lw_model_create_accent(db, &s, &model), LW_OK);
  EXPECT_NE(std::string(lw_last_error()).find("floor_height must be between -10 and 10 metres"), std::string::npos)
      << lw_last_error();
  s.floor_height = -0.2;
  EXPECT_DOUBLE_EQ(s.foot_lock_hold_seconds, legwork::accent::Settings{}.foot_lock_hold_seconds);  // ABI 15: the engine's default
  s.foot_lock_hold_seconds = -0.1;
  EXPECT_NE(lw_model_create_accent(db, &s, &model), LW_OK);
  EXPECT_NE(std::string(lw_last_error()).find("foot_lock_hold_seconds must be between 0 and 10 s"), std::string::npos)
      << lw_last_error();
  s.foot_lock_hold_seconds = 0.3;
  EXPECT_EQ(lw_model_create_accent(db, &s, &model), LW_OK) << lw_last_error();
  lw_model_destroy(model);
  model = nullptr;
  s.recognize_class = 1;
  s.k = 99;
  EXPECT_EQ(lw_model_create_accent(db, &s, &model), LW_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(lw_last_error()).find("k must be 1..32, got 99"), std::string::npos) << lw_last_error();
  lw_accent_settings_default(&s);
  ASSERT_EQ(lw_model_create_accent(db, &s, &model), LW_OK);
  lw_avatar* avatar = nullptr;
  ASSERT_EQ(lw_avatar_create(model, &avatar), LW_OK);
  EXPECT_EQ(lw_avatar_update(avatar, nullptr), LW_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(lw_avatar_update(nullptr, nullptr), LW_ERROR_INVALID_ARGUMENT);
  lw_frame nan_frame{};
  nan_frame.time = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(lw_avatar_update(avatar, &nan_frame), LW_REJECTED);
  // Its figures: none until a frame is consumed; a field out of range or unknown is named.
  EXPECT_EQ(lw_avatar_info_count(avatar), 0);
  EXPECT_EQ(lw_avatar_info_count(nullptr), 0);
  double number = 0;
  EXPECT_EQ(lw_avatar_info_find(avatar, "match", &number, nullptr), LW_ERROR_INVALID_ARGUMENT);
  EXPECT_STREQ(lw_last_error(), "lw_avatar_info_find: no field 'match' (no frame consumed yet since the avatar's creation or reset)");
  EXPECT_EQ(lw_avatar_info_field(avatar, 0, nullptr, &number, nullptr), LW_ERROR_INVALID_ARGUMENT);
  EXPECT_STREQ(lw_last_error(), "lw_avatar_info_field: field 0 of 0 (lw_avatar_info_count)");
  EXPECT_EQ(lw_avatar_info_find(avatar, nullptr, &number, nullptr), LW_ERROR_INVALID_ARGUMENT);
  EXPECT_STREQ(lw_last_error(), "lw_avatar_info_find: avatar and name must not be NULL");
  double rot[8];
  EXPECT_EQ(lw_avatar_pose(avatar, rot, nullptr, nullptr, 2), LW_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(lw_last_error()).find("capacity 2 <"), std::string::npos);
  EXPECT_EQ(lw_avatar_set_floor(avatar, 0, 0), LW_ERROR_UNSUPPORTED);
  EXPECT_EQ(lw_convert_positions(static_cast<lw_engine>(9), 1, rot, 1), LW_ERROR_INVALID_ARGUMENT);
  lw_avatar_destroy(avatar);
  lw_model_destroy(model);
  lw_database_destroy(db);
  lw_avatar_destroy(nullptr);  // destroying NULL is a no-op
}

TEST(CApi, EngineConversionsMatchTheDocumentedFormulas) {
  double p[3] = {0.1, 1.6, 0.3};
  ASSERT_EQ(lw_convert_positions(LW_ENGINE_UNREAL, 1, p, 1), LW_OK);
  EXPECT_DOUBLE_EQ(p[0], 30.0);
  EXPECT_DOUBLE_EQ(p[1], -10.0);
  EXPECT_DOUBLE_EQ(p[2], 160.0);
  ASSERT_EQ(lw_convert_positions(LW_ENGINE_UNREAL, 0, p, 1), LW_OK);
  EXPECT_NEAR(p[0], 0.1, 1e-12);
  double q[4] = {0.9, 0.1, 0.2, 0.3};
  ASSERT_EQ(lw_convert_rotations(LW_ENGINE_UNITY, 1, q, 1), LW_OK);
  EXPECT_DOUBLE_EQ(q[2], -0.2);
  EXPECT_DOUBLE_EQ(q[3], -0.3);
}

TEST(CApi, CallerAllocatorSeesEveryHandle) {
  static long live = 0, total = 0;
  lw_allocator a{[](std::size_t size, std::size_t align, void*) -> void* {
                   ++live, ++total;
                   return std::aligned_alloc(align, (size + align - 1) / align * align);
                 },
                 [](void* p, void*) {
                   --live;
                   std::free(p);
                 },
                 nullptr};
  ASSERT_EQ(lw_set_allocator(&a), LW_OK);
  lw_skeleton* skel = nullptr;
  ASSERT_EQ(lw_skeleton_load_bvh(sample("cmu/bvh/walking/07_01.bvh").c_str(), &skel), LW_OK);
  lw_model* model = nullptr;
  ASSERT_EQ(lw_model_create_ik(skel, &model), LW_OK);
  lw_avatar* avatar = nullptr;
  ASSERT_EQ(lw_avatar_create(model, &avatar), LW_OK);
  EXPECT_EQ(live, 3);
  lw_avatar_destroy(avatar);
  lw_model_destroy(model);
  lw_skeleton_destroy(skel);
  EXPECT_EQ(live, 0);
  EXPECT_EQ(total, 3);
  lw_allocator bad{nullptr, nullptr, nullptr};
  EXPECT_EQ(lw_set_allocator(&bad), LW_ERROR_INVALID_ARGUMENT);
  ASSERT_EQ(lw_set_allocator(nullptr), LW_OK);
}

}  // namespace
}  // namespace legwork

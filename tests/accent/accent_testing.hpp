#pragma once
// Shared helpers for the accent tests: sample trials from the repo's data/cmu.
#include <legwork/accent/accent.hpp>
#include <legwork/accent/offline/builder.hpp>
#include <legwork/accent/offline/run.hpp>
#include <legwork/core/fk.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/core/measure.hpp>
#include <legwork/io/bvh.hpp>

#include "testdata.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <filesystem>
#include <string>
#include <vector>

namespace legwork::accent::testing {

// A trial of the repo's sample data ("walking/07_01"), T-pose dropped.
inline TrialInput sample_trial(const std::string& cls_slash_name) {
  io::BvhReadOptions opt;
  opt.drop_first_frame = true;
  const auto slash = cls_slash_name.find('/');
  const std::string cls = cls_slash_name.substr(0, slash), name = cls_slash_name.substr(slash + 1);
  const std::string dir = cls == "climbing_ladder" ? "cmu/bvh_daz/" : "cmu/bvh/";
  TrialInput t;
  t.file = cls_slash_name + ".bvh";
  t.cls = cls;
  t.motion = io::load_bvh(testdata::sample(dir + cls_slash_name + ".bvh").string(), opt);
  return t;
}

inline std::vector<TrialInput> sample_trials(const std::vector<std::string>& names) {
  std::vector<TrialInput> out;
  for (const auto& n : names) out.push_back(sample_trial(n));
  return out;
}

// A database over sample trials with its KD-trees built, as searches need it.
inline Database indexed_database(const std::vector<std::string>& names, const BuildConfig& cfg = {},
                                 BuildReport* report = nullptr) {
  Database db = build_database(sample_trials(names), cfg, report);
  db.build_index();
  return db;
}

// A sample trial at the 90 Hz tracker rate the accentuator runs at.
inline Motion tracker_rate_trial(const std::string& cls_slash_name) {
  return resample(sample_trial(cls_slash_name).motion, 90.0);
}

// A shared-data trial file (full path) as the evaluation reads it: its first
// frame (the T-pose) dropped, resampled to `fps` (the 90 Hz tracker rate).
inline Motion shared_trial(const std::string& file, double fps = 90.0) {
  io::BvhReadOptions opt;
  opt.drop_first_frame = true;
  return resample(io::load_bvh(file, opt), fps);
}

// Ankles near the floor: horizontal slide (metres) summed over the frame
// pairs, among the first `frames` frames, in which an ankle stays within 3 cm
// of its own floor level (its 5th-percentile height over the whole clip), and
// the number of such pairs. metres / pairs is the evaluation's foot skating on
// the ankles.
struct FloorSlide {
  double metres = 0;
  long pairs = 0;
  double per_pair() const { return pairs ? metres / static_cast<double>(pairs) : 0.0; }
};
inline FloorSlide ankle_floor_slide(const Motion& m, int frames = std::numeric_limits<int>::max()) {
  FloorSlide out;
  const int n = m.frame_count();
  std::vector<std::array<Vec3, 2>> p(static_cast<std::size_t>(n));
  for (int f = 0; f < n; ++f) {
    const auto all = joint_positions(m.skeleton, m.frame(f));
    p[static_cast<std::size_t>(f)] = {all[static_cast<std::size_t>(m.skeleton.roles[Role::LeftAnkle])],
                                      all[static_cast<std::size_t>(m.skeleton.roles[Role::RightAnkle])]};
  }
  for (std::size_t a = 0; a < 2; ++a) {
    std::vector<double> h;
    for (const auto& x : p) h.push_back(x[a].y());
    if (h.empty()) continue;
    std::nth_element(h.begin(), h.begin() + static_cast<std::ptrdiff_t>(h.size() / 20), h.end());
    const double band = h[h.size() / 20] + 0.03;
    for (int f = 0; f + 1 < n && f < frames; ++f) {
      const auto fu = static_cast<std::size_t>(f);
      if (p[fu][a].y() >= band || p[fu + 1][a].y() >= band) continue;
      out.metres += std::hypot(p[fu + 1][a].x() - p[fu][a].x(), p[fu + 1][a].z() - p[fu][a].z());
      ++out.pairs;
    }
  }
  return out;
}

// A cross-subject fold of the shared data (data = its folder): the database
// of class `cls` without any trial of `subject` ("126": files 126_*.bvh),
// its search index built, and that subject's trial files (full paths, sorted).
struct SubjectFold {
  Database db;
  std::vector<std::string> held_out;
};
inline SubjectFold subject_fold(const std::string& data, const std::string& cls, const std::string& subject) {
  SubjectFold f;
  std::vector<std::string> exclude;
  for (const auto& e : std::filesystem::directory_iterator(data + "/bvh/" + cls))
    if (e.path().filename().string().rfind(subject + "_", 0) == 0) {
      exclude.push_back("bvh/" + cls + "/" + e.path().filename().string());
      f.held_out.push_back(e.path().string());
    }
  std::sort(f.held_out.begin(), f.held_out.end());
  f.db = build_database(load_trials(data, {cls}, exclude), BuildConfig{});
  f.db.build_index();
  return f;
}

// One avatar through the runtime contract (model + state + pose buffer), so
// tests read like the old one-object use: avatar.update(frame), avatar.pose.
inline Settings for_user(const Motion& user) {
  Settings s;
  s.user_height = measure_body(user.skeleton).standing_height;
  return s;
}

struct Avatar {
  Model model;
  State state;
  Pose pose;
  Avatar(const Database& db, const Settings& s) : model(make_model(db, s)), state(model), pose(model.neutral()) {}
  // The default settings for a user of `user`'s standing height (as the
  // evaluation sets it for a held-out trial).
  Avatar(const Database& db, const Motion& user) : Avatar(db, for_user(user)) {}
  Info update(const TrackerFrame& f) {
    Info info;
    last_status = accent::update(model, f, state, pose.ref(), &info);
    if (recorded < output.frame_count()) output.set_frame(recorded++, pose);
    return info;
  }
  // Keeps the pose after each of the next `frames` updates in `output` (at
  // `fps`): frame by frame what accentuate() returns for the same frames, so
  // a test that walks the avatar needs no second run for the body.
  void record(int frames, double fps) {
    output = Motion(model.skeleton(), fps, frames);
    recorded = 0;
  }
  Motion output;
  int recorded = 0;
  std::span<const Match> matches(int hand) const { return last_matches(state, hand); }
  const Feature& live_feature(int hand) const { return state.live[static_cast<std::size_t>(hand)]; }
  const Skeleton& skeleton() const { return model.skeleton(); }
  UpdateStatus last_status = UpdateStatus::Ok;
};

}  // namespace legwork::accent::testing

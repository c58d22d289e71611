#pragma once
// Shared by the fuzz targets that end in a body: the repo's sample CMU
// skeleton (data/cmu/bvh/walking/07_01.bvh, loaded once) and a full-body IK
// avatar that every decoded TrackerFrame drives, so a parsed-but-absurd frame
// reaches a per-frame update, whose output must stay finite.
#include <legwork/core/tracker.hpp>
#include <legwork/ik/full_body.hpp>
#include <legwork/io/bvh.hpp>

#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace legwork::fuzz {

// The first `count` frames of a repo sample trial (path under data/, first
// frame dropped) as trackers at `rate` Hz: the streams the targets replay.
// (tracker_frames_from_motion's max_frames is a limit that throws, not a cut:
// accent_db_fuzz passed 12 there, so its stream threw and the Error, caught
// with the reader's, kept every input from reaching accent::update.)
inline std::vector<TrackerFrame> sample_frames(const char* trial, double rate, std::size_t count) {
  io::BvhReadOptions o;
  o.drop_first_frame = true;
  auto all = tracker_frames_from_motion(io::load_bvh(std::string(LEGWORK_SOURCE_DIR) + "/data/" + trial, o), rate);
  if (all.size() > count) all.resize(count);
  return all;
}

inline const Skeleton& sample_skeleton() {
  static const Skeleton s = [] {
    io::BvhReadOptions o;
    o.drop_first_frame = true;
    return io::load_bvh(std::string(LEGWORK_SOURCE_DIR) + "/data/cmu/bvh/walking/07_01.bvh", o).skeleton;
  }();
  return s;
}

// One IK avatar, back to a new stream for every fuzz input (reset()).
class IkAvatar {
 public:
  IkAvatar() : model_(ik::make_model(sample_skeleton())), state_(model_), pose_(model_.skeleton()), before_(pose_) {}
  void restart() { ik::reset(model_, state_); }
  const Pose& pose() const { return pose_; }
  const Skeleton& skeleton() const { return model_.skeleton(); }
  // Any frame: the pose stays finite and a Rejected frame leaves it untouched.
  UpdateStatus drive(const TrackerFrame& f) {
    before_ = pose_;  // same sizes: no allocation per frame (vmc_fuzz drives one per packet)
    const UpdateStatus s = ik::update(model_, f, state_, pose_.ref());
    if (s == UpdateStatus::Rejected && !same(before_, pose_)) std::abort();
    for (std::size_t j = 0; j < pose_.rotations.size(); ++j)
      if (!pose_.rotations[j].coeffs().allFinite() || !pose_.translations[j].allFinite()) std::abort();
    return s;
  }

 private:
  static bool same(const Pose& a, const Pose& b) {
    for (std::size_t j = 0; j < a.rotations.size(); ++j)
      if (std::memcmp(a.rotations[j].coeffs().data(), b.rotations[j].coeffs().data(), 4 * sizeof(double)) != 0 ||
          std::memcmp(a.translations[j].data(), b.translations[j].data(), 3 * sizeof(double)) != 0)
        return false;
    return true;
  }
  ik::Model model_;
  ik::State state_;
  Pose pose_;
  Pose before_;  // the pose before the last drive()
};

}  // namespace legwork::fuzz

#include <legwork/core/motion.hpp>

#include <algorithm>

namespace legwork {

Pose::Pose(const Skeleton& skel)
    : rotations(static_cast<std::size_t>(skel.joint_count()), Quat::Identity()),
      translations(skel.rest_offsets) {}

Motion::Motion(Skeleton skel, double rate, int frames) : skeleton(std::move(skel)), fps(rate) {
  resize(frames);
}

PoseRef Motion::frame(int f) {
  const auto n = static_cast<std::size_t>(joint_count());
  const auto off = static_cast<std::size_t>(f) * n;
  return {std::span<Quat>(rotations_).subspan(off, n), std::span<Vec3>(translations_).subspan(off, n)};
}

ConstPoseRef Motion::frame(int f) const {
  const auto n = static_cast<std::size_t>(joint_count());
  const auto off = static_cast<std::size_t>(f) * n;
  return {std::span<const Quat>(rotations_).subspan(off, n),
          std::span<const Vec3>(translations_).subspan(off, n)};
}

void Motion::set_frame(int f, ConstPoseRef pose) {
  auto dst = frame(f);
  std::copy(pose.rotations.begin(), pose.rotations.end(), dst.rotations.begin());
  std::copy(pose.translations.begin(), pose.translations.end(), dst.translations.begin());
}

void Motion::push_back(ConstPoseRef pose) {
  if (pose.joint_count() != joint_count()) throw Error("Motion::push_back: pose has the wrong joint count");
  rotations_.insert(rotations_.end(), pose.rotations.begin(), pose.rotations.end());
  translations_.insert(translations_.end(), pose.translations.begin(), pose.translations.end());
  ++frames_;
}

void Motion::resize(int frames) {
  const auto n = static_cast<std::size_t>(joint_count());
  const auto old = static_cast<std::size_t>(frames_);
  frames_ = frames;
  rotations_.resize(n * static_cast<std::size_t>(frames), Quat::Identity());
  translations_.resize(n * static_cast<std::size_t>(frames));
  // New frames start at the rest pose.
  for (auto f = old; f < static_cast<std::size_t>(frames); ++f)
    std::copy(skeleton.rest_offsets.begin(), skeleton.rest_offsets.end(), translations_.begin() + static_cast<std::ptrdiff_t>(f * n));
}

}  // namespace legwork

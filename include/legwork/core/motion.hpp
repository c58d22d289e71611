#pragma once
// Pose and Motion: local joint transforms over a shared Skeleton.
// A pose stores, per joint, the local rotation (in the parent's frame) and the
// local translation (metres, in the parent's frame). For the root the
// translation is its world position; for other joints it normally equals the
// skeleton's rest offset (it differs only for translating joints or after
// retargeting/mirroring of an asymmetric skeleton).
#include <legwork/core/skeleton.hpp>

#include <span>
#include <vector>

namespace legwork {

// Non-owning mutable view of one pose (joint_count entries each).
struct PoseRef {
  std::span<Quat> rotations;
  std::span<Vec3> translations;
  int joint_count() const { return static_cast<int>(rotations.size()); }
};
// Non-owning read-only view of one pose.
struct ConstPoseRef {
  std::span<const Quat> rotations;
  std::span<const Vec3> translations;
  ConstPoseRef() = default;
  ConstPoseRef(std::span<const Quat> r, std::span<const Vec3> t) : rotations(r), translations(t) {}
  ConstPoseRef(const PoseRef& p) : rotations(p.rotations), translations(p.translations) {}  // NOLINT
  int joint_count() const { return static_cast<int>(rotations.size()); }
};

// An owning single pose.
struct Pose {
  std::vector<Quat> rotations;
  std::vector<Vec3> translations;

  Pose() = default;
  // The rest pose of `skel`: identity rotations, rest offsets.
  explicit Pose(const Skeleton& skel);
  PoseRef ref() { return {rotations, translations}; }
  ConstPoseRef ref() const { return {rotations, translations}; }
  operator ConstPoseRef() const { return ref(); }  // NOLINT
  int joint_count() const { return static_cast<int>(rotations.size()); }
};

// A sampled motion: skeleton, frame rate and frames stored contiguously
// (frame-major: frame f, joint j is at f * joint_count + j).
class Motion {
 public:
  Skeleton skeleton;
  double fps = 30.0;

  Motion() = default;
  Motion(Skeleton skel, double fps, int frames);

  int frame_count() const { return frames_; }
  int joint_count() const { return skeleton.joint_count(); }
  double frame_time() const { return 1.0 / fps; }
  // Duration from the first to the last frame, seconds.
  double duration() const { return frames_ > 1 ? (frames_ - 1) / fps : 0.0; }

  PoseRef frame(int f);
  ConstPoseRef frame(int f) const;
  void set_frame(int f, ConstPoseRef pose);
  // Appends a frame (copy of pose).
  void push_back(ConstPoseRef pose);
  void resize(int frames);

  std::span<Quat> all_rotations() { return rotations_; }
  std::span<const Quat> all_rotations() const { return rotations_; }
  std::span<Vec3> all_translations() { return translations_; }
  std::span<const Vec3> all_translations() const { return translations_; }

 private:
  int frames_ = 0;
  std::vector<Quat> rotations_;
  std::vector<Vec3> translations_;
};

}  // namespace legwork

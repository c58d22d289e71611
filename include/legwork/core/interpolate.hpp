#pragma once
// Interpolation of rotations and poses; resampling, trimming, concatenation.
#include <legwork/core/motion.hpp>

namespace legwork {

// Normalised lerp along the shortest arc (cheap, fine for close rotations).
Quat nlerp(const Quat& a, const Quat& b, double t);
// Spherical lerp along the shortest arc.
Quat slerp(const Quat& a, const Quat& b, double t);

// out = interpolation between poses a and b at t in [0,1] (slerp rotations,
// lerp translations). All three must have the same joint count. No allocation.
void blend_poses(ConstPoseRef a, ConstPoseRef b, double t, PoseRef out);

// Samples a motion at time t (seconds from the first frame), clamped to its
// duration. No allocation.
void sample_motion(const Motion& m, double t, PoseRef out);

// Largest motion resample() makes: frames x joints (2^26 joint poses = 3.7 GB).
inline constexpr double kMaxResampledJointPoses = 67108864.0;
// Frames resample(m, fps) makes; throws legwork::Error when fps is not
// positive or the result would exceed kMaxResampledJointPoses.
int resampled_frame_count(const Motion& m, double fps);
// New motion at `fps`, same duration (last sample at floor(duration*fps)/fps).
// Bounded as resampled_frame_count says, checked before allocating.
Motion resample(const Motion& m, double fps);
// Frames [first, last] inclusive; throws legwork::Error if out of range.
Motion trim(const Motion& m, int first, int last);
// b appended after a; same skeleton (joint names) and fps required.
Motion concatenate(const Motion& a, const Motion& b);

}  // namespace legwork

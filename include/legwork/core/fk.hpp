#pragma once
// Forward kinematics: local pose -> model-space joint transforms.
// Model space = the world frame the root translation lives in (metres).
// Runtime code: no allocation; output buffers are owned by the caller.
#include <legwork/core/motion.hpp>

#include <span>
#include <vector>

namespace legwork {

// Model-space transforms of every joint. `out` must have joint_count entries.
void forward_kinematics(const Skeleton& skel, ConstPoseRef pose, std::span<Transform> out);
// The same for the subtree of joint `root` only (root and its descendants),
// after a change to their local transforms: the other joints' entries of `out`
// are already the pose's and stay as they are.
void forward_kinematics_subtree(const Skeleton& skel, ConstPoseRef pose, int root, std::span<Transform> out);
// Model-space positions only (cheaper). `out` must have joint_count entries.
void forward_positions(const Skeleton& skel, ConstPoseRef pose, std::span<Vec3> out);
// Batched over a whole motion: out has frame_count * joint_count entries,
// frame-major. Allocates nothing.
void forward_positions(const Motion& motion, std::span<Vec3> out);
void forward_kinematics(const Motion& motion, std::span<Transform> out);
// Convenience (allocates): positions of all joints of all frames.
std::vector<Vec3> joint_positions(const Motion& motion);
std::vector<Vec3> joint_positions(const Skeleton& skel, ConstPoseRef pose);
// Model-space position of joint j's End Site tip (or the joint itself).
Vec3 end_site_position(const Skeleton& skel, std::span<const Transform> model, int j);

// From model-space rotations back to local rotations (inverse of FK).
void local_from_model_rotations(const Skeleton& skel, std::span<const Quat> model,
                                std::span<Quat> local);

}  // namespace legwork

#pragma once
// Analytic two-bone IK (hip-knee-ankle, shoulder-elbow-wrist).
// Runtime code: no allocation, no exceptions; writes local rotations of an
// existing pose. Positions are model space (the frame FK produces), metres.
#include <legwork/core/motion.hpp>

#include <span>

namespace legwork::ik {

// Joint indices of a chain: root (hip/shoulder), mid (knee/elbow), end (ankle/wrist).
struct TwoBoneChain {
  int root = -1, mid = -1, end = -1;
};
// Chains from resolved roles.
TwoBoneChain left_leg(const Skeleton& s);
TwoBoneChain right_leg(const Skeleton& s);
TwoBoneChain left_arm(const Skeleton& s);
TwoBoneChain right_arm(const Skeleton& s);

struct TwoBoneTarget {
  Vec3 position = Vec3::Zero();      // model space, where the end joint should go
  Quat rotation = Quat::Identity();  // model-space rotation for the end joint
  Vec3 hint = Vec3::Zero();          // model-space pole: the mid joint bends toward it
  double position_weight = 1.0;      // 0..1 blend from the input pose to the solution
  double rotation_weight = 0.0;      // 0..1 for the end joint's rotation
  double hint_weight = 1.0;          // 0..1; 0 keeps the current bend plane
};

// Solves the chain in place. `model` must hold the pose's FK transforms on
// entry (e.g. from forward_kinematics); on return the chain's three joints are
// updated in `model` (descendants of the end joint are not: rerun FK if they
// are needed). Unreachable targets straighten the chain toward the target.
void solve_two_bone(const Skeleton& skel, const TwoBoneChain& chain, const TwoBoneTarget& target, PoseRef pose,
                    std::span<Transform> model);

}  // namespace legwork::ik

#pragma once
// A skeleton's humanoid bones for VMC output. The names come from the one
// role -> Unity HumanBodyBones mapping in core (legwork/core/engine.hpp,
// humanoid_bone(); documented in docs/protocol.md):
//
//   Hips <- Pelvis          Spine <- Spine          Chest <- Chest (when it is not the Spine joint)
//   Neck <- Neck            Head <- Head
//   LeftShoulder <- LeftClavicle    LeftUpperArm <- LeftShoulder
//   LeftLowerArm <- LeftElbow       LeftHand <- LeftHand
//   LeftUpperLeg <- LeftHip         LeftLowerLeg <- LeftKnee
//   LeftFoot <- LeftAnkle           LeftToes <- LeftToe      (Right* the same)
//
// Bones whose role the skeleton lacks are left out. Each bone's parent is the
// nearest mapped ancestor; its local rotation/position are relative to that
// parent's joint (joints in between are folded in), so they match a humanoid
// rig whose rest pose is legwork's rest pose (a T-pose with world-aligned
// joint frames, like a normalised VRM). Output is in Unity's frame
// (to_engine(Engine::Unity, ...): x -> -x, (w,x,y,z) -> (w,x,-y,-z)).
#include <legwork/core/motion.hpp>

#include <span>
#include <string_view>
#include <vector>

namespace legwork::serve {

struct HumanoidBone {
  std::string_view name;  // Unity HumanBodyBones name
  int joint = -1;         // legwork joint
  int parent = -1;        // index into the bone list, -1 for Hips
};
// The humanoid bones present in `skel` (Hips first, parents before children).
std::vector<HumanoidBone> humanoid_bones(const Skeleton& skel);

struct BoneTransform {
  Vec3 position = Vec3::Zero();  // Unity frame: Hips world, others local to the parent bone
  Quat rotation = Quat::Identity();
};
// Bone transforms (Unity's frame) from model-space joint transforms.
void humanoid_pose(std::span<const HumanoidBone> bones, std::span<const Transform> model, std::span<BoneTransform> out);

}  // namespace legwork::serve

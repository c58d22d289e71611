// legwork roles -> Unity HumanBodyBones (see humanoid.hpp).
#include <legwork/serve/humanoid.hpp>

#include <legwork/core/engine.hpp>

namespace legwork::serve {

std::vector<HumanoidBone> humanoid_bones(const Skeleton& skel) {
  std::vector<HumanoidBone> bones;
  std::vector<int> bone_of(static_cast<std::size_t>(skel.joint_count()), -1);
  for (int r = 0; r < kRoleCount; ++r) {  // role order is hierarchy order (Pelvis, Spine, Chest, ...)
    const Role role = static_cast<Role>(r);
    const std::string_view name = humanoid_bone(role, Humanoid::Unity);
    const int j = skel.roles[role];
    if (j < 0 || bone_of[static_cast<std::size_t>(j)] >= 0) continue;  // absent, or Chest == Spine
    if (role != Role::Pelvis && bones.empty()) continue;               // no Hips: nothing to hang bones on
    bone_of[static_cast<std::size_t>(j)] = static_cast<int>(bones.size());
    bones.push_back({name, j, -1});
  }
  // Parent = nearest mapped ancestor. Bones were added in role order, which is
  // not joint order; every mapped joint's ancestors are mapped earlier or not at all.
  for (auto& b : bones) {
    for (int a = skel.parents[static_cast<std::size_t>(b.joint)]; a >= 0; a = skel.parents[static_cast<std::size_t>(a)])
      if (bone_of[static_cast<std::size_t>(a)] >= 0) {
        b.parent = bone_of[static_cast<std::size_t>(a)];
        break;
      }
  }
  return bones;
}

void humanoid_pose(std::span<const HumanoidBone> bones, std::span<const Transform> model, std::span<BoneTransform> out) {
  for (std::size_t i = 0; i < bones.size(); ++i) {
    const Transform& t = model[static_cast<std::size_t>(bones[i].joint)];
    if (bones[i].parent < 0) {
      out[i] = {to_engine(Engine::Unity, t.translation), to_engine(Engine::Unity, t.rotation)};
      continue;
    }
    const Transform& p = model[static_cast<std::size_t>(bones[bones[i].parent].joint)];
    const Quat inv = p.rotation.conjugate();
    out[i] = {to_engine(Engine::Unity, Vec3(inv * (t.translation - p.translation))), to_engine(Engine::Unity, Quat(inv * t.rotation))};
  }
}

}  // namespace legwork::serve

#include <legwork/walkcycle/keys.hpp>

#include <array>

namespace legwork::walkcycle {

namespace {
constexpr std::array<std::string_view, kKeyCount> kKeyNames{"contact", "down", "pass", "up"};
}  // namespace

std::string_view key_name(KeyName k) { return kKeyNames[static_cast<std::size_t>(k)]; }

const Quat* KeyPose::find(int joint) const {
  for (const auto& [j, q] : rotations)
    if (j == joint) return &q;
  return nullptr;
}

void KeyPose::set(int joint, const Quat& q) {
  for (auto& [j, r] : rotations)
    if (j == joint) {
      r = q;
      return;
    }
  rotations.emplace_back(joint, q);
}

int find_joint_or_role(const Skeleton& skel, std::string_view name) {
  if (int j = skel.find(name); j >= 0) return j;
  for (int r = 0; r < kRoleCount; ++r)
    if (role_name(static_cast<Role>(r)) == name) return skel.roles[static_cast<Role>(r)];
  return -1;
}

WalkKeys retime(const WalkKeys& keys, int frames) {
  WalkKeys out = keys;
  if (frames == keys.frames_per_cycle) return out;
  const double s = static_cast<double>(frames) / keys.frames_per_cycle;
  for (double& f : out.key_frames) f *= s;
  for (auto& ib : out.inbetweens) ib.frame *= s;
  out.fps = keys.fps * s;  // same duration per cycle: more frames, higher rate
  out.frames_per_cycle = frames;
  return out;
}

}  // namespace legwork::walkcycle

#include <legwork/core/mirror.hpp>

namespace legwork {

Quat mirror_rotation(const Quat& q) { return Quat(q.w(), q.x(), -q.y(), -q.z()); }
Vec3 mirror_vector(const Vec3& v) { return {-v.x(), v.y(), v.z()}; }

void mirror_pose(const Skeleton& skel, ConstPoseRef in, PoseRef out) {
  for (int j = 0; j < skel.joint_count(); ++j) {
    const auto src = static_cast<std::size_t>(skel.mirror[static_cast<std::size_t>(j)]);
    out.rotations[static_cast<std::size_t>(j)] = mirror_rotation(in.rotations[src]);
    out.translations[static_cast<std::size_t>(j)] = mirror_vector(in.translations[src]);
  }
}

Motion mirror_motion(const Motion& m) {
  Motion out(m.skeleton, m.fps, m.frame_count());
  for (int f = 0; f < m.frame_count(); ++f) mirror_pose(m.skeleton, m.frame(f), out.frame(f));
  return out;
}

}  // namespace legwork

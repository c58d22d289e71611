#include <legwork/core/fk.hpp>

namespace legwork {

namespace {
void fk_joint(const int* parent, ConstPoseRef pose, int j, std::span<Transform> out) {
  const Quat& r = pose.rotations[static_cast<std::size_t>(j)];
  const Vec3& t = pose.translations[static_cast<std::size_t>(j)];
  Transform& g = out[static_cast<std::size_t>(j)];
  const int p = parent[j];
  if (p < 0) {
    g.rotation = r;
    g.translation = t;
  } else {
    const Transform& gp = out[static_cast<std::size_t>(p)];
    g.rotation = gp.rotation * r;
    g.translation = gp.rotation * t + gp.translation;
  }
}
}  // namespace

void forward_kinematics(const Skeleton& skel, ConstPoseRef pose, std::span<Transform> out) {
  const int n = skel.joint_count();
  const int* parent = skel.parents.data();
  for (int j = 0; j < n; ++j) fk_joint(parent, pose, j, out);
}

void forward_kinematics_subtree(const Skeleton& skel, ConstPoseRef pose, int root, std::span<Transform> out) {
  // Parents come before their children, so the subtree lies in [root, n): a
  // joint is in it when its parent is. Joints past kStack are redone whatever
  // their parent (correct, only slower for huge rigs).
  constexpr int kStack = 256;
  const int n = skel.joint_count();
  const int* parent = skel.parents.data();
  bool in[kStack] = {};
  for (int j = root; j < n; ++j) {
    const bool mine = j == root || j >= kStack || (parent[j] >= root && parent[j] < kStack && in[parent[j]]);
    if (!mine) continue;
    if (j < kStack) in[j] = true;
    fk_joint(parent, pose, j, out);
  }
}

void forward_positions(const Skeleton& skel, ConstPoseRef pose, std::span<Vec3> out) {
  // Rotations are needed for children; keep them on a small stack buffer when
  // possible so this stays allocation-free for typical rigs.
  constexpr int kStack = 128;
  const int n = skel.joint_count();
  Quat stack[kStack];
  std::vector<Quat> heap;
  Quat* rot = stack;
  if (n > kStack) {
    heap.resize(static_cast<std::size_t>(n));
    rot = heap.data();
  }
  const int* parent = skel.parents.data();
  for (int j = 0; j < n; ++j) {
    const int p = parent[j];
    const auto ju = static_cast<std::size_t>(j);
    if (p < 0) {
      rot[j] = pose.rotations[ju];
      out[ju] = pose.translations[ju];
    } else {
      rot[j] = rot[p] * pose.rotations[ju];
      out[ju] = rot[p] * pose.translations[ju] + out[static_cast<std::size_t>(p)];
    }
  }
}

void forward_positions(const Motion& motion, std::span<Vec3> out) {
  const auto n = static_cast<std::size_t>(motion.joint_count());
  for (int f = 0; f < motion.frame_count(); ++f)
    forward_positions(motion.skeleton, motion.frame(f), out.subspan(static_cast<std::size_t>(f) * n, n));
}

void forward_kinematics(const Motion& motion, std::span<Transform> out) {
  const auto n = static_cast<std::size_t>(motion.joint_count());
  for (int f = 0; f < motion.frame_count(); ++f)
    forward_kinematics(motion.skeleton, motion.frame(f), out.subspan(static_cast<std::size_t>(f) * n, n));
}

std::vector<Vec3> joint_positions(const Motion& motion) {
  std::vector<Vec3> out(static_cast<std::size_t>(motion.frame_count() * motion.joint_count()));
  forward_positions(motion, out);
  return out;
}

std::vector<Vec3> joint_positions(const Skeleton& skel, ConstPoseRef pose) {
  std::vector<Vec3> out(static_cast<std::size_t>(skel.joint_count()));
  forward_positions(skel, pose, out);
  return out;
}

Vec3 end_site_position(const Skeleton& skel, std::span<const Transform> model, int j) {
  const auto ju = static_cast<std::size_t>(j);
  if (!skel.has_end_site[ju]) return model[ju].translation;
  return model[ju].apply(skel.end_sites[ju]);
}

void local_from_model_rotations(const Skeleton& skel, std::span<const Quat> model, std::span<Quat> local) {
  for (int j = 0; j < skel.joint_count(); ++j) {
    const auto ju = static_cast<std::size_t>(j);
    const int p = skel.parents[ju];
    local[ju] = p < 0 ? model[ju] : (model[static_cast<std::size_t>(p)].conjugate() * model[ju]).normalized();
  }
}

}  // namespace legwork

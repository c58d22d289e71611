// PLACEHOLDER two-bone solver so the eval branch builds and tests before the
// wip helper's implementation lands in main; on `git merge main` this file is
// replaced by main's src/ik/two_bone.cpp (take theirs).
#include <legwork/ik/two_bone.hpp>

#include <algorithm>
#include <cmath>

namespace legwork::ik {
namespace {
TwoBoneChain chain_of(const Skeleton& s, Role a, Role b, Role c) { return {s.roles[a], s.roles[b], s.roles[c]}; }
Quat parent_rotation(const Skeleton& skel, std::span<const Transform> model, int j) {
  const int p = skel.parents[static_cast<std::size_t>(j)];
  return p < 0 ? Quat::Identity() : model[static_cast<std::size_t>(p)].rotation;
}
}  // namespace

TwoBoneChain left_leg(const Skeleton& s) { return chain_of(s, Role::LeftHip, Role::LeftKnee, Role::LeftAnkle); }
TwoBoneChain right_leg(const Skeleton& s) { return chain_of(s, Role::RightHip, Role::RightKnee, Role::RightAnkle); }
TwoBoneChain left_arm(const Skeleton& s) { return chain_of(s, Role::LeftShoulder, Role::LeftElbow, Role::LeftHand); }
TwoBoneChain right_arm(const Skeleton& s) { return chain_of(s, Role::RightShoulder, Role::RightElbow, Role::RightHand); }

void solve_two_bone(const Skeleton& skel, const TwoBoneChain& chain, const TwoBoneTarget& target, PoseRef pose,
                    std::span<Transform> model) {
  const auto r = static_cast<std::size_t>(chain.root), m = static_cast<std::size_t>(chain.mid),
             e = static_cast<std::size_t>(chain.end);
  const Vec3 a = model[r].translation, b = model[m].translation, c = model[e].translation;
  const Vec3 t = c + std::clamp(target.position_weight, 0.0, 1.0) * (target.position - c);
  const double l1 = (b - a).norm(), l2 = (c - b).norm();
  if (l1 < 1e-9 || l2 < 1e-9) return;
  Vec3 at = t - a;
  double d = at.norm();
  const Vec3 u = d > 1e-9 ? Vec3(at / d) : Vec3((c - a).normalized());
  d = std::clamp(d, std::abs(l1 - l2) + 1e-6, l1 + l2 - 1e-6);
  auto perp = [&](const Vec3& v) { return Vec3(v - v.dot(u) * u); };
  Vec3 cur = perp(b - a), hint = perp(target.hint - a);
  if (cur.norm() > 1e-9) cur.normalize();
  if (hint.norm() > 1e-9) hint.normalize();
  const double hw = std::clamp(target.hint_weight, 0.0, 1.0);
  Vec3 v = (1 - hw) * cur + hw * hint;
  if (v.norm() < 1e-9) v = u.unitOrthogonal();
  v.normalize();
  const double cos_a = std::clamp((l1 * l1 + d * d - l2 * l2) / (2 * l1 * d), -1.0, 1.0);
  const Vec3 mid = a + l1 * (cos_a * u + std::sqrt(1 - cos_a * cos_a) * v);
  const Vec3 end = a + d * u;
  // Root: swing the upper bone onto the new mid position.
  const Quat r1 = Quat::FromTwoVectors(b - a, mid - a);
  const Quat root_model = (r1 * model[r].rotation).normalized();
  pose.rotations[r] = (parent_rotation(skel, model, chain.root).conjugate() * root_model).normalized();
  model[r].rotation = root_model;
  Quat mid_model = (r1 * model[m].rotation).normalized();
  const Vec3 end_after_root = mid + r1 * (c - b);
  const Quat r2 = Quat::FromTwoVectors(end_after_root - mid, end - mid);
  mid_model = (r2 * mid_model).normalized();
  pose.rotations[m] = (root_model.conjugate() * mid_model).normalized();
  model[m].rotation = mid_model;
  model[m].translation = mid;
  Quat end_model = (r2 * r1 * model[e].rotation).normalized();
  const double rw = std::clamp(target.rotation_weight, 0.0, 1.0);
  if (rw > 0) end_model = end_model.slerp(rw, target.rotation).normalized();
  pose.rotations[e] = (mid_model.conjugate() * end_model).normalized();
  model[e].rotation = end_model;
  model[e].translation = end;
}

}  // namespace legwork::ik

// Analytic two-bone IK: the law of cosines gives the mid-joint angle, the
// hint (pole) picks the bend plane, and two minimal rotations move the chain.
#include <legwork/ik/two_bone.hpp>
#include <legwork/core/rotation.hpp>

#include <algorithm>
#include <cmath>

namespace legwork::ik {

namespace {

TwoBoneChain chain_of(const Skeleton& s, Role root, Role mid, Role end) {
  return {s.roles[root], s.roles[mid], s.roles[end]};
}


// Unit vector perpendicular to `axis` (unit) in the direction of v, or false
// if v is (nearly) parallel to the axis.
bool perpendicular_part(const Vec3& v, const Vec3& axis, Vec3& out) {
  Vec3 p = v - v.dot(axis) * axis;
  const double n = p.norm();
  if (!(n > 1e-9 * std::max(1.0, v.norm()))) return false;
  out = p / n;
  return true;
}

// Rotates joint j's model transform about `pivot` by q.
void rotate_about(Transform& g, const Vec3& pivot, const Quat& q) {
  g.rotation = (q * g.rotation).normalized();
  g.translation = pivot + q * (g.translation - pivot);
}

// Rotates the joints on the path (from, to] (to included, from excluded) about pivot.
void rotate_path(const Skeleton& skel, int from, int to, const Vec3& pivot, const Quat& q,
                 std::span<Transform> model) {
  for (int j = to; j >= 0 && j != from; j = skel.parents[static_cast<std::size_t>(j)])
    rotate_about(model[static_cast<std::size_t>(j)], pivot, q);
}

// Local rotation of joint j from its (updated) model rotation.
void write_local(const Skeleton& skel, int j, std::span<const Transform> model, PoseRef pose) {
  const int p = skel.parents[static_cast<std::size_t>(j)];
  const Quat& g = model[static_cast<std::size_t>(j)].rotation;
  pose.rotations[static_cast<std::size_t>(j)] =
      (p < 0 ? g : (model[static_cast<std::size_t>(p)].rotation.conjugate() * g)).normalized();
}

// Any unit vector perpendicular to unit d, preferring the character's forward
// (+z: knees and elbows of a standing figure bend in the sagittal plane).
Vec3 fallback_pole(const Vec3& d) {
  Vec3 out;
  if (perpendicular_part(Vec3::UnitZ(), d, out)) return out;
  perpendicular_part(Vec3::UnitX(), d, out);
  return out;
}

// a.slerp(w, b): at w = 1 (a target's rotation taken fully) it is b on a's
// side of the sphere, which slerp reaches as 0 a + (+-1) b - without its acos and sines.
Quat toward(const Quat& a, double w, const Quat& b) {
  if (w != 1.0) return a.slerp(w, b);
  return a.dot(b) < 0 ? Quat(-b.coeffs()) : b;
}

}  // namespace

TwoBoneChain left_leg(const Skeleton& s) { return chain_of(s, Role::LeftHip, Role::LeftKnee, Role::LeftAnkle); }
TwoBoneChain right_leg(const Skeleton& s) { return chain_of(s, Role::RightHip, Role::RightKnee, Role::RightAnkle); }
TwoBoneChain left_arm(const Skeleton& s) { return chain_of(s, Role::LeftShoulder, Role::LeftElbow, Role::LeftHand); }
TwoBoneChain right_arm(const Skeleton& s) { return chain_of(s, Role::RightShoulder, Role::RightElbow, Role::RightHand); }

void solve_two_bone(const Skeleton& skel, const TwoBoneChain& chain, const TwoBoneTarget& target, PoseRef pose,
                    std::span<Transform> model) {
  if (chain.root < 0 || chain.mid < 0 || chain.end < 0) return;
  const auto ru = static_cast<std::size_t>(chain.root), mu = static_cast<std::size_t>(chain.mid),
             eu = static_cast<std::size_t>(chain.end);
  const Vec3 a = model[ru].translation;
  const Vec3 b = model[mu].translation;
  const Vec3 c = model[eu].translation;
  const double wp = std::clamp(target.position_weight, 0.0, 1.0);
  const double wh = std::clamp(target.hint_weight, 0.0, 1.0);
  const double wr = std::clamp(target.rotation_weight, 0.0, 1.0);
  // Bad input leaves the pose untouched rather than spreading NaN.
  if (!all_finite(target.position) || !all_finite(target.hint) || !std::isfinite(wp + wh + wr)) return;

  const Vec3 t = c + wp * (target.position - c);
  const double lab = (b - a).norm(), lcb = (c - b).norm();
  if (lab < 1e-9 || lcb < 1e-9) return;

  // Direction from the root to the target (keep the current one if the target
  // sits on the root).
  Vec3 d = t - a;
  double lat = d.norm();
  if (lat < 1e-9) {
    d = c - a;
    lat = d.norm();
    if (lat < 1e-9) d = b - a, lat = d.norm();
  }
  d /= lat;
  // Reachable distances are [|lab-lcb|, lab+lcb]; beyond, the chain straightens toward the target.
  lat = std::clamp(lat, std::max(std::abs(lab - lcb), 1e-6 * (lab + lcb)), lab + lcb);

  // Bend direction: the current bend, turned toward the hint by hint_weight.
  Vec3 current_pole, hint_pole, pole;
  const bool has_current = perpendicular_part(b - a, d, current_pole);
  const bool has_hint = wh > 0 && perpendicular_part(target.hint - a, d, hint_pole);
  if (has_hint && has_current)
    pole = current_pole + wh * (hint_pole - current_pole);
  else if (has_hint)
    pole = hint_pole;
  else if (has_current)
    pole = current_pole;
  else
    pole = fallback_pole(d);
  if (!perpendicular_part(pole, d, pole)) pole = has_current ? current_pole : fallback_pole(d);

  // Law of cosines for the angle at the root between d and the upper bone.
  const double cos_a = std::clamp((lab * lab + lat * lat - lcb * lcb) / (2 * lab * lat), -1.0, 1.0);
  const double sin_a = std::sqrt(std::max(0.0, 1 - cos_a * cos_a));
  const Vec3 b_new = a + lab * (cos_a * d + sin_a * pole);
  const Vec3 c_new = a + lat * d;

  // Root: minimal rotation of the upper bone onto its new direction.
  const Quat q1 = Quat::FromTwoVectors(b - a, b_new - a);
  rotate_path(skel, chain.root, chain.end, a, q1, model);
  model[ru].rotation = (q1 * model[ru].rotation).normalized();
  // Mid: minimal rotation of the (moved) lower bone onto its new direction.
  const Vec3 b_moved = model[mu].translation;
  const Quat q2 = Quat::FromTwoVectors(model[eu].translation - b_moved, c_new - b_new);
  rotate_path(skel, chain.mid, chain.end, b_moved, q2, model);
  model[mu].rotation = (q2 * model[mu].rotation).normalized();
  model[mu].translation = b_new;
  // Remove the rounding drift so the end lands exactly.
  model[eu].translation = c_new;
  if (wr > 0 && std::isfinite(target.rotation.coeffs().sum()))
    model[eu].rotation = toward(model[eu].rotation, wr, target.rotation.normalized()).normalized();

  // Write local rotations for every joint whose model frame changed.
  write_local(skel, chain.root, model, pose);
  for (int j = chain.end; j >= 0 && j != chain.root; j = skel.parents[static_cast<std::size_t>(j)])
    write_local(skel, j, model, pose);
}

}  // namespace legwork::ik

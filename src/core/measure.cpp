#include <legwork/core/measure.hpp>

#include <legwork/core/fk.hpp>

#include <algorithm>
#include <cstdio>

namespace legwork {

namespace {
double bone(const std::vector<Vec3>& p, int a, int b) {
  if (a < 0 || b < 0) return 0;
  return (p[static_cast<std::size_t>(a)] - p[static_cast<std::size_t>(b)]).norm();
}
}  // namespace

BodyMeasures measure_body(const Skeleton& skel) {
  BodyMeasures m;
  Pose rest(skel);
  std::vector<Transform> g(static_cast<std::size_t>(skel.joint_count()));
  forward_kinematics(skel, rest, g);
  std::vector<Vec3> p(g.size());
  double lo = 1e300, hi = -1e300;
  for (int j = 0; j < skel.joint_count(); ++j) {
    p[static_cast<std::size_t>(j)] = g[static_cast<std::size_t>(j)].translation;
    Vec3 tip = end_site_position(skel, g, j);
    for (const Vec3& q : {p[static_cast<std::size_t>(j)], tip}) {
      lo = std::min(lo, q.y());
      hi = std::max(hi, q.y());
    }
  }
  m.standing_height = hi - lo;
  const auto& r = skel.roles;
  // Rest poses are not always upright (CMU's legs splay 20 degrees at zero
  // rotation): with roles known, stack the straightened leg under the torso.
  if (r.has(Role::Pelvis) && r.has(Role::Head) && r.has(Role::LeftHip) && r.has(Role::LeftKnee) &&
      r.has(Role::LeftAnkle) && r.has(Role::RightHip) && r.has(Role::RightKnee) && r.has(Role::RightAnkle)) {
    auto at = [&](Role role) { return p[static_cast<std::size_t>(r[role])]; };
    const double head_top = end_site_position(skel, g, r[Role::Head]).y();
    const double pelvis = at(Role::Pelvis).y();
    const double hip_drop = pelvis - 0.5 * (at(Role::LeftHip).y() + at(Role::RightHip).y());
    const double leg = 0.5 * (bone(p, r[Role::LeftHip], r[Role::LeftKnee]) + bone(p, r[Role::LeftKnee], r[Role::LeftAnkle]) +
                              bone(p, r[Role::RightHip], r[Role::RightKnee]) + bone(p, r[Role::RightKnee], r[Role::RightAnkle]));
    // Ankle above the sole: lowest point of the foot's subtree (toes, end sites).
    // Parents precede children, so one pass marks the subtree (linear, not joints x depth).
    double sole = at(Role::LeftAnkle).y();
    std::vector<unsigned char> in_foot(static_cast<std::size_t>(skel.joint_count()), 0);
    for (int j = r[Role::LeftAnkle]; j < skel.joint_count(); ++j) {
      const auto ju = static_cast<std::size_t>(j);
      const int parent = skel.parents[ju];
      in_foot[ju] = j == r[Role::LeftAnkle] || (parent >= 0 && parent < j && in_foot[static_cast<std::size_t>(parent)]);
      if (in_foot[ju]) sole = std::min(sole, std::min(p[ju].y(), end_site_position(skel, g, j).y()));
    }
    const double ankle_height = at(Role::LeftAnkle).y() - sole;
    m.standing_height = (head_top - pelvis) + hip_drop + leg + ankle_height;
    m.hip_height = hip_drop + leg + ankle_height;
  }
  if (m.hip_height == 0 && r.has(Role::Pelvis)) m.hip_height = p[static_cast<std::size_t>(r[Role::Pelvis])].y() - lo;
  auto leg = [&](Role h, Role k, Role a) { return bone(p, r[h], r[k]) + bone(p, r[k], r[a]); };
  auto arm = [&](Role s, Role e, Role h) { return bone(p, r[s], r[e]) + bone(p, r[e], r[h]); };
  m.leg_length = 0.5 * (leg(Role::LeftHip, Role::LeftKnee, Role::LeftAnkle) +
                        leg(Role::RightHip, Role::RightKnee, Role::RightAnkle));
  m.arm_length = 0.5 * (arm(Role::LeftShoulder, Role::LeftElbow, Role::LeftHand) +
                        arm(Role::RightShoulder, Role::RightElbow, Role::RightHand));
  return m;
}

double guess_unit_scale(double h, std::string* why) {
  struct Unit {
    double lo, hi, scale;
    const char* name;
  };
  // Ranges of a plausible human standing height (about 0.8 to 2.5 m) in each unit.
  static const Unit units[] = {
      {0.5, 3.0, 1.0, "metres"},
      {15.0, 45.0, kCmuUnitMetres, "CMU ASF units (1/0.45 inch)"},
      {45.0, 100.0, 0.0254, "inches"},
      {100.0, 300.0, 0.01, "centimetres"},
      {500.0, 3000.0, 0.001, "millimetres"},
  };
  for (const auto& u : units)
    if (h >= u.lo && h < u.hi) {
      if (why) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "rest height %.3g units looks like %s (x%.6g)", h, u.name, u.scale);
        *why = buf;
      }
      return u.scale;
    }
  if (why) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "rest height %.3g units fits no known unit; pass --scale", h);
    *why = buf;
  }
  return 0.0;
}

}  // namespace legwork

#include <legwork/accent/offline/retarget.hpp>

#include <legwork/core/fk.hpp>
#include <legwork/core/measure.hpp>
#include <legwork/core/rotation.hpp>

#include <string>

namespace legwork::accent {

RoleRetarget make_role_retarget(const Skeleton& src, const Skeleton& dst) {
  RoleRetarget r;
  r.src = &src;
  r.dst = &dst;
  std::string missing;
  for (int role = 0; role < kRoleCount; ++role) {
    const Role ro = static_cast<Role>(role);
    if (role_is_required(ro) && dst.roles.has(ro) && !src.roles.has(ro)) missing += (missing.empty() ? "" : ", ") + std::string(role_name(ro));
  }
  if (!missing.empty()) throw Error("cannot retarget: the source skeleton has no joint for role(s) " + missing);
  const auto n = static_cast<std::size_t>(dst.joint_count());
  r.source_of.assign(n, -1);
  r.rest_fix.assign(n, Quat::Identity());
  // Role joints first (they define the anatomy), then exact names for the rest.
  for (int role = 0; role < kRoleCount; ++role) {
    const Role ro = static_cast<Role>(role);
    if (dst.roles.has(ro) && src.roles.has(ro)) r.source_of[static_cast<std::size_t>(dst.roles[ro])] = src.roles[ro];
  }
  for (std::size_t j = 0; j < n; ++j)
    if (r.source_of[j] < 0) r.source_of[j] = src.find(dst.names[j]);
  for (std::size_t j = 0; j < n; ++j) {
    const int s = r.source_of[j];
    if (s < 0) continue;
    ++r.paired;
    const Vec3 dd = rest_direction(dst, static_cast<int>(j), Vec3::Zero());
    const Vec3 ds = rest_direction(src, s, Vec3::Zero());
    if (dd.norm() > 0 && ds.norm() > 0) r.rest_fix[j] = Quat::FromTwoVectors(dd, ds);
  }
  const double hs = measure_body(src).hip_height, hd = measure_body(dst).hip_height;
  r.root_scale = hs > 1e-6 && hd > 1e-6 ? hd / hs : 1.0;
  return r;
}

void apply_retarget(const RoleRetarget& r, ConstPoseRef src, PoseRef dst, std::span<Quat> src_model,
                    std::span<Quat> dst_model) {
  const Skeleton& ss = *r.src;
  const Skeleton& ds = *r.dst;
  for (int j = 0; j < ss.joint_count(); ++j) {
    const auto ju = static_cast<std::size_t>(j);
    const int p = ss.parents[ju];
    src_model[ju] = p < 0 ? src.rotations[ju] : src_model[static_cast<std::size_t>(p)] * src.rotations[ju];
  }
  for (int j = 0; j < ds.joint_count(); ++j) {
    const auto ju = static_cast<std::size_t>(j);
    const int s = r.source_of[ju];
    const int p = ds.parents[ju];
    if (s >= 0)
      dst_model[ju] = (src_model[static_cast<std::size_t>(s)] * r.rest_fix[ju]).normalized();
    else
      dst_model[ju] = p < 0 ? Quat::Identity() : dst_model[static_cast<std::size_t>(p)];
    dst.translations[ju] = ds.rest_offsets[ju];
  }
  local_from_model_rotations(ds, dst_model, dst.rotations);
  dst.translations[0] = src.translations[0] * r.root_scale;
}

Motion retarget_motion(const Motion& m, const Skeleton& dst) {
  const RoleRetarget r = make_role_retarget(m.skeleton, dst);
  Motion out(dst, m.fps, m.frame_count());
  std::vector<Quat> sm(static_cast<std::size_t>(m.joint_count())), dm(static_cast<std::size_t>(dst.joint_count()));
  for (int f = 0; f < m.frame_count(); ++f) apply_retarget(r, m.frame(f), out.frame(f), sm, dm);
  return out;
}

Motion retarget_motion_at_head(const Motion& m, const Skeleton& dst) {
  Motion out = retarget_motion(m, dst);
  const int hs = m.skeleton.roles[Role::Head], ht = out.skeleton.roles[Role::Head];
  std::vector<Vec3> ps(static_cast<std::size_t>(m.joint_count())), pt(static_cast<std::size_t>(out.joint_count()));
  for (int f = 0; f < out.frame_count(); ++f) {
    forward_positions(m.skeleton, m.frame(f), ps);
    forward_positions(out.skeleton, out.frame(f), pt);
    out.frame(f).translations[0] += ps[static_cast<std::size_t>(hs)] - pt[static_cast<std::size_t>(ht)];
  }
  return out;
}

}  // namespace legwork::accent

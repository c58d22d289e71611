#pragma once
// Role-based pose retargeting between skeletons (e.g. the DAZ ladder trials
// onto the CMU database skeleton, or the synthesized pose onto a user's rig).
// Joints are paired by exact name first, then by anatomical role. Each paired
// joint copies the source's model-space rotation, corrected by the rest-pose
// difference of its bone direction (shortest arc), so a bone points where the
// source bone points even when the rest poses differ; unpaired joints keep
// their parent's model rotation (identity local). Roots copy the position,
// scaled by the ratio of hip heights.
#include <legwork/core/motion.hpp>

#include <span>
#include <vector>

namespace legwork::accent {

struct RoleRetarget {
  const Skeleton* src = nullptr;
  const Skeleton* dst = nullptr;
  std::vector<int> source_of;   // per dst joint: source joint or -1
  std::vector<Quat> rest_fix;   // per dst joint: model-space rest correction
  double root_scale = 1.0;
  int paired = 0;               // number of dst joints with a source

  // Workspace sizes needed by apply().
  int src_joints() const { return src->joint_count(); }
};

// Pairs the joints. Throws legwork::Error if the source lacks the roles the
// destination needs (pelvis, head, hands, feet...), listing them.
RoleRetarget make_role_retarget(const Skeleton& src, const Skeleton& dst);

// Retargets one pose. Workspaces: src_model (src joints), dst_model (dst
// joints). No allocation.
void apply_retarget(const RoleRetarget& r, ConstPoseRef src, PoseRef dst, std::span<Quat> src_model,
                    std::span<Quat> dst_model);

// Whole motion (allocates).
Motion retarget_motion(const Motion& m, const Skeleton& dst);
// Whole motion, then each frame shifted so the destination's head joint sits
// where the source's does (as the runtime places its own rig at the headset).
Motion retarget_motion_at_head(const Motion& m, const Skeleton& dst);

}  // namespace legwork::accent

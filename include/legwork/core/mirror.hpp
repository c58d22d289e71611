#pragma once
// Mirroring about the character's sagittal plane (the yz plane, x -> -x).
// Left/right pairs come from Skeleton::mirror (resolve_roles). Rotations are
// reflected by conjugating with the reflection (q -> (w, x, -y, -z) in local
// frames, since BVH rest frames are axis-aligned), translations by negating x
// and taking the counterpart's values, so mirroring twice is the identity and
// a mirrored left-hand path is exactly the reflected right-hand path.
#include <legwork/core/motion.hpp>

namespace legwork {

Quat mirror_rotation(const Quat& q);
Vec3 mirror_vector(const Vec3& v);
// out may not alias in. No allocation.
void mirror_pose(const Skeleton& skel, ConstPoseRef in, PoseRef out);
Motion mirror_motion(const Motion& m);

}  // namespace legwork

#pragma once
// Skeleton: the immutable joint hierarchy shared by poses and motions.
// Runtime layout is flat (ozz style): joints in depth-first order, so every
// parent index is smaller than its child's; the root is joint 0 (parent -1).
#include <legwork/core/types.hpp>

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace legwork {

// Anatomical roles that modules address joints by, whatever the rig names them.
enum class Role : int {
  Pelvis = 0,
  Spine,  // lowest spine joint; the full chain is JointRoles::spine_chain
  Chest,  // highest spine joint (below neck and clavicles)
  Neck,
  Head,
  LeftClavicle,
  LeftShoulder,  // upper arm joint
  LeftElbow,     // forearm joint
  LeftHand,      // wrist
  RightClavicle,
  RightShoulder,
  RightElbow,
  RightHand,
  LeftHip,  // upper leg joint
  LeftKnee,
  LeftAnkle,
  LeftToe,  // ball / toe base
  RightHip,
  RightKnee,
  RightAnkle,
  RightToe,
  Count
};
constexpr int kRoleCount = static_cast<int>(Role::Count);
std::string_view role_name(Role r);
// Roles every legged, armed character needs; clavicles and toes are optional.
bool role_is_required(Role r);

struct JointRoles {
  std::array<int, kRoleCount> joint{};  // joint index per role, -1 if absent
  std::vector<int> spine_chain;         // pelvis (exclusive) up to neck (exclusive)

  JointRoles() { joint.fill(-1); }
  int operator[](Role r) const { return joint[static_cast<std::size_t>(r)]; }
  int& operator[](Role r) { return joint[static_cast<std::size_t>(r)]; }
  bool has(Role r) const { return (*this)[r] >= 0; }
};

struct Skeleton {
  std::vector<std::string> names;
  std::vector<int> parents;       // -1 for the root; parents[i] < i
  std::vector<Vec3> rest_offsets;  // metres, in the parent's frame
  // BVH "End Site" tip per joint (metres, joint frame); NaN-free, valid if has_end_site.
  std::vector<Vec3> end_sites;
  std::vector<unsigned char> has_end_site;
  JointRoles roles;         // filled by resolve_roles()
  std::vector<int> mirror;  // left/right counterpart per joint (itself if central)

  int joint_count() const { return static_cast<int>(names.size()); }
  // Index of a joint by exact name, or -1.
  int find(std::string_view name) const;
  // Index by exact name; throws legwork::Error naming the joint if absent.
  int require(std::string_view name) const;
  // Children of joint j, in order.
  std::vector<int> children(int j) const;
  // True if `ancestor` is on the path from j to the root (or equals j).
  bool is_ancestor(int ancestor, int j) const;
  // Appends a joint; the parent must already exist. Returns its index.
  int add_joint(std::string name, int parent, const Vec3& offset);
  // Checks depth-first order, sizes and finite offsets; throws legwork::Error.
  void validate() const;
  // Multiplies every offset (and end site) by s.
  void scale(double s);
};

// Resolves roles and left/right mirror pairs from joint names. Knows the CMU
// BVH names (Hips, LeftUpLeg, LeftLeg, LeftFoot...), Mixamo ("mixamorig:"),
// DAZ (hip, lThigh, lShin...), and the common Left*/Right*, L_/R_, l*/r*,
// *_l/*_r patterns. Fills skel.roles and skel.mirror. Returns the list of
// roles it could not resolve (empty if all were found).
std::vector<Role> resolve_roles(Skeleton& skel);
// Like resolve_roles, but throws legwork::Error listing every missing
// required role when any is missing. `what` names the file for the message.
void require_roles(Skeleton& skel, std::string_view what);

}  // namespace legwork

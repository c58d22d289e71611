#pragma once
// Walk key poses as data, in memory (reading and writing walk files:
// legwork/walkcycle/offline/keys.hpp).
// One step of a walk is four key poses - contact, down, pass, up - plus the
// next contact, which is the mirror of the first (document 001). A walk file
// holds those four poses as joint-local rotations (degrees, Euler angles in a
// stated order, the frame BVH channels live in) and root offsets (metres),
// optional in-betweens at any frame of the step, per-joint key offsets
// ("shift", frames) and a standing pose used to stop. Joints left out of a
// key pose keep their rest rotation; joints left out of an in-between are
// interpolated. Convention: at the contact key the LEFT foot is in front and
// takes the weight for the first step; the second step is the mirror.
#include <legwork/core/motion.hpp>

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace legwork::walkcycle {

enum class KeyName : int { Contact = 0, Down, Pass, Up };
constexpr int kKeyCount = 4;
std::string_view key_name(KeyName k);  // "contact", "down", "pass", "up"

// One authored pose. Sparse: only the listed joints are set.
struct KeyPose {
  std::vector<std::pair<int, Quat>> rotations;  // joint index -> local rotation
  // Root offset from the standing root position, metres, character frame:
  // x = side (+ = character's left), y = height, z = forward.
  std::optional<Vec3> root_offset;
  // "height": "floor": the height is set when the cycle is built so the
  // lowest point of either foot in this pose touches the floor
  // (root_offset->y ignored). In-betweens take the joints they leave out
  // from the spline.
  bool height_on_floor = false;
  // The rotation of `joint` if listed, else nullptr.
  const Quat* find(int joint) const;
  void set(int joint, const Quat& q);  // adds or replaces
};

// An in-between pose at a frame of the first step (0 < frame < half cycle).
struct Inbetween {
  double frame = 0;  // in frames of WalkKeys::frames_per_cycle
  KeyPose pose;
};

// Euler order of the angles in the file: the rotation is applied as
// R = R_order[0] * R_order[1] * R_order[2] (e.g. "ZYX": R = Rz*Ry*Rx, the
// CMU BVH channel order). Angles are always listed as [x, y, z].
struct EulerOrder {
  std::array<char, 3> axes{'Z', 'Y', 'X'};
  std::string str() const { return {axes[0], axes[1], axes[2]}; }
};

struct WalkKeys {
  std::string name;
  std::string description;
  std::string skeleton_path;  // as written in the file (relative to the file's folder)
  int frames_per_cycle = 24;  // two steps; document 001: 24 (film), 32 (NTSC)
  double fps = 24.0;          // playback rate of those frames
  EulerOrder euler;
  // Frames of the down, pass and up keys after contact, in frames of
  // frames_per_cycle (contact is at 0). Default: evenly spaced, N/8, N/4, 3N/8.
  std::array<double, kKeyCount> key_frames{0, 3, 6, 9};
  std::array<KeyPose, kKeyCount> keys;
  std::vector<Inbetween> inbetweens;
  // Per-joint key delay in frames (overlapping action); the mirrored joint
  // gets the same delay unless listed itself.
  std::vector<std::pair<int, double>> shift;
  // Standing pose used to stop at the end of a path (rotations only). If
  // absent, the symmetric mean of the eight key poses of the cycle.
  std::optional<KeyPose> stand;
  // Lift the root smoothly wherever a foot would go below the floor between
  // keys (the spline does not know about the floor). Default on.
  bool floor_clamp = true;
};

// The key frames for `frames` per cycle scaled from `keys` (timing, in-betweens
// keep their place in the step); shift offsets stay in frames.
WalkKeys retime(const WalkKeys& keys, int frames);

// Joint index by name or role name, -1 if unknown.
int find_joint_or_role(const Skeleton& skel, std::string_view name);

}  // namespace legwork::walkcycle

#pragma once
// Walk files (JSON key poses, document 001) read and written; Euler angles
// in the file's order. Offline: allocates, throws legwork::Error naming the
// file and the field at fault.
#include <legwork/walkcycle/keys.hpp>

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace legwork::walkcycle {

// Reads a walk file for `skel` (joint names must exist in it; role names such
// as "left_knee" are accepted too). Throws legwork::Error with file and field.
WalkKeys parse_walk_keys(std::string_view json_text, const Skeleton& skel, std::string_view source);
WalkKeys read_walk_keys(const std::string& path, const Skeleton& skel);
// The "skeleton" field of a walk file resolved against the file's folder, or ""
// if the file has none. Throws on unreadable/invalid JSON.
std::string walk_skeleton_path(const std::string& walk_path);

// A walk file with its skeleton: `skeleton_bvh` if given, else the file's
// "skeleton" field (relative to the walk file; the T-pose frame dropped).
// Throws legwork::Error with a hint when neither names a skeleton.
struct WalkFile {
  Skeleton skeleton;
  WalkKeys keys;
};
WalkFile load_walk(const std::string& walk_path, const std::string& skeleton_bvh = "");

// Writes a walk file (angles rounded to 0.001 degree, offsets to 0.1 mm, so
// the output is stable and readable). Every joint with a non-identity rotation
// in a key is written.
std::string format_walk_keys(const WalkKeys& keys, const Skeleton& skel);
void write_walk_keys(const std::string& path, const WalkKeys& keys, const Skeleton& skel);

// Parses "Name=1.5,Other=2" into (joint, frames) pairs; role names accepted.
std::vector<std::pair<int, double>> parse_shift_spec(std::string_view spec, const Skeleton& skel);

// Local rotation from [x, y, z] degrees in `order`, and back.
Quat euler_xyz_to_quat(const Vec3& xyz_degrees, const EulerOrder& order);
Vec3 quat_to_euler_xyz(const Quat& q, const EulerOrder& order);

}  // namespace legwork::walkcycle

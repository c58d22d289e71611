#pragma once
// glTF 2.0 binary (.glb) export of a skeleton + animation, via tinygltf.
// The skeleton becomes a node hierarchy with a skin (one joint per node, with
// inverse bind matrices of the rest pose) and a stick-figure mesh skinned to it
// so viewers (Blender, three.js) show something; the motion becomes one
// animation with translation + rotation channels per joint (LINEAR sampling).
// BVH End Sites become leaf nodes "<joint>_end" (not skin joints). Data is
// stored as 32-bit floats. Checked with the Khronos glTF validator (docs/io.md).
// Units and axes are already glTF's (metres, y up, +z forward).
#include <legwork/core/motion.hpp>

#include <string>
#include <string_view>

namespace legwork::io {

struct GltfOptions {
  std::string animation_name = "motion";
  bool include_mesh = true;  // a skinned bone mesh so the animation is visible
};

// Throws legwork::Error on failure (path not writable, empty motion).
void write_glb(const std::string& path, const Motion& m, const GltfOptions& opt = {});

// Limits of the reader: the resampled motion holds at most this many joint
// poses (frames x joints; 2^24 = 0.9 GB, e.g. 31 joints for 4.5 hours at
// 30 fps), and `fps` is at most kMaxGlbFps. A file's duration does not cost
// bytes (two keys can span a year), so this bound is absolute.
inline constexpr double kMaxGlbJointPoses = 16777216.0;
inline constexpr double kMaxGlbFps = 10000.0;

// Reads back a .glb written by write_glb (skeleton + first animation,
// resampled at `fps`); used by tests to check round trips. Nothing in the
// file is trusted: accessor counts, offsets and strides are checked against
// the buffers without overflow, key times must be finite and increasing,
// values finite, external buffer files are refused, and the sample count is
// bounded before allocating. Throws legwork::Error naming the file.
Motion read_glb(const std::string& path, double fps = 30.0);
// The same from the bytes of a .glb; `path` names it in messages.
Motion parse_glb(std::string_view bytes, const std::string& path, double fps = 30.0);

}  // namespace legwork::io

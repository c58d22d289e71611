#pragma once
// glTF 2.0 binary (.glb) export of a skeleton + animation, via tinygltf.
// The skeleton becomes a node hierarchy with a skin (one joint per node, with
// inverse bind matrices of the rest pose) and a stick-figure mesh skinned to it
// so viewers (Blender, three.js) show something; the motion becomes one
// animation with translation + rotation channels per joint (LINEAR sampling).
// BVH End Sites become leaf nodes "<joint>_end" (not skin joints). Data is
// stored as 32-bit floats. Checked with the Khronos glTF validator (docs/io.md).
// Units and axes are already glTF's (metres, y up, +z forward).
// Since glTF stores floats, the animation's extras also keep the exact frame
// rate and (by default) a copy of the motion in doubles, so that legwork reads
// back exactly what it wrote (a BVH -> GLB -> BVH round trip is lossless);
// other tools ignore the extras and play the float channels.
#include <legwork/core/motion.hpp>

#include <string>
#include <string_view>

namespace legwork::io {

struct GltfOptions {
  std::string animation_name = "motion";
  bool include_mesh = true;  // a skinned bone mesh so the animation is visible
  // Keep a copy of the motion in doubles (extras.legwork.exact_view, about
  // twice the animation's bytes) so read_glb gives back every value exactly.
  bool exact_copy = true;
};

// Throws legwork::Error on failure (path not writable, empty motion).
void write_glb(const std::string& path, const Motion& m, const GltfOptions& opt = {});

// Limits of the reader: the resampled motion holds at most this many joint
// poses (frames x joints; 2^24 = 0.9 GB, e.g. 31 joints for 4.5 hours at
// 30 fps), and `fps` is at most kMaxGlbFps. A file's duration does not cost
// bytes (two keys can span a year), so this bound is absolute.
inline constexpr double kMaxGlbJointPoses = 16777216.0;
inline constexpr double kMaxGlbFps = 10000.0;

// Reads a .glb: the skeleton of the first skin and its first animation.
// Files written by write_glb come back exactly (frames, frame rate and, with
// the exact copy, every value). Files from other tools (Blender, three.js...)
// are read when their joints resolve to roles (else an error lists the
// missing roles and the joint names): skin joints in any order (the largest
// joint tree is kept), node TRS or matrices, a uniform scale/rotation above
// the root folded into the root, translation-only or rotation-only channels
// (other joints keep their node pose), STEP, LINEAR and CUBICSPLINE
// interpolation. `fps` = 0 keeps the file's own frames: the rate legwork
// wrote, or, when every channel shares evenly spaced keys, one frame per
// key; otherwise 30 fps. A positive `fps` resamples the animation.
// Nothing in the file is trusted: accessor counts, offsets and strides are
// checked against the buffers without overflow, key times must be finite and
// increasing, values finite, external buffer files are refused, and the
// sample count is bounded before allocating. Throws legwork::Error naming
// the file.
Motion read_glb(const std::string& path, double fps = 0.0);
// The same from the bytes of a .glb; `path` names it in messages.
Motion parse_glb(std::string_view bytes, const std::string& path, double fps = 0.0);

}  // namespace legwork::io

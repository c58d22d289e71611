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

namespace legwork::io {

struct GltfOptions {
  std::string animation_name = "motion";
  bool include_mesh = true;  // a skinned bone mesh so the animation is visible
};

// Throws legwork::Error on failure (path not writable, empty motion).
void write_glb(const std::string& path, const Motion& m, const GltfOptions& opt = {});

// Reads back a .glb written by write_glb (skeleton + first animation,
// resampled at `fps`); used by tests to check round trips.
Motion read_glb(const std::string& path, double fps = 30.0);

}  // namespace legwork::io

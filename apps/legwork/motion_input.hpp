#pragma once
// Options every command that reads a BVH shares: --scale, --drop-first, --lenient.
#include "command.hpp"

#include <legwork/io/bvh.hpp>

#include <string>

namespace legwork::cli {

struct MotionInput {
  std::string path;
  double scale = 0;         // 0 = detect
  bool drop_first = false;  // drop frame 0 (CMU T-pose)
  bool lenient = false;     // tolerate extra motion lines

  // Adds the positional IN (if `positional`) and the shared flags.
  void add_options(CLI::App* cmd, bool positional = true, const std::string& name = "input");
  io::BvhFile load() const;
};

}  // namespace legwork::cli

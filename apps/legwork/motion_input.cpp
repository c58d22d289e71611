#include "motion_input.hpp"

namespace legwork::cli {

void MotionInput::add_options(CLI::App* cmd, bool positional, const std::string& name) {
  if (positional) cmd->add_option(name, path, "BVH file to read")->required()->check(CLI::ExistingFile);
  cmd->add_option("--scale", scale,
                  "file units -> metres (default: detect from the rest-pose height; CMU = 0.056444)")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--drop-first", drop_first, "drop frame 0 (the synthetic T-pose of CMU files)");
  cmd->add_flag("--lenient", lenient, "accept more motion lines than 'Frames:' declares (extra lines ignored)");
}

io::BvhFile MotionInput::load() const {
  io::BvhReadOptions opt;
  opt.scale = scale;
  opt.drop_first_frame = drop_first;
  opt.strict_frame_count = !lenient;
  return io::read_bvh(path, opt);
}

}  // namespace legwork::cli

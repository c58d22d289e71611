#include "motion_input.hpp"

#include <legwork/io/gltf.hpp>
#include <legwork/io/text.hpp>
#include <legwork/core/interpolate.hpp>

namespace legwork::cli {

void MotionInput::add_options(CLI::App* cmd, bool positional, const std::string& name) {
  if (positional) cmd->add_option(name, path, "motion file to read: .bvh, or a .glb written by legwork")->required()->check(CLI::ExistingFile);
  cmd->add_option("--scale", scale,
                  "file units -> metres (default: detect from the rest-pose height; CMU = 0.056444)")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--drop-first", drop_first, "drop frame 0 (the synthetic T-pose of CMU files)");
  cmd->add_flag("--lenient", lenient, "accept more motion lines than 'Frames:' declares (extra lines ignored)");
}

io::BvhFile MotionInput::load() const {
  if (io::extension_of(path) == ".glb") {
    // legwork's own glTF files (metres already); other glTF files are refused by read_glb.
    io::BvhFile f;
    f.motion = io::read_glb(path);
    if (scale > 0) {
      f.motion.skeleton.scale(scale);
      for (auto& t : f.motion.all_translations()) t *= scale;
    }
    f.report.scale = scale > 0 ? scale : 1.0;
    f.report.scale_reason = "glTF is in metres";
    f.report.missing_roles = resolve_roles(f.motion.skeleton);
    if (drop_first && f.motion.frame_count() > 1) f.motion = trim(f.motion, 1, f.motion.frame_count() - 1);
    return f;
  }
  io::BvhReadOptions opt;
  opt.scale = scale;
  opt.drop_first_frame = drop_first;
  opt.strict_frame_count = !lenient;
  return io::read_bvh(path, opt);
}

}  // namespace legwork::cli

// legwork info / convert: inspect and convert motion files (io/motion_file.hpp).
#include "command.hpp"

#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

namespace legwork::cli {
namespace {

void register_info(CLI::App& app) {
  auto* cmd = app.add_subcommand("info", "Show a BVH file's joints, roles, frames, rate, duration and height.\n"
                                         "Example: legwork info data/cmu/bvh/walking/07_01.bvh");
  auto in = std::make_shared<MotionInput>();
  auto json = std::make_shared<bool>(false);
  in->add_options(cmd);
  cmd->add_flag("--json", *json, "print machine-readable JSON instead of text");
  cmd->callback([in, json] {
    const auto f = in->load();
    if (*json) {
      auto j = io::motion_info_json(f);
      j["file"] = in->path;
      std::cout << j.dump(2) << "\n";
    } else {
      std::cout << "file:       " << in->path << "\n" << io::motion_info_text(f);
    }
  });
}

void register_convert(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "convert",
      "Convert a motion: BVH -> BVH or GLB, with optional resampling, mirroring, trimming and unit scaling.\n"
      "Example: legwork convert data/cmu/bvh/walking/07_01.bvh walk.glb --frames 1: --rate 30");
  auto in = std::make_shared<MotionInput>();
  auto out = std::make_shared<std::string>();
  auto opt = std::make_shared<io::ConvertOptions>();
  in->add_options(cmd);
  output_file(cmd->add_option("output", *out, "output file: .bvh or .glb")->required());
  cmd->add_option("--rate", opt->rate, "resample to this frame rate (Hz, 0 = keep), keeping the duration")->check(non_negative_number());
  cmd->add_flag("--mirror", opt->mirror, "mirror about the character's sagittal plane (swap left and right)");
  cmd->add_option("--frames", opt->frames, "keep frames A:B (inclusive; either side optional, e.g. 1: drops the T-pose)");
  cmd->callback([=] {
    require_extension("output", *out, {".bvh", ".glb"});
    const Motion m = io::convert_motion(in->load(), *opt, *out);
    std::printf("%d frames at %.4g Hz, %d joints\n", m.frame_count(), m.fps, m.joint_count());
    announce("motion", *out);
  });
}

LEGWORK_COMMAND(register_info, 10);
LEGWORK_COMMAND(register_convert, 20);

}  // namespace
}  // namespace legwork::cli

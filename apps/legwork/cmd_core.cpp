// legwork info / convert: inspect and convert motion files (io/motion_file.hpp).
#include "command.hpp"

#include <legwork/accent/database.hpp>
#include <legwork/accent/offline/report.hpp>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

namespace legwork::cli {
namespace {

// Whether the file starts with the accent database's magic (whatever its name).
bool is_accent_database(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[sizeof accent::kMagic] = {};
  return in.read(magic, sizeof magic) && std::memcmp(magic, accent::kMagic, sizeof magic) == 0;
}

// database_info (accent/offline/report.hpp) with the file and its load time.
nlohmann::json database_info(const std::string& path) {
  const auto t0 = std::chrono::steady_clock::now();
  const accent::Database db = accent::load_database(path);  // checksum verified, index read
  const double load_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  nlohmann::json j = {{"file", path}};
  j.update(accent::database_info(db));
  j["load_ms"] = load_ms;
  return j;
}

void print_database_info(const nlohmann::json& j) {
  std::printf("file:       %s\n", j["file"].get<std::string>().c_str());
  std::printf("format:     legwork accent database, version %d, %.1f MB (loaded and verified in %.1f ms)\n",
              j["format_version"].get<int>(), j["bytes"].get<double>() / 1e6, j["load_ms"].get<double>());
  std::printf("windows:    %d over %zu trials (%d poses); %d joints, %.2f m tall\n", j["windows"].get<int>(),
              j["trials"].size(), j["poses"].get<int>(), j["joints"].get<int>(), j["height_m"].get<double>());
  std::printf("windows of: %d samples %d apart at %.4g Hz (%.0f ms), one every %d samples; speeds",
              j["window_samples"].get<int>(), j["window_stride"].get<int>(), j["fps"].get<double>(),
              1000 * j["window_seconds"].get<double>(), j["hop"].get<int>());
  for (double v : j["speeds"]) std::printf(" %.3g", v);
  std::printf("%s\n", j["mirrored"].get<bool>() ? ", mirrored copies" : "");
  std::printf("classes:   ");
  for (const auto& c : j["classes"])
    std::printf(" %s (%d trial%s, %d windows)", c["name"].get<std::string>().c_str(), c["trials"].get<int>(),
                c["trials"].get<int>() == 1 ? "" : "s",
                c["windows"].get<int>());
  std::printf("\nindex:      %s\n", j["search_index"].get<bool>() ? "KD-trees stored in the file" : "none");
}

void register_info(CLI::App& app) {
  auto* cmd = app.add_subcommand("info", "Show a BVH or GLB file's joints, roles, frames, rate, duration and height, or what an "
                                         "accent database (.lwdb) holds.\n"
                                         "Example: legwork info data/cmu/bvh/walking/07_01.bvh");
  auto in = std::make_shared<MotionInput>();
  auto json = std::make_shared<bool>(false);
  in->add_options(cmd);
  cmd->add_flag("--json", *json, "print machine-readable JSON instead of text");
  cmd->callback([in, json] {
    if (is_accent_database(in->path)) {
      const auto j = database_info(in->path);
      if (*json)
        std::cout << j.dump(2) << "\n";
      else
        print_database_info(j);
      return;
    }
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

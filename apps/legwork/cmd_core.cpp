// legwork info / convert: inspect and convert motion files.
#include "command.hpp"
#include "motion_input.hpp"

#include <legwork/core/interpolate.hpp>
#include <legwork/core/measure.hpp>
#include <legwork/core/mirror.hpp>
#include <legwork/io/gltf.hpp>
#include <legwork/io/text.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

namespace legwork::cli {
namespace {

nlohmann::json info_json(const io::BvhFile& f) {
  const Motion& m = f.motion;
  const auto body = measure_body(m.skeleton);
  nlohmann::json j;
  j["joints"] = m.joint_count();
  j["frames"] = m.frame_count();
  j["fps"] = m.fps;
  j["duration_s"] = m.duration();
  j["scale_to_metres"] = f.report.scale;
  j["scale_reason"] = f.report.scale_reason;
  j["standing_height_m"] = body.standing_height;
  j["hip_height_m"] = body.hip_height;
  j["leg_length_m"] = body.leg_length;
  j["arm_length_m"] = body.arm_length;
  j["repaired_zero_frames"] = f.report.repaired_zero_frames;
  nlohmann::json roles = nlohmann::json::object();
  for (int r = 0; r < kRoleCount; ++r) {
    int idx = m.skeleton.roles.joint[static_cast<std::size_t>(r)];
    roles[std::string(role_name(static_cast<Role>(r)))] = idx >= 0 ? nlohmann::json(m.skeleton.names[static_cast<std::size_t>(idx)]) : nlohmann::json(nullptr);
  }
  j["roles"] = roles;
  nlohmann::json joints = nlohmann::json::array();
  for (int i = 0; i < m.joint_count(); ++i) {
    const auto iu = static_cast<std::size_t>(i);
    joints.push_back({{"name", m.skeleton.names[iu]},
                      {"parent", m.skeleton.parents[iu] >= 0 ? nlohmann::json(m.skeleton.names[static_cast<std::size_t>(m.skeleton.parents[iu])]) : nlohmann::json(nullptr)},
                      {"mirror", m.skeleton.names[static_cast<std::size_t>(m.skeleton.mirror[iu])]}});
  }
  j["joint_list"] = joints;
  j["warnings"] = f.report.warnings;
  return j;
}

void print_info(const io::BvhFile& f) {
  const Motion& m = f.motion;
  const auto body = measure_body(m.skeleton);
  std::printf("joints:     %d\n", m.joint_count());
  std::printf("frames:     %d at %.4g Hz (%.3f s)%s\n", m.frame_count(), m.fps, m.duration(),
              f.report.dropped_first_frame ? ", frame 0 dropped" : "");
  std::printf("units:      x%.6g to metres (%s)\n", f.report.scale, f.report.scale_reason.c_str());
  std::printf("height:     %.3f m standing (rest pose), hips %.3f m, leg %.3f m, arm %.3f m\n",
              body.standing_height, body.hip_height, body.leg_length, body.arm_length);
  if (body.standing_height < 1.4 || body.standing_height > 2.0)
    std::printf("            note: a standing height outside 1.4-2.0 m suggests wrong units (see --scale)\n");
  if (f.report.repaired_zero_frames)
    std::printf("repaired:   %d all-zero frame(s) replaced by the nearest real frame\n", f.report.repaired_zero_frames);
  for (const auto& w : f.report.warnings) std::printf("warning:    %s\n", w.c_str());
  std::printf("roles:\n");
  for (int r = 0; r < kRoleCount; ++r) {
    int idx = m.skeleton.roles.joint[static_cast<std::size_t>(r)];
    std::printf("  %-15s %s\n", std::string(role_name(static_cast<Role>(r))).c_str(),
                idx >= 0 ? m.skeleton.names[static_cast<std::size_t>(idx)].c_str() : "(not found)");
  }
  std::printf("hierarchy:\n");
  for (int i = 0; i < m.joint_count(); ++i) {
    int depth = 0;
    for (int p = m.skeleton.parents[static_cast<std::size_t>(i)]; p >= 0; p = m.skeleton.parents[static_cast<std::size_t>(p)]) ++depth;
    std::printf("  %*s%s\n", depth * 2, "", m.skeleton.names[static_cast<std::size_t>(i)].c_str());
  }
}

void register_info(CLI::App& app) {
  auto* cmd = app.add_subcommand("info", "Show a BVH file's joints, roles, frames, rate, duration and height.\n"
                                         "Example: legwork info data/cmu/bvh/walking/07_01.bvh");
  auto in = std::make_shared<MotionInput>();
  auto json = std::make_shared<bool>(false);
  in->add_options(cmd);
  cmd->add_flag("--json", *json, "print machine-readable JSON instead of text");
  cmd->callback([in, json] {
    auto f = in->load();
    if (*json) {
      auto j = info_json(f);
      j["file"] = in->path;
      std::cout << j.dump(2) << "\n";
    } else {
      std::printf("file:       %s\n", in->path.c_str());
      print_info(f);
    }
  });
}

// Resampling bounds: no capture system records faster, and the output stays
// a file a tool can load (frames x joints, checked before any work).
constexpr double kMaxConvertRate = 1000.0;
constexpr double kMaxConvertJointPoses = 16777216.0;  // 2^24: 0.9 GB of poses

std::string number_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

void check_resample_size(const Motion& m, double rate) {
  const double frames = std::floor(m.duration() * rate + 1e-6) + 1;
  if (frames * m.joint_count() > kMaxConvertJointPoses)
    throw Error("--rate " + number_text(rate) + " Hz would make " + number_text(frames) + " frames x " +
                std::to_string(m.joint_count()) + " joints; the limit is " + number_text(kMaxConvertJointPoses) +
                " joint poses (at most " + number_text(std::floor(kMaxConvertJointPoses / m.joint_count() / std::max(m.duration(), 1e-9))) +
                " Hz for this clip)");
}

void register_convert(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "convert",
      "Convert a motion: BVH -> BVH or GLB, with optional resampling, mirroring, trimming and unit scaling.\n"
      "Example: legwork convert data/cmu/bvh/walking/07_01.bvh walk.glb --frames 1: --rate 30");
  auto in = std::make_shared<MotionInput>();
  auto out = std::make_shared<std::string>();
  auto rate = std::make_shared<double>(0);
  auto mirror = std::make_shared<bool>(false);
  auto frames = std::make_shared<std::string>();
  in->add_options(cmd);
  cmd->add_option("output", *out, "output file: .bvh or .glb")->required();
  cmd->add_option("--rate", *rate, "resample to this frame rate (Hz), keeping the duration")->check(CLI::PositiveNumber);
  cmd->add_flag("--mirror", *mirror, "mirror about the character's sagittal plane (swap left and right)");
  cmd->add_option("--frames", *frames, "keep frames A:B (inclusive; either side optional, e.g. 1: drops the T-pose)");
  cmd->callback([=] {
    const auto ext = io::extension_of(*out);
    if (ext != ".bvh" && ext != ".glb")
      throw Error("output '" + *out + "' must end in .bvh or .glb");
    if (*rate > kMaxConvertRate)
      throw Error("--rate " + number_text(*rate) + " Hz is above the limit of " + number_text(kMaxConvertRate) + " Hz");
    auto f = in->load();
    Motion m = std::move(f.motion);
    if (!frames->empty()) {
      auto [a, b] = parse_frame_range(*frames, m.frame_count());
      m = trim(m, a, b);
    }
    if (*rate > 0) check_resample_size(m, *rate);
    if (*mirror) m = mirror_motion(m);
    if (*rate > 0) m = resample(m, *rate);
    if (ext == ".bvh") {
      io::BvhWriteOptions w;
      // Keep the file's own channel layout (and units) unless it cannot hold the data.
      w.channels = f.channels;
      w.scale = 1.0 / f.report.scale;
      try {
        io::write_bvh(*out, m, w);
      } catch (const Error&) {
        w.channels.clear();
        io::write_bvh(*out, m, w);
      }
    } else {
      io::write_glb(*out, m);
    }
    std::printf("%d frames at %.4g Hz, %d joints\n", m.frame_count(), m.fps, m.joint_count());
    announce("motion", *out);
  });
}

LEGWORK_COMMAND(register_info, 10);
LEGWORK_COMMAND(register_convert, 20);

}  // namespace
}  // namespace legwork::cli

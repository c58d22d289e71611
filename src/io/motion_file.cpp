#include <legwork/io/motion_file.hpp>

#include <legwork/core/interpolate.hpp>
#include <legwork/core/measure.hpp>
#include <legwork/core/mirror.hpp>
#include <legwork/io/gltf.hpp>
#include <legwork/io/text.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace legwork::io {

namespace {

std::string number_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// `v` rounded to a multiple of `step` (for JSON a person reads: 120.0, not 120.0000480000192).
double rounded(double v, double step) { return std::round(v / step) * step; }

void check_resample_size(const Motion& m, double rate) {
  const double frames = std::floor(m.duration() * rate + 1e-6) + 1;
  if (frames * m.joint_count() > kMaxConvertJointPoses)
    throw Error("--rate " + number_text(rate) + " Hz would make " + number_text(frames) + " frames x " +
                std::to_string(m.joint_count()) + " joints; the limit is " + number_text(kMaxConvertJointPoses) +
                " joint poses (at most " +
                number_text(std::floor(kMaxConvertJointPoses / m.joint_count() / std::max(m.duration(), 1e-9))) +
                " Hz for this clip)");
}

}  // namespace

BvhFile read_motion(const std::string& path, const MotionReadOptions& opt) {
  if (extension_of(path) == ".glb") {
    BvhFile f;
    f.motion = read_glb(path);
    if (opt.scale > 0) {
      f.motion.skeleton.scale(opt.scale);
      for (auto& t : f.motion.all_translations()) t *= opt.scale;
    }
    f.report.scale = opt.scale > 0 ? opt.scale : 1.0;
    f.report.scale_reason = "glTF is in metres";
    f.report.missing_roles = resolve_roles(f.motion.skeleton);
    if (opt.drop_first && f.motion.frame_count() > 1) f.motion = trim(f.motion, 1, f.motion.frame_count() - 1);
    return f;
  }
  BvhReadOptions b;
  b.scale = opt.scale;
  b.drop_first_frame = opt.drop_first;
  b.strict_frame_count = !opt.lenient;
  return read_bvh(path, b);
}

void write_motion(const std::string& path, const Motion& m, const std::string& animation_name, const std::string& option) {
  require_extension(option, path, {".bvh", ".glb"});
  if (extension_of(path) == ".bvh") {
    write_bvh(path, m);
  } else {
    GltfOptions g;
    g.animation_name = animation_name;
    write_glb(path, m, g);
  }
}

Motion convert_motion(const BvhFile& source, const ConvertOptions& opt, const std::string& out) {
  require_extension("output", out, {".bvh", ".glb"});
  if (opt.rate > kMaxConvertRate)
    throw Error("--rate " + number_text(opt.rate) + " Hz is above the limit of " + number_text(kMaxConvertRate) + " Hz");
  Motion m = source.motion;
  if (!opt.frames.empty()) {
    const auto [a, b] = parse_frame_range(opt.frames, m.frame_count());
    m = trim(m, a, b);
  }
  if (opt.rate > 0) check_resample_size(m, opt.rate);
  if (opt.mirror) m = mirror_motion(m);
  if (opt.rate > 0) m = resample(m, opt.rate);
  if (extension_of(out) == ".glb") {
    write_glb(out, m);
    return m;
  }
  BvhWriteOptions w;
  // Keep the file's own channel layout (and units) unless it cannot hold the data.
  w.channels = source.channels;
  w.scale = 1.0 / source.report.scale;
  try {
    write_bvh(out, m, w);
  } catch (const Error&) {
    w.channels.clear();
    write_bvh(out, m, w);
  }
  return m;
}

std::string motion_info_text(const BvhFile& f) {
  const Motion& m = f.motion;
  const auto body = measure_body(m.skeleton);
  std::string s;
  char buf[512];
  const auto line = [&](const char* fmt, auto... args) {
    std::snprintf(buf, sizeof buf, fmt, args...);
    s += buf;
  };
  line("joints:     %d\n", m.joint_count());
  line("frames:     %d at %.4g Hz (%.3f s)%s\n", m.frame_count(), m.fps, m.duration(),
       f.report.dropped_first_frame ? ", frame 0 dropped" : "");
  line("units:      x%.6g to metres (%s)\n", f.report.scale, f.report.scale_reason.c_str());
  line("height:     %.3f m standing (rest pose), hips %.3f m, leg %.3f m, arm %.3f m\n", body.standing_height,
       body.hip_height, body.leg_length, body.arm_length);
  if (body.standing_height < 1.4 || body.standing_height > 2.0)
    s += "            note: a standing height outside 1.4-2.0 m suggests wrong units (see --scale)\n";
  if (f.report.repaired_zero_frames)
    line("repaired:   %d all-zero frame(s) replaced by the nearest real frame\n", f.report.repaired_zero_frames);
  for (const auto& w : f.report.warnings) s += "warning:    " + w + "\n";
  s += "roles:\n";
  for (int r = 0; r < kRoleCount; ++r) {
    const int idx = m.skeleton.roles.joint[static_cast<std::size_t>(r)];
    line("  %-15s %s\n", std::string(role_name(static_cast<Role>(r))).c_str(),
         idx >= 0 ? m.skeleton.names[static_cast<std::size_t>(idx)].c_str() : "(not found)");
  }
  s += "hierarchy:\n";
  for (int i = 0; i < m.joint_count(); ++i) {
    int depth = 0;
    for (int p = m.skeleton.parents[static_cast<std::size_t>(i)]; p >= 0; p = m.skeleton.parents[static_cast<std::size_t>(p)]) ++depth;
    s += std::string(2 + 2 * static_cast<std::size_t>(depth), ' ') + m.skeleton.names[static_cast<std::size_t>(i)] + "\n";
  }
  return s;
}

nlohmann::json motion_info_json(const BvhFile& f) {
  const Motion& m = f.motion;
  const auto body = measure_body(m.skeleton);
  const auto name = [&](int idx) {
    return idx >= 0 ? nlohmann::json(m.skeleton.names[static_cast<std::size_t>(idx)]) : nlohmann::json(nullptr);
  };
  nlohmann::json j;
  j["joints"] = m.joint_count();
  j["frames"] = m.frame_count();
  j["fps"] = rounded(m.fps, 1e-3);
  j["frame_time_s"] = m.fps > 0 ? 1.0 / m.fps : 0.0;
  j["duration_s"] = rounded(m.duration(), 1e-4);
  j["scale_to_metres"] = f.report.scale;
  j["scale_reason"] = f.report.scale_reason;
  j["standing_height_m"] = rounded(body.standing_height, 1e-4);
  j["hip_height_m"] = rounded(body.hip_height, 1e-4);
  j["leg_length_m"] = rounded(body.leg_length, 1e-4);
  j["arm_length_m"] = rounded(body.arm_length, 1e-4);
  j["repaired_zero_frames"] = f.report.repaired_zero_frames;
  nlohmann::json roles = nlohmann::json::object();
  for (int r = 0; r < kRoleCount; ++r)
    roles[std::string(role_name(static_cast<Role>(r)))] = name(m.skeleton.roles.joint[static_cast<std::size_t>(r)]);
  j["roles"] = roles;
  nlohmann::json joints = nlohmann::json::array();
  for (int i = 0; i < m.joint_count(); ++i) {
    const auto iu = static_cast<std::size_t>(i);
    joints.push_back({{"name", m.skeleton.names[iu]}, {"parent", name(m.skeleton.parents[iu])}, {"mirror", name(m.skeleton.mirror[iu])}});
  }
  j["joint_list"] = joints;
  j["warnings"] = f.report.warnings;
  return j;
}

}  // namespace legwork::io

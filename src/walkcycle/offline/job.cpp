#include <legwork/walkcycle/offline/job.hpp>

#include <legwork/core/fk.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/core/rotation.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/io/gltf.hpp>
#include <legwork/io/motion_file.hpp>
#include <legwork/io/text.hpp>
#include <legwork/render/render.hpp>
#include <legwork/walkcycle/offline/keys.hpp>
#include <legwork/walkcycle/offline/extract.hpp>
#include <legwork/walkcycle/offline/measure.hpp>
#include <legwork/walkcycle/offline/report.hpp>
#include <legwork/render/compose.hpp>

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

namespace legwork::walkcycle {
namespace {

namespace fs = std::filesystem;
namespace wc = legwork::walkcycle;
using nlohmann::json;

std::string stem_of(const std::string& path) {
  fs::path p(path);
  return (p.parent_path() / p.stem()).string();
}

// Key-pose sheet: the five poses of the step, front and side, inactive ones x-ray.
void write_sheet(const wc::CycleModel& m, const WalkJob& a, const std::string& name) {
  render::SheetOptions o;
  o.views.clear();
  for (const auto& v : io::split_commas(a.sheet_views)) o.views.push_back(render::parse_view(v));
  if (o.views.empty()) throw Error("--sheet-views: give at least one view");
  o.spacing = a.spacing;
  o.face_forward = false;
  const double half = m.half_cycle();
  const char* names[] = {"contact", "down", "pass", "up", "contact (mirror)"};
  for (int i = 0; i < 5; ++i) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%s  f%g", names[i], i < 4 ? m.key_frames[static_cast<std::size_t>(i)] : half);
    o.labels.push_back(buf);
    if (!a.active.empty() && (a.active == names[i] || (i == 4 && a.active == "next"))) o.active = i;
  }
  if (!a.active.empty() && o.active < 0)
    throw Error("--active '" + a.active + "': expected contact, down, pass, up or next");
  o.title = "walk '" + name + "': key poses of one step (" + std::to_string(m.frames_per_cycle) + " frames per cycle)";
  io::prepare_output(a.sheet);
  render::render_contact_sheet(m.skeleton, {m.step_keys.begin(), m.step_keys.end()}, o, a.sheet);
  io::announce("key-pose sheet", a.sheet);
}

// A joint's arc: CSV, side + front pictures over translucent key poses, the printed line and report entry.
json write_arc(const wc::CycleModel& m, const std::string& joint_name, const std::string& prefix) {
  const wc::ArcFigures arc = wc::arc_figures(m, joint_name);
  const std::string base = prefix + "_arc_" + arc.name;
  io::prepare_output(base);
  io::write_text_file(base + ".csv", wc::arc_csv(arc));
  render::Curve c;
  c.points = arc.fine.points;
  c.points.push_back(arc.fine.points.front());
  c.width = 2.0;
  for (std::size_t k = 0; k < arc.fine.key_indices.size(); ++k) {
    c.marks.push_back(arc.fine.key_indices[k]);
    c.mark_labels.push_back(std::string(1, "CDPU"[k % 4]) + (k >= 4 ? "'" : ""));
  }
  c.label = arc.name;
  render::render_arc(m.skeleton, {m.step_keys.begin(), m.step_keys.begin() + 4}, c, wc::arc_title(arc), base);
  io::announce("arc", base + ".svg");
  std::printf("%s", wc::arc_summary(arc).c_str());
  return wc::arc_report(arc, base + ".csv");
}

void write_slide_video(const wc::CycleModel& m, double spacing, const std::string& path) {
  render::SlideVideo v;
  v.key_poses.assign(m.step_keys.begin(), m.step_keys.end());
  v.labels = {"contact", "down", "pass", "up", "contact'"};
  v.key_times = {m.key_frames[0], m.key_frames[1], m.key_frames[2], m.key_frames[3], m.half_cycle()};
  v.sample = [&m](double t, PoseRef out) { wc::sample_cycle(m, t, out); };
  v.duration = m.half_cycle();
  v.spacing = spacing;
  io::prepare_output(path);
  render::render_slide_video(m.skeleton, v, path);
  io::announce("sliding video", path);
}

void write_top(const wc::WalkResult& w, const wc::Path* path, const std::string& out, const std::string& name) {
  std::vector<render::Footprint> prints;
  for (const auto& st : w.footsteps) prints.push_back({0.5 * (st.heel + st.ball), st.heading, st.left});
  char title[160];
  std::snprintf(title, sizeof title, "walk '%s' from above: %d steps, %zu footprints, turning %.0f deg", name.c_str(), w.steps,
                w.footsteps.size(), rad2deg(w.turning));
  io::prepare_output(out);
  render::render_walk_top(w.motion, path ? &path->points : nullptr, prints, title, out);
  io::announce("top view", out);
}

wc::WalkKeys load_keys(const WalkJob& a, Skeleton& skel) {
  if (!a.from_bvh.empty()) {
    io::BvhReadOptions o;
    o.drop_first_frame = false;
    auto clip = io::read_bvh(a.from_bvh, o);
    std::vector<int> frames;
    for (const auto& s : io::split_commas(a.keys)) {
      char* end = nullptr;
      const long v = std::strtol(s.c_str(), &end, 10);
      if (end != s.c_str() + s.size()) throw Error("--keys '" + a.keys + "': with --from-bvh, give four frame numbers like 0,3,6,9");
      frames.push_back(static_cast<int>(v));
    }
    skel = clip.motion.skeleton;
    return wc::keys_from_frames(clip.motion, frames, a.frames > 0 ? a.frames : 24, 24.0);
  }
  wc::WalkFile w = wc::load_walk(a.keys, a.skeleton);
  skel = std::move(w.skeleton);
  return std::move(w.keys);
}

// The walk's keys: read (or taken from a clip), retimed and shifted as asked.
wc::WalkKeys prepared_keys(const WalkJob& a, Skeleton& skel) {
  if (a.frames_given && (a.frames % 2 || a.frames < 8 || a.frames > 10000))
    throw Error("--frames " + std::to_string(a.frames) + ": expected an even number of frames per cycle from 8 to 10000");
  wc::WalkKeys keys = load_keys(a, skel);
  if (a.frames_given) {
    keys = wc::retime(keys, a.frames);
  }
  if (!a.shift.empty()) {
    auto extra = wc::parse_shift_spec(a.shift, skel);
    for (auto [j, d] : extra) {
      bool replaced = false;
      for (auto& [k, e] : keys.shift)
        if (k == j) e = d, replaced = true;
      if (!replaced) keys.shift.emplace_back(j, d);
    }
  }
  return keys;
}

// A walk is held in memory while it is made: one longer than
// WalkOptions::max_frames is refused before any work, naming the option.
void check_walk_size(const wc::CycleModel& model, const wc::Path& path, const wc::WalkOptions& wo, const WalkJob& a) {
  const double frames = wc::expected_walk_frames(model, path.length(), wo);
  if (frames <= wo.max_frames) return;
  auto num = [](double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return std::string(buf);
  };
  const std::string option = a.steps >= 0 ? "--steps " + std::to_string(a.steps)
                             : a.straight > 0 ? "--straight " + num(a.straight)
                             : !a.path.empty() ? "--path '" + a.path + "'" : "--svg-path";
  const double fps = wo.fps > 0 ? wo.fps : model.fps;
  throw Error(option + " makes a walk of about " + std::to_string(std::llround(std::min(frames, 1e18))) + " frames at " +
              num(fps) + " fps; the limit is " + std::to_string(wo.max_frames) +
              " frames (a walk is made in memory): walk fewer steps or at a lower --fps");
}

// The walk (along a path, straight, a number of steps) or the in-place
// cycle; its figures printed and added to the report.
Motion walk_or_cycle(const wc::CycleModel& model, const WalkJob& a, const std::string& name, json& report, bool& walked,
                     wc::Ground& ground) {
  std::unique_ptr<wc::Path> path;
  wc::WalkOptions wo;
  wo.fps = a.fps;
  wo.root = a.root == "pivot" ? wc::RootMotion::Pivot : wc::RootMotion::Smooth;
  wo.turn_on_ball = a.stance_turn != "twist";
  wo.fit_stairs_stride = a.stairs_stride != "keep";
  if (!a.path.empty()) path = std::make_unique<wc::Path>(wc::read_path(a.path));
  else if (!a.svg_path.empty()) path = std::make_unique<wc::Path>(wc::parse_svg_path(a.svg_path, "--svg-path"));
  else if (a.straight > 0) path = std::make_unique<wc::Path>(wc::straight_path(a.straight));
  else if (a.steps >= 0) {
    path = std::make_unique<wc::Path>(wc::straight_path(1e6));  // (the report gives the length walked)
    wo.steps = a.steps;
  }
  Motion result;
  if (path) {
    check_walk_size(model, *path, wo, a);
    const auto t0 = std::chrono::steady_clock::now();
    wc::WalkResult w = wc::walk_path(model, *path, wo);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    std::string text;
    wc::add_walk_report(model, w, ms, report, text);
    std::printf("%s", text.c_str());
    if (!a.top.empty()) write_top(w, path.get(), a.top, name);
    result = std::move(w.motion);  // (not a copy: a long walk's motion is hundreds of MB)
    ground = path->ground;
  } else {
    result = wc::bake_cycle(model);
    wc::add_in_place_report(result, report);
    if (!a.top.empty()) throw Error("--top needs a walk: give --path, --straight or --steps");
  }
  walked = path != nullptr;
  return result;
}

// The ground under a walk as the pictures draw it: its height along the
// root's track on the floor, every centimetre (a stair's riser becomes two
// points a centimetre apart), as wide as a body either side of the walk.
render::GroundStrip ground_strip(const wc::Ground& ground, const Motion& walk) {
  render::GroundStrip strip;
  if (ground.flat() || walk.frame_count() < 2) return strip;
  const Vec3 first = horizontal(walk.frame(0).translations[0]), last = horizontal(walk.frame(walk.frame_count() - 1).translations[0]);
  if ((last - first).norm() > 1e-6) strip.across = Vec3::UnitY().cross(last - first).normalized();
  auto add = [&](const Vec3& p) { strip.profile.push_back(Vec3(p.x(), ground.height(p), p.z())); };
  Vec3 at = first;
  add(at);
  for (int f = 1; f < walk.frame_count(); ++f) {
    const Vec3 next = horizontal(walk.frame(f).translations[0]);
    const int pieces = static_cast<int>(std::ceil((next - at).norm() / 0.01));
    for (int k = 1; k <= pieces; ++k) add(at + (next - at) * (static_cast<double>(k) / pieces));
    if (pieces > 0) at = next;
  }
  return strip;
}

void write_walk_video(const Motion& result, const Skeleton& skel, const WalkJob& a, const std::string& name, const wc::Ground& ground) {
  if (a.video.empty()) return;
  render::VideoOptions vo;
  vo.ground = ground_strip(ground, result);
  vo.camera.view = render::parse_view(a.video_view);
  vo.camera.width = 960;
  vo.camera.height = 540;
  vo.fps = 30;
  vo.trace_joint = skel.roles[Role::LeftToe] >= 0 ? skel.roles[Role::LeftToe] : skel.roles[Role::LeftAnkle];
  vo.title = "walk '" + name + "'";
  io::prepare_output(a.video);
  render::render_video(result, vo, a.video);
  io::announce("video", a.video);
}

}  // namespace

void run_walk_job(const WalkJob& a) {
  if (a.keys.empty()) throw Error("walkcycle: --keys walk.json is required (or --from-bvh clip.bvh --keys 0,3,6,9)");
  int sources = (!a.path.empty()) + (!a.svg_path.empty()) + (a.straight > 0) + (a.steps >= 0);
  if (sources > 1 && !(sources == 2 && a.steps >= 0 && a.straight > 0))
    throw Error("walkcycle: give one of --path, --svg-path, --straight, --steps");
  if (a.out.empty() && a.cycle_out.empty() && a.sheet.empty() && a.arc.empty() && a.report.empty() && a.video.empty() &&
      a.slide_video.empty() && a.top.empty())
    throw Error("walkcycle: nothing to write; give --out (and/or --cycle-out, --sheet, --arc, --video, --report)");
  Skeleton skel;
  const wc::WalkKeys keys = prepared_keys(a, skel);
  const std::string name = keys.name.empty() ? fs::path(a.keys).stem().string() : keys.name;
  std::fprintf(stderr, "walkcycle: building the cycle of '%s' (%d frames at %g fps)\n", name.c_str(), keys.frames_per_cycle, keys.fps);
  const wc::CycleModel model = wc::build_cycle(skel, keys);
  std::string text;
  json report = wc::cycle_report(model, name, text);
  std::printf("%s", text.c_str());

  if (!a.cycle_out.empty()) io::write_motion(io::prepare_output(a.cycle_out, "--cycle-out"), wc::bake_cycle(model), "in-place cycle", "--cycle-out"), io::announce("in-place cycle", a.cycle_out);
  if (!a.sheet.empty()) write_sheet(model, a, name);
  if (!a.arc.empty()) {
    const std::string prefix = !a.arc_out.empty() ? a.arc_out : stem_of(!a.out.empty() ? a.out : (!a.sheet.empty() ? a.sheet : a.report));
    report["arcs"] = json::array();
    for (const auto& j : io::split_commas(a.arc)) report["arcs"].push_back(write_arc(model, j, prefix));
  }
  if (!a.slide_video.empty()) write_slide_video(model, a.spacing, a.slide_video);

  bool walked = false;
  wc::Ground ground;
  const Motion result = walk_or_cycle(model, a, name, report, walked, ground);
  if (!a.out.empty()) {
    io::write_motion(io::prepare_output(a.out, "--out"), result, walked ? "walk" : "in-place cycle", "--out");
    io::announce(walked ? "walk" : "in-place cycle", a.out);
  }
  write_walk_video(result, skel, a, name, ground);
  if (!a.report.empty()) {
    io::prepare_output(a.report);
    io::write_text_file(a.report, report.dump(2) + "\n");
    io::announce("report", a.report);
  }
}



void run_extract_job(const ExtractJob& a) {
  io::BvhReadOptions o;
  o.drop_first_frame = true;
  std::fprintf(stderr, "walkcycle extract: reading %s\n", a.input.c_str());
  const auto clip = io::read_bvh(a.input, o);
  wc::ExtractOptions eo;
  eo.frames_per_cycle = a.frames;
  eo.fps = a.fps;
  const wc::Extraction ex = wc::extract_walk(clip.motion, eo);
  wc::WalkKeys keys = ex.keys;
  keys.name = a.name.empty() ? fs::path(a.input).stem().string() : a.name;
  keys.skeleton_path = fs::relative(fs::absolute(a.input), fs::absolute(fs::path(a.out).parent_path().empty() ? "." : fs::path(a.out).parent_path())).string();
  io::prepare_output(a.out);
  wc::write_walk_keys(a.out, keys, clip.motion.skeleton);
  std::printf("%s", wc::extraction_summary(ex, keys).c_str());
  if (!ex.warning.empty()) std::fprintf(stderr, "warning: %s: %s; the keys are written, check them\n", a.input.c_str(), ex.warning.c_str());
  io::announce("key poses", a.out);
  if (!a.sheet.empty()) {
    WalkJob wa;
    wa.sheet = a.sheet;
    write_sheet(wc::build_cycle(clip.motion.skeleton, keys), wa, keys.name);
  }
  if (!a.report.empty()) {
    const json r = wc::extraction_report(ex, clip.motion, a.input);
    io::prepare_output(a.report);
    io::write_text_file(a.report, r.dump(2) + "\n");
    io::announce("report", a.report);
  }
}

}  // namespace legwork::walkcycle

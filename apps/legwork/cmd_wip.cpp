// legwork wip / wip eval: walking-in-place legs from tracked ankle heights,
// and their evaluation on real walking.
#include "command.hpp"

#include <legwork/core/interpolate.hpp>
#include <legwork/core/measure.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/io/gltf.hpp>
#include <legwork/io/text.hpp>
#include <legwork/io/tracker_csv.hpp>
#include <legwork/render/plot.hpp>
#include <legwork/render/render.hpp>
#include <legwork/wip/eval.hpp>

#include <cairo.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <unistd.h>

namespace legwork::cli {
namespace {

namespace fs = std::filesystem;
using namespace legwork::wip;

// ---- locating the sample data ---------------------------------------------

// The repo root: the first of the working directory and the executable's
// ancestors that holds data/cmu/bvh/walking.
fs::path find_repo_root() {
  std::vector<fs::path> starts{fs::current_path()};
  char buf[4096];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n > 0) starts.push_back(fs::path(std::string(buf, static_cast<std::size_t>(n))).parent_path());
  for (auto p : starts)
    for (int up = 0; up < 5 && !p.empty(); ++up, p = p.parent_path())
      if (fs::exists(p / "data" / "cmu" / "bvh" / "walking" / "07_01.bvh")) return p;
  return {};
}

std::string default_avatar() {
  const fs::path root = find_repo_root();
  if (root.empty())
    throw Error("--avatar not given and the default avatar data/cmu/bvh/walking/07_01.bvh was not found "
                "(run from the repository or pass --avatar FILE.bvh)");
  return (root / "data" / "cmu" / "bvh" / "walking" / "07_01.bvh").string();
}

Motion load_bvh_motion(const std::string& path, bool keep_first) {
  io::BvhReadOptions opt;
  opt.drop_first_frame = !keep_first;
  auto f = io::read_bvh(path, opt);
  for (const auto& w : f.report.warnings) std::cerr << "legwork: " << path << ": " << w << "\n";
  return std::move(f.motion);
}

// ---- options ----------------------------------------------------------------

struct WipArgs {
  std::string input, avatar, out, csv, plot, baseline, clip, tracker_out, strip;
  bool synthetic = false, keep_first = false, no_adaptive = false, raw_height = false;
  std::string calibrate = "auto", speed_model = "step";
  double rate = 30, cutoff = 4, h1 = 0.1, v1 = 0.2, v2 = 0.6, stop_time = 1.5, max_speed = 3.5, heading = 0;
  double step_length = 0.6;
  SyntheticOptions syn;
  // eval
  std::string data, eval_out;
  double noise = 0.015, drop_rate = 0.02;
  unsigned long long seed = 1;
  int limit = 0;
};

WipParams params_from(const WipArgs& a, double rate) {
  WipParams p;
  p.signal.rate = rate;
  p.signal.cutoff = a.cutoff;
  p.gait.h1 = a.h1;
  p.gait.v1 = a.v1;
  p.gait.v2 = a.v2;
  p.gait.adaptive = !a.no_adaptive;
  p.mapping.normalise_height = !a.raw_height;
  p.mapping.stop_time = a.stop_time;
  p.mapping.max_speed = a.max_speed;
  p.mapping.step_length = a.step_length;
  if (a.speed_model == "step") p.mapping.speed_model = SpeedModel::StepSpeed;
  else if (a.speed_model == "frequency") p.mapping.speed_model = SpeedModel::StepFrequency;
  else throw Error("--speed-model '" + a.speed_model + "': expected 'step' (Bruno et al.) or 'frequency' (GUD-WIP)");
  if (!(rate > 0) || !(a.cutoff > 0) || a.cutoff >= rate / 2)
    throw Error("--cutoff " + std::to_string(a.cutoff) + " Hz must be between 0 and half the sample rate (" +
                std::to_string(rate) + " Hz)");
  return p;
}

void add_method_options(CLI::App* cmd, WipArgs& a) {
  cmd->add_option("--cutoff", a.cutoff, "low-pass cutoff, Hz (default 4)")->check(CLI::PositiveNumber);
  cmd->add_option("--h1", a.h1, "lift height threshold H1, m (default 0.1)")->check(CLI::PositiveNumber);
  cmd->add_option("--v1", a.v1, "rise velocity threshold V1, m/s (default 0.2)")->check(CLI::PositiveNumber);
  cmd->add_option("--v2", a.v2, "descent velocity threshold V2, m/s (default 0.6)")->check(CLI::PositiveNumber);
  cmd->add_flag("--no-adaptive", a.no_adaptive,
                "use H1/V1/V2 as fixed thresholds (default: they shrink toward the user's own step)");
  cmd->add_flag("--raw-height", a.raw_height,
                "feed the raw height into the equations (default: normalised by the user's step apex)");
  cmd->add_option("--stop-time", a.stop_time, "double support longer than this stops the legs, s (default 1.5)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--step-length", a.step_length, "maximum step length S for a 0.8 m leg, m (default 0.6; scaled to the avatar)")
      ->check(CLI::PositiveNumber);
}

// ---- frame CSV and plots -------------------------------------------------

void write_frames_csv(const std::string& path, std::span<const WipFrame> frames) {
  std::ostringstream o;
  o << "time,phase_left,phase_right,h_left,h_right,v_left,v_right,confidence_left,confidence_right,h1_left,h1_right,"
       "z_target_left,z_target_right,z_left,z_right,y_left,y_right,root_offset,speed,distance,walking,events_left,"
       "events_right,root_x,root_y,root_z\n";
  char buf[512];
  for (const auto& f : frames) {
    std::snprintf(buf, sizeof buf,
                  "%.4f,%s,%s,%.5f,%.5f,%.4f,%.4f,%.3f,%.3f,%.4f,%.4f,%.5f,%.5f,%.5f,%.5f,%.5f,%.5f,%.5f,%.4f,%.4f,%d,%u,%u,"
                  "%.4f,%.4f,%.4f\n",
                  f.time, std::string(phase_name(f.phase[0])).c_str(), std::string(phase_name(f.phase[1])).c_str(), f.h[0],
                  f.h[1], f.v[0], f.v[1], f.confidence[0], f.confidence[1], f.h1[0], f.h1[1], f.z_target[0],
                  f.z_target[1], f.z[0], f.z[1], f.y[0], f.y[1], f.root_offset, f.speed, f.distance, f.walking ? 1 : 0,
                  f.events[0], f.events[1], f.root_position.x(), f.root_position.y(), f.root_position.z());
    o << buf;
  }
  io::write_text_file(path, o.str());
}

// Swing intervals of one foot as plot bands.
std::vector<render::Band> swing_bands(std::span<const SwingEvent> swings, int foot, render::Rgb color,
                                      const std::string& label, double alpha = 0.18) {
  std::vector<render::Band> out;
  for (const auto& s : swings)
    if (s.foot == foot) out.emplace_back(s.off, s.strike, color, label, alpha);
  return out;
}

std::vector<double> column(std::span<const WipFrame> frames, double (*get)(const WipFrame&)) {
  std::vector<double> v;
  v.reserve(frames.size());
  for (const auto& f : frames) v.push_back(get(f));
  return v;
}

// Stacks PNG images vertically into one PNG (white background).
void stack_pngs(const std::vector<std::string>& parts, const std::string& out) {
  std::vector<cairo_surface_t*> imgs;
  int w = 0, h = 0;
  for (const auto& p : parts) {
    cairo_surface_t* s = cairo_image_surface_create_from_png(p.c_str());
    if (cairo_surface_status(s) != CAIRO_STATUS_SUCCESS) {
      for (auto* i : imgs) cairo_surface_destroy(i);
      cairo_surface_destroy(s);
      throw Error("cannot read the intermediate picture " + p);
    }
    w = std::max(w, cairo_image_surface_get_width(s));
    h += cairo_image_surface_get_height(s);
    imgs.push_back(s);
  }
  cairo_surface_t* dst = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
  cairo_t* cr = cairo_create(dst);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  int y = 0;
  for (auto* s : imgs) {
    cairo_set_source_surface(cr, s, (w - cairo_image_surface_get_width(s)) / 2.0, y);
    cairo_paint(cr);
    y += cairo_image_surface_get_height(s);
    cairo_surface_destroy(s);
  }
  cairo_destroy(cr);
  const auto st = cairo_surface_write_to_png(dst, out.c_str());
  cairo_surface_destroy(dst);
  if (st != CAIRO_STATUS_SUCCESS) throw Error("cannot write " + out);
}

// The document's Figure 2-like curves plus a side-view strip of the avatar.
void write_phase_plot(const std::string& path, const std::string& title, std::span<const WipFrame> frames,
                      const Motion& avatar, const std::vector<int>& strip, const std::vector<double>* baseline_z,
                      const GaitParams& gait) {
  if (io::extension_of(path) != ".png") throw Error("--plot '" + path + "' must end in .png");
  if (frames.empty()) throw Error("nothing to plot: no frames");
  const auto t = column(frames, [](const WipFrame& f) { return f.time; });
  const auto det = detected_swings(frames);
  render::LinePlot p;
  p.title = title;
  p.x_label = "time (s)";
  p.panel_height = 170;
  auto& ph = p.panels.emplace_back();
  ph.title = "ankle height above floor (filtered) with detected swings";
  ph.y_label = "h (m)";
  ph.series.emplace_back("left", t, column(frames, [](const WipFrame& f) { return f.h[0]; }), render::kLeftColor);
  ph.series.emplace_back("right", t, column(frames, [](const WipFrame& f) { return f.h[1]; }), render::kRightColor);
  ph.series.emplace_back("H1 in use (left)", t, column(frames, [](const WipFrame& f) { return f.h1[0]; }),
                         render::Rgb{0.4, 0.4, 0.45});
  ph.series.back().dashed = true;
  for (auto& b : swing_bands(det, 0, render::kLeftColor, "left swing")) ph.bands.push_back(b);
  for (auto& b : swing_bands(det, 1, render::kRightColor, "right swing")) ph.bands.push_back(b);
  auto& pv = p.panels.emplace_back();
  pv.title = "vertical velocity";
  pv.y_label = "v (m/s)";
  pv.series.emplace_back("left", t, column(frames, [](const WipFrame& f) { return f.v[0]; }), render::kLeftColor);
  pv.series.emplace_back("right", t, column(frames, [](const WipFrame& f) { return f.v[1]; }), render::kRightColor);
  pv.ref_lines.emplace_back(gait.v1, "V1");
  pv.ref_lines.emplace_back(-gait.v2, "-V2");
  auto& pp = p.panels.emplace_back();
  pp.title = "gait phase (0 double support, 1 initial, 2 mid, 3 terminal swing)";
  pp.y_label = "phase";
  pp.series.emplace_back("left", t, column(frames, [](const WipFrame& f) { return double(int(f.phase[0])); }),
                         render::kLeftColor);
  pp.series.emplace_back("right", t, column(frames, [](const WipFrame& f) { return int(f.phase[1]) + 0.08; }),
                         render::kRightColor);
  pp.y_min = -0.2;
  pp.y_max = 3.3;
  auto& pz = p.panels.emplace_back();
  pz.title = "IK-target depth (forward +, relative to the pelvis)";
  pz.y_label = "z (m)";
  pz.series.emplace_back("left", t, column(frames, [](const WipFrame& f) { return f.z[0]; }), render::kLeftColor);
  pz.series.emplace_back("right", t, column(frames, [](const WipFrame& f) { return f.z[1]; }), render::kRightColor);
  if (baseline_z) {
    pz.series.emplace_back("left, key-frame baseline", t, baseline_z[0], render::kLeftColor);
    pz.series.back().dashed = true;
  }
  auto& ps = p.panels.emplace_back();
  ps.title = "forward speed and body drop";
  ps.y_label = "m/s, m";
  ps.series.emplace_back("speed (m/s)", t, column(frames, [](const WipFrame& f) { return f.speed; }));
  ps.series.emplace_back("root offset (m)", t, column(frames, [](const WipFrame& f) { return f.root_offset; }));
  if (strip.empty() || avatar.frame_count() == 0) {
    render::plot_lines(p, path);
    return;
  }
  const std::string tmp_plot = path + ".curves.tmp.png", tmp_strip = path + ".strip.tmp.png";
  render::plot_lines(p, tmp_plot);
  std::vector<Pose> poses;
  std::vector<std::string> labels;
  for (int f : strip) {
    if (f < 0 || f >= avatar.frame_count()) continue;
    Pose pose(avatar.skeleton);
    auto fr = avatar.frame(f);
    std::copy(fr.rotations.begin(), fr.rotations.end(), pose.rotations.begin());
    std::copy(fr.translations.begin(), fr.translations.end(), pose.translations.begin());
    poses.push_back(pose);
    char lab[64];
    static const char* kShort[] = {"DS", "IS", "MS", "TS"};
    std::snprintf(lab, sizeof lab, "%.2fs L:%s R:%s", frames[static_cast<std::size_t>(f)].time,
                  kShort[int(frames[static_cast<std::size_t>(f)].phase[0])],
                  kShort[int(frames[static_cast<std::size_t>(f)].phase[1])]);
    labels.push_back(lab);
  }
  render::SheetOptions so;
  so.views = {render::View::Side};
  so.labels = labels;
  so.panel_height = 300;
  so.face_forward = false;
  so.title = "avatar, side view (DS double support, IS/MS/TS swing)";
  render::render_contact_sheet(avatar.skeleton, poses, so, tmp_strip);
  stack_pngs({tmp_plot, tmp_strip}, path);
  fs::remove(tmp_plot);
  fs::remove(tmp_strip);
}

// Frames for the side strip: "a,b,c" or about six spread over the walking part.
std::vector<int> strip_frames(const std::string& spec, std::span<const WipFrame> frames) {
  std::vector<int> out;
  if (!spec.empty()) {
    std::stringstream ss(spec);
    std::string item;
    while (std::getline(ss, item, ',')) {
      try {
        out.push_back(std::stoi(item));
      } catch (...) {
        throw Error("--strip '" + spec + "': expected frame numbers separated by commas");
      }
    }
    for (int f : out)
      if (f < 0 || f >= static_cast<int>(frames.size()))
        throw Error("--strip frame " + std::to_string(f) + " is outside 0:" + std::to_string(frames.size() - 1));
    return out;
  }
  // Six consecutive phase-change frames of the first well-established steps.
  int first_walk = -1;
  for (std::size_t i = 0; i < frames.size(); ++i)
    if (frames[i].walking) {
      first_walk = static_cast<int>(i);
      break;
    }
  if (first_walk < 0) first_walk = 0;
  const int span = std::max(1, static_cast<int>(std::lround(1.2 * frames.size() / std::max(1.0, frames.back().time))));
  for (int k = 0; k < 6; ++k)
    out.push_back(std::min(static_cast<int>(frames.size()) - 1, first_walk + span + k * span / 5));
  return out;
}

// ---- legwork wip -----------------------------------------------------------

struct Input {
  std::vector<TrackerSample> samples;
  double rate = 30;
  std::string what;
  bool still_start = true;  // may be calibrated from a standing start
  std::vector<SwingEvent> truth;
};

Input load_input(const WipArgs& a) {
  Input in;
  if (a.synthetic == !a.input.empty())
    throw Error("give exactly one of --input FILE (.csv or .bvh) and --synthetic");
  if (a.synthetic) {
    SyntheticOptions o = a.syn;
    o.rate = a.rate;
    auto tr = synthetic_stepping(o);
    in.samples = std::move(tr.samples);
    in.truth = std::move(tr.swings);
    in.rate = o.rate;
    char buf[200];
    std::snprintf(buf, sizeof buf, "synthetic in-place stepping (%.1f steps/s, %.2f m lift, noise %.1f cm, seed %llu)",
                  o.cadence, o.step_height, 100 * o.noise, static_cast<unsigned long long>(o.seed));
    in.what = buf;
    return in;
  }
  const std::string ext = io::extension_of(a.input);
  if (ext == ".csv") {
    const auto table = io::read_tracker_csv(a.input);
    in.samples = samples_from_table(table, a.input);
    if (in.samples.size() < 3) throw Error(a.input + ": fewer than 3 samples");
    std::vector<double> dts;
    for (std::size_t i = 1; i < in.samples.size(); ++i) dts.push_back(in.samples[i].time - in.samples[i - 1].time);
    std::nth_element(dts.begin(), dts.begin() + static_cast<std::ptrdiff_t>(dts.size() / 2), dts.end());
    in.rate = 1.0 / dts[dts.size() / 2];
    in.what = "tracker CSV " + a.input;
  } else if (ext == ".bvh") {
    const Motion m = load_bvh_motion(a.input, a.keep_first);
    in.samples = samples_from_motion(m, a.rate);
    in.truth = true_swings(m);
    in.rate = a.rate;
    in.still_start = false;
    in.what = "ankles of " + a.input + " (" + std::to_string(m.frame_count()) + " frames, sampled at " +
              std::to_string(static_cast<int>(a.rate)) + " Hz)";
  } else {
    throw Error("--input '" + a.input + "' must be a tracker .csv or a .bvh motion");
  }
  return in;
}

// Copies the baseline clip's local rotations onto the avatar, joint by name.
void baseline_to_avatar(const Skeleton& clip, const Pose& from, const Skeleton& avatar, double root_scale, PoseRef to) {
  for (int j = 0; j < avatar.joint_count(); ++j) {
    const int c = clip.find(avatar.names[static_cast<std::size_t>(j)]);
    if (c < 0) continue;
    to.rotations[static_cast<std::size_t>(j)] = from.rotations[static_cast<std::size_t>(c)];
  }
  to.translations[0] = from.translations[0] * root_scale;
}

void run_wip_command(const WipArgs& a) {
  if (a.out.empty()) throw Error("--out FILE (.glb or .bvh) is required");
  const std::string ext = io::extension_of(a.out);
  if (ext != ".glb" && ext != ".bvh") throw Error("--out '" + a.out + "' must end in .glb or .bvh");
  if (!a.baseline.empty() && a.baseline != "keyframe")
    throw Error("--baseline '" + a.baseline + "': the only baseline is 'keyframe'");
  const std::string avatar_path = a.avatar.empty() ? default_avatar() : a.avatar;
  const Motion avatar_file = load_bvh_motion(avatar_path, a.keep_first);
  const Input in = load_input(a);
  const WipParams params = params_from(a, in.rate);
  WipModel model;
  try {
    model = make_wip_model(avatar_file.skeleton, params);
  } catch (const Error& e) {
    throw Error("--avatar " + avatar_path + ": " + e.what());
  }
  std::cerr << "legwork wip: " << in.what << "\n";
  std::fprintf(stderr, "legwork wip: avatar %s, leg %.3f m, step length S %.3f m\n", avatar_path.c_str(),
               model.leg_length, model.shape.S);

  RunOptions ro;
  ro.calibrate = a.calibrate == "on" || (a.calibrate == "auto" && in.still_start);
  if (a.calibrate != "on" && a.calibrate != "off" && a.calibrate != "auto")
    throw Error("--calibrate '" + a.calibrate + "': expected auto, on or off");
  WipRun run;
  try {
    run = run_wip(model, in.samples, ro);
  } catch (const Error& e) {
    throw Error(std::string(e.what()) + " [--calibrate off uses a rolling floor instead]");
  }
  if (ro.calibrate) std::cerr << "legwork wip: " << run.calibration.message << "\n";
  else std::cerr << "legwork wip: no calibration: rolling floor estimate\n";

  Motion out = run.motion;
  std::vector<double> baseline_z[2];
  if (!a.baseline.empty() || !a.plot.empty()) {
    const std::string clip_path = a.clip.empty() ? default_avatar() : a.clip;
    const Motion cycle = extract_walk_cycle(load_bvh_motion(clip_path, false));
    const auto bm = make_keyframe_baseline(cycle, model.leg_length);
    auto bs = make_baseline_state(bm);
    const double clip_hip = measure_body(cycle.skeleton).hip_height;
    const double root_scale = clip_hip > 0 ? measure_body(model.skeleton).hip_height / clip_hip : 1.0;
    int missing = 0;
    for (const auto& n : model.skeleton.names) missing += cycle.skeleton.find(n) < 0 ? 1 : 0;
    if (!a.baseline.empty() && missing > model.skeleton.joint_count() / 2)
      throw Error("--baseline keyframe: the walk-cycle clip " + clip_path +
                  " shares too few joint names with the avatar; pass --clip with a BVH on the avatar's skeleton");
    for (std::size_t i = 0; i < run.frames.size(); ++i) {
      update_baseline(bm, run.frames[i].walking, 1.0 / in.rate, bs);
      for (int f = 0; f < 2; ++f) baseline_z[f].push_back(bs.z[f]);
      if (!a.baseline.empty()) {
        auto fr = out.frame(static_cast<int>(i));
        baseline_to_avatar(cycle.skeleton, bs.pose, model.skeleton, root_scale, fr);
        // The baseline moves with the same forward speed as the method.
        fr.translations[0].x() += run.frames[i].root_position.x();
        fr.translations[0].z() += run.frames[i].root_position.z();
      }
    }
    if (!a.baseline.empty()) std::cerr << "legwork wip: output is the key-frame baseline (clip " << clip_path << ")\n";
  }

  if (ext == ".glb") {
    io::GltfOptions g;
    g.animation_name = a.baseline.empty() ? "walking_in_place" : "keyframe_baseline";
    io::write_glb(a.out, out, g);
  } else {
    io::write_bvh(a.out, out);
  }
  int steps = 0;
  for (const auto& f : run.frames) steps += ((f.events[0] | f.events[1]) & kEventFootOff) ? 1 : 0;
  const auto& last = run.frames.back();
  std::printf("%zu frames at %.4g Hz: %d steps detected, walked %.2f m (mean %.2f m/s over %.1f s)\n", run.frames.size(),
              in.rate, steps, last.distance, last.distance / std::max(1e-9, last.time - run.frames.front().time),
              last.time - run.frames.front().time);
  if (!in.truth.empty()) {
    const auto sc = score_steps(detected_swings(run.frames), in.truth, 0.5, last.time - 0.1);
    std::printf("against the input's true steps: precision %.3f, recall %.3f, F1 %.3f, foot-off latency %.0f ms\n",
                sc.precision, sc.recall, sc.f1, sc.off_latency_ms);
  }
  announce(a.baseline.empty() ? "legs" : "key-frame baseline", a.out);
  if (!a.csv.empty()) {
    write_frames_csv(a.csv, run.frames);
    announce("frames", a.csv);
  }
  if (!a.tracker_out.empty()) {
    io::write_tracker_csv(a.tracker_out, table_from_samples(in.samples));
    announce("tracker input", a.tracker_out);
  }
  if (!a.plot.empty()) {
    write_phase_plot(a.plot, "walking in place: " + in.what, run.frames, run.motion, strip_frames(a.strip, run.frames),
                     baseline_z, params.gait);
    announce("phase plot", a.plot);
  }
}

// ---- legwork wip eval ----------------------------------------------------

fs::path default_eval_data(std::string* note) {
  const fs::path root = find_repo_root();
  std::vector<fs::path> shared{fs::current_path() / ".." / "shared" / "data" / "cmu" / "bvh" / "walking"};
  if (!root.empty()) shared.push_back(root.parent_path() / "shared" / "data" / "cmu" / "bvh" / "walking");
  for (const auto& p : shared)
    if (fs::is_directory(p)) return fs::weakly_canonical(p);
  if (root.empty()) throw Error("--data not given and no walking trials found (../shared/data/cmu/bvh/walking or data/cmu/bvh/walking)");
  *note = "the full CMU walking set (../shared/data/cmu/bvh/walking) is absent: evaluating only the repo's sample trials";
  return root / "data" / "cmu" / "bvh" / "walking";
}

nlohmann::json score_json(const StepScore& s) {
  return {{"true_steps", s.true_steps},          {"detected", s.detected},   {"matched", s.matched},
          {"precision", s.precision},            {"recall", s.recall},       {"f1", s.f1},
          {"foot_off_latency_ms", s.off_latency_ms}, {"foot_strike_latency_ms", s.strike_latency_ms}};
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

void write_trial_plot(const TrialEval& e, const std::string& path) {
  render::LinePlot p;
  p.title = e.name + ": detected (coloured) vs true (grey) swings; generated vs true vs baseline depth";
  p.x_label = "time (s)";
  p.panel_height = 150;
  const auto t = column(e.frames, [](const WipFrame& f) { return f.time; });
  const char* side[2] = {"left", "right"};
  const render::Rgb col[2] = {render::kLeftColor, render::kRightColor};
  for (int f = 0; f < 2; ++f) {
    auto& ph = p.panels.emplace_back();
    ph.title = std::string(side[f]) + " ankle height";
    ph.y_label = "h (m)";
    std::vector<double> h;
    for (const auto& fr : e.frames) h.push_back(fr.h[f]);
    ph.series.emplace_back(side[f], t, h, col[f]);
    for (auto& b : swing_bands(e.truth, f, {0.35, 0.35, 0.35}, "true swing", 0.12)) ph.bands.push_back(b);
    for (auto& b : swing_bands(e.detected, f, col[f], "detected swing", 0.22)) ph.bands.push_back(b);
  }
  for (int f = 0; f < 2; ++f) {
    auto& pz = p.panels.emplace_back();
    pz.title = std::string(side[f]) + " foot depth relative to the pelvis";
    pz.y_label = "z (m)";
    const std::size_t n = std::min(e.frames.size(), e.true_depth.time.size());
    std::vector<double> tt(t.begin(), t.begin() + static_cast<std::ptrdiff_t>(n)), gen, tru, base;
    for (std::size_t i = 0; i < n; ++i) {
      gen.push_back(e.frames[i].z[f]);
      tru.push_back(e.true_depth.z[f][i]);
      base.push_back(e.baseline_z[f][i]);
    }
    pz.series.emplace_back("generated IK target", tt, gen, col[f]);
    pz.series.emplace_back("real foot", tt, tru, render::Rgb{0.1, 0.1, 0.1});
    pz.series.emplace_back("key-frame baseline", tt, base, render::Rgb{0.55, 0.55, 0.55});
    pz.series.back().dashed = true;
  }
  render::plot_lines(p, path);
}

void run_eval_command(const WipArgs& a) {
  if (a.eval_out.empty()) throw Error("--out DIR is required");
  std::string note;
  const fs::path data = a.data.empty() ? default_eval_data(&note) : fs::path(a.data);
  if (!fs::is_directory(data)) throw Error("--data '" + data.string() + "' is not a directory");
  if (!note.empty()) std::cerr << "legwork wip eval: note: " << note << "\n";
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(data))
    if (io::extension_of(e.path().string()) == ".bvh") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  if (a.limit > 0 && static_cast<int>(files.size()) > a.limit) files.resize(static_cast<std::size_t>(a.limit));
  if (files.empty()) throw Error("--data '" + data.string() + "' holds no .bvh files");
  fs::create_directories(a.eval_out);
  const fs::path out(a.eval_out);
  const std::string clip_path = a.clip.empty() ? default_avatar() : a.clip;
  const Motion cycle = extract_walk_cycle(load_bvh_motion(clip_path, false));

  EvalOptions eo;
  eo.params = params_from(a, a.rate);
  eo.noise = a.noise;
  eo.drop_rate = a.drop_rate;
  eo.seed = a.seed;
  EvalOptions fixed = eo;  // the document's fixed thresholds, for comparison
  fixed.params.gait.adaptive = false;

  std::vector<StepScore> clean, noisy, clean_fixed;
  Agreement depth, base;
  nlohmann::json trials = nlohmann::json::array();
  std::ostringstream rows;
  int index = 0, failed = 0;
  for (const auto& file : files) {
    const std::string name = file.stem().string();
    std::fprintf(stderr, "\r[%d/%zu] %-12s", index + 1, files.size(), name.c_str());
    std::fflush(stderr);
    TrialEval e, ef;
    try {
      const Motion m = load_bvh_motion(file.string(), false);
      e = evaluate_trial(m, name, cycle, eo, index);
      ef = evaluate_trial(m, name, cycle, fixed, index);
    } catch (const Error& err) {
      std::fprintf(stderr, "\nlegwork wip eval: skipping %s: %s\n", file.string().c_str(), err.what());
      ++failed;
      ++index;
      continue;
    }
    ++index;
    clean.push_back(e.steps);
    noisy.push_back(e.steps_noisy);
    clean_fixed.push_back(ef.steps);
    depth.merge(e.depth);
    base.merge(e.baseline_depth);
    write_trial_plot(e, (out / (name + ".png")).string());
    trials.push_back({{"trial", name},
                      {"duration_s", e.duration},
                      {"leg_length_m", e.leg_length},
                      {"steps", score_json(e.steps)},
                      {"steps_noisy", score_json(e.steps_noisy)},
                      {"steps_fixed_thresholds", score_json(ef.steps)},
                      {"depth_correlation", e.depth.correlation},
                      {"depth_rms_cm", 100 * e.depth.rms},
                      {"baseline_depth_correlation", e.baseline_depth.correlation},
                      {"baseline_depth_rms_cm", 100 * e.baseline_depth.rms},
                      {"plot", name + ".png"}});
    char row[400];
    std::snprintf(row, sizeof row, "| %s | %.1f | %d | %d | %.2f | %.2f | %.0f | %.2f | %.1f | %.2f | %.1f |\n",
                  name.c_str(), e.duration, e.steps.true_steps, e.steps.matched, e.steps.f1, e.steps_noisy.f1,
                  e.steps.off_latency_ms, e.depth.correlation, 100 * e.depth.rms, e.baseline_depth.correlation,
                  100 * e.baseline_depth.rms);
    rows << row;
  }
  std::fprintf(stderr, "\n");
  if (clean.empty()) throw Error("no trial in '" + data.string() + "' could be evaluated");
  depth.finish();
  base.finish();
  const auto all = combine(clean), all_noisy = combine(noisy), all_fixed = combine(clean_fixed);
  nlohmann::json j;
  j["step_f1"] = all.f1;
  j["step_f1_noisy"] = all_noisy.f1;
  j["step_precision"] = all.precision;
  j["step_recall"] = all.recall;
  j["detection_latency_ms"] = all.off_latency_ms;
  j["detection_latency_median_ms"] = median(all.off_latencies_ms);
  j["foot_strike_latency_ms"] = all.strike_latency_ms;
  j["depth_correlation"] = depth.correlation;
  j["depth_rms_cm"] = 100 * depth.rms;
  j["baseline_depth_correlation"] = base.correlation;
  j["baseline_depth_rms_cm"] = 100 * base.rms;
  j["step_f1_fixed_thresholds"] = all_fixed.f1;
  j["trials"] = static_cast<int>(clean.size());
  j["trials_skipped"] = failed;
  j["steps"] = score_json(all);
  j["steps_noisy"] = score_json(all_noisy);
  j["steps_fixed_thresholds"] = score_json(all_fixed);
  j["data"] = data.string();
  if (!note.empty()) j["note"] = note;
  j["baseline_clip"] = clip_path;
  j["settings"] = {{"tracker_rate_hz", a.rate}, {"cutoff_hz", a.cutoff},   {"h1_m", a.h1},
                   {"v1_mps", a.v1},            {"v2_mps", a.v2},          {"adaptive", !a.no_adaptive},
                   {"noise_m", a.noise},        {"drop_rate", a.drop_rate}, {"seed", a.seed}};
  j["per_trial"] = trials;
  io::write_text_file((out / "report.json").string(), j.dump(2) + "\n");

  std::ostringstream md;
  char buf[2000];
  md << "# Walking-in-place evaluation on real walking\n\n";
  md << "Data: `" << data.string() << "` (" << clean.size() << " trials";
  if (failed) md << ", " << failed << " skipped";
  md << "). Each trial's own ankles drive the method at " << a.rate
     << " Hz (rolling floor, no calibration) with its own skeleton as the avatar.\n";
  if (!note.empty()) md << "\n**Note:** " << note << ".\n";
  std::snprintf(buf, sizeof buf,
                "\n| measure | value |\n|---|---|\n"
                "| step precision / recall / F1 | %.3f / %.3f / **%.3f** (%d of %d true steps, %d detected) |\n"
                "| step F1 with %.1f cm noise + %.0f%% drops | **%.3f** |\n"
                "| step F1 with the document's fixed H1/V1/V2 | %.3f |\n"
                "| foot-off detection latency | mean **%.0f ms**, median %.0f ms |\n"
                "| foot-strike detection latency | mean %.0f ms (negative: before the true strike) |\n"
                "| IK-target depth vs real foot depth | r = **%.3f**, RMS **%.1f cm** |\n"
                "| key-frame baseline depth vs real foot depth | r = %.3f, RMS %.1f cm |\n",
                all.precision, all.recall, all.f1, all.matched, all.true_steps, all.detected, 100 * a.noise,
                100 * a.drop_rate, all_noisy.f1, all_fixed.f1, all.off_latency_ms, median(all.off_latencies_ms),
                all.strike_latency_ms, depth.correlation, 100 * depth.rms, base.correlation, 100 * base.rms);
  md << buf;
  md << "\n## Per trial\n\n| trial | s | true steps | matched | F1 | F1 noisy | latency ms | depth r | depth RMS cm | "
        "baseline r | baseline RMS cm |\n|---|---|---|---|---|---|---|---|---|---|---|\n"
     << rows.str();
  io::write_text_file((out / "report.md").string(), md.str());

  render::BarChart bc;
  bc.title = "walking in place on " + std::to_string(clean.size()) + " CMU walking trials";
  bc.groups = {"step F1", "step F1 (noisy)", "depth r"};
  bc.series.emplace_back("method", std::vector<double>{all.f1, all_noisy.f1, depth.correlation});
  bc.series.emplace_back("document's fixed thresholds", std::vector<double>{all_fixed.f1, NAN, NAN});
  bc.series.emplace_back("key-frame baseline", std::vector<double>{NAN, NAN, base.correlation});
  render::plot_bars(bc, (out / "summary.png").string());

  std::printf("%zu trials: step F1 %.3f (noisy %.3f, fixed thresholds %.3f), foot-off latency %.0f ms, depth r %.3f / "
              "RMS %.1f cm, baseline r %.3f / RMS %.1f cm\n",
              clean.size(), all.f1, all_noisy.f1, all_fixed.f1, all.off_latency_ms, depth.correlation, 100 * depth.rms,
              base.correlation, 100 * base.rms);
  announce("report", (out / "report.md").string());
  announce("report", (out / "report.json").string());
}

// ---- registration ---------------------------------------------------------

void register_wip(CLI::App& app) {
  auto a = std::make_shared<WipArgs>();
  auto* cmd = app.add_subcommand(
      "wip",
      "Walking-in-place legs: tracked ankle heights -> gait phases -> two-bone IK leg animation that walks forward.\n"
      "Input: a tracker CSV (time,left_ankle_x/y/z,right_ankle_x/y/z), a BVH whose ankles act as the tracker, or\n"
      "--synthetic in-place stepping. Output: the avatar's animation (.glb or .bvh), per-frame CSV, phase plot.\n"
      "Example: legwork wip --synthetic --out legs.glb --csv frames.csv --plot phases.png\n"
      "Example: legwork wip --input data/cmu/bvh/walking/07_01.bvh --out legs.bvh --plot phases.png");
  cmd->add_option("--input", a->input, "tracker .csv or .bvh motion (its ankle joints are the tracker)");
  cmd->add_flag("--synthetic", a->synthetic, "generate in-place stepping instead of reading --input");
  cmd->add_option("--avatar", a->avatar, "avatar skeleton .bvh (default data/cmu/bvh/walking/07_01.bvh)");
  cmd->add_option("--out", a->out, "output animation: .glb or .bvh");
  cmd->add_option("--csv", a->csv, "per-frame CSV: phases, heights, velocities, IK targets, speed");
  cmd->add_option("--plot", a->plot, "phase plot .png (heights, velocities, phases, depths + side-view strip)");
  cmd->add_option("--strip", a->strip, "frames for the plot's side-view strip, e.g. 40,45,50 (default: six)");
  cmd->add_option("--baseline", a->baseline, "'keyframe': output the key-frame baseline (canned walk cycle) instead");
  cmd->add_option("--clip", a->clip, "walking BVH for the baseline's walk cycle (default: the default avatar file)");
  cmd->add_option("--tracker-out", a->tracker_out, "also write the (e.g. synthetic) tracker input as CSV");
  cmd->add_option("--rate", a->rate, "tracker rate for --synthetic and BVH input, Hz (default 30)")
      ->check(CLI::Range(10.0, 1000.0));
  cmd->add_option("--calibrate", a->calibrate,
                  "floor calibration from the first 3 s standing still: auto (CSV/synthetic yes, BVH no), on, off");
  cmd->add_option("--speed-model", a->speed_model, "forward speed: step (Bruno et al., default) or frequency (GUD-WIP)");
  cmd->add_option("--max-speed", a->max_speed, "forward speed cap, m/s (default 3.5)")->check(CLI::NonNegativeNumber);
  cmd->add_flag("--keep-first-frame", a->keep_first, "keep BVH frame 0 (dropped by default: CMU's T-pose)");
  add_method_options(cmd, *a);
  auto& s = a->syn;
  cmd->add_option("--duration", s.duration, "synthetic: seconds (default 20)")->check(CLI::PositiveNumber);
  cmd->add_option("--stand-time", s.stand_time, "synthetic: standing still at the start, s (default 3)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--cadence", s.cadence, "synthetic: steps per second (default 1.8)")->check(CLI::PositiveNumber);
  cmd->add_option("--step-height", s.step_height, "synthetic: ankle lift, m (default 0.15)")->check(CLI::PositiveNumber);
  cmd->add_option("--asymmetry", s.asymmetry, "synthetic: right lift = (1 - a) * left (default 0)")->check(CLI::Range(0.0, 0.9));
  cmd->add_option("--noise", s.noise, "synthetic: jitter per coordinate, m (default 0.015)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--drop-rate", s.drop_rate, "synthetic: dropped-sample probability (default 0.02)")->check(CLI::Range(0.0, 0.9));
  cmd->add_option("--pause", s.pause_start, "synthetic: a 3 s stop starts here, s (default 11; negative = none)");
  cmd->add_option("--seed", s.seed, "synthetic: random seed (default 1)");

  auto* ev = cmd->add_subcommand(
      "eval",
      "Evaluate on real walking: step detection (precision/recall/F1, latency) against mocap gait events, with and\n"
      "without Kinect-like noise, and IK-target depth vs the real feet (correlation, RMS), also for the key-frame\n"
      "baseline. Writes report.md, report.json, summary.png and one PNG per trial.\n"
      "Example: legwork wip eval --data ../shared/data/cmu/bvh/walking --out wip-eval");
  ev->add_option("--data", a->data, "folder of walking BVH trials (default ../shared/data/cmu/bvh/walking, else data/cmu/bvh/walking)");
  ev->add_option("--out", a->eval_out, "output folder")->required();
  ev->add_option("--clip", a->clip, "walking BVH for the baseline's walk cycle (default data/cmu/bvh/walking/07_01.bvh)");
  ev->add_option("--noise", a->noise, "jitter of the noisy run, m (default 0.015)")->check(CLI::NonNegativeNumber);
  ev->add_option("--drop-rate", a->drop_rate, "dropped samples in the noisy run (default 0.02)")->check(CLI::Range(0.0, 0.9));
  ev->add_option("--seed", a->seed, "noise seed (default 1)");
  ev->add_option("--limit", a->limit, "evaluate only the first N trials")->check(CLI::PositiveNumber);
  ev->add_option("--rate", a->rate, "tracker rate, Hz (default 30)")->check(CLI::Range(10.0, 1000.0));
  add_method_options(ev, *a);
  ev->callback([a] { run_eval_command(*a); });
  cmd->callback([a, ev] {
    if (ev->parsed()) return;
    if (a->syn.pause_start < 0) a->syn.pause_length = 0;
    run_wip_command(*a);
  });
}

LEGWORK_COMMAND(register_wip, 30);

}  // namespace
}  // namespace legwork::cli

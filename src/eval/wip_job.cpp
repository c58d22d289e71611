#include <legwork/eval/wip_job.hpp>

#include <legwork/eval/wip.hpp>
#include <legwork/eval/wip_tune.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/io/data_files.hpp>
#include <legwork/io/gltf.hpp>
#include <legwork/io/progress.hpp>
#include <legwork/io/text.hpp>
#include <legwork/io/tracker_csv.hpp>
#include <legwork/wip/offline/input.hpp>
#include <legwork/wip/offline/learn.hpp>
#include <legwork/wip/offline/run.hpp>
#include <legwork/wip/offline/walk_cycle.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <set>
#include <sstream>

namespace legwork::eval {
namespace {

namespace fs = std::filesystem;
using namespace legwork::wip;

Motion load_bvh_motion(const std::string& path, bool keep_first) {
  io::BvhReadOptions opt;
  opt.drop_first_frame = !keep_first;
  auto f = io::read_bvh(path, opt);
  for (const auto& w : f.report.warnings) std::cerr << "legwork: " << path << ": " << w << "\n";
  return std::move(f.motion);
}



}  // namespace

wip::LearnedMapping load_learned_table(const WipJob& a) {
  std::string path = a.table;
  if (path.empty()) {
    const auto root = io::find_repo_root("data/wip/learned_mapping.txt");
    if (root.empty()) throw Error("--mapping learned: data/wip/learned_mapping.txt not found; pass --table FILE (legwork wip learn)");
    path = (root / "data/wip/learned_mapping.txt").string();
  }
  if (!fs::exists(path)) throw Error("--table '" + path + "' does not exist (make one with `legwork wip learn`)");
  return read_learned_mapping(path);
}

wip::Settings wip_settings(const WipJob& a, double rate) {
  Settings p;
  p.signal.rate = rate;
  p.signal.cutoff = a.cutoff;
  p.gait.h1 = a.h1;
  p.gait.v1 = a.v1;
  p.gait.v2 = a.v2;
  p.gait.adaptive = !a.no_adaptive;
  if (a.detector == "document") p.gait.detector = StepDetector::Document;
  else if (a.detector == "adaptive") p.gait.detector = StepDetector::Adaptive;
  else throw Error("--detector '" + a.detector + "': expected 'document' (the document's thresholds) or 'adaptive'");
  p.signal.detect_cutoff = a.detect_cutoff;
  p.signal.baseline_tau = a.baseline_tau;
  p.gait.noise_factor = a.noise_factor;
  p.gait.lift_fraction = a.lift_fraction;
  p.gait.rise_fraction = a.rise_fraction;
  p.gait.min_lift = a.min_lift;
  p.gait.min_rise = a.min_rise;
  p.gait.rise_noise_factor = a.rise_noise_factor;
  p.gait.rest_time = a.rest_time;
  p.gait.rest_lift = a.rest_lift;
  p.gait.rest_rise = a.rest_rise;
  p.gait.rest_noise_factor = a.rest_noise_factor;
  p.gait.settle_time = a.settle_time;
  p.gait.min_swing_time = a.min_swing_time;
  p.mapping.normalise_height = !a.raw_height;
  p.mapping.stop_time = a.stop_time;
  p.mapping.max_speed = a.max_speed;
  p.mapping.speed_gain = a.speed_gain;
  p.mapping.step_length = a.step_length;
  if (a.mapping == "document") p.mapping.depth = DepthMapping::Document;
  else if (a.mapping == "learned") p.mapping.depth = DepthMapping::Learned;
  else throw Error("--mapping '" + a.mapping + "': expected 'document' (equations 1-4) or 'learned' (from real walks)");
  if (a.speed_model == "step") p.mapping.speed_model = SpeedModel::StepSpeed;
  else if (a.speed_model == "frequency") p.mapping.speed_model = SpeedModel::StepFrequency;
  else throw Error("--speed-model '" + a.speed_model + "': expected 'step' (Bruno et al.) or 'frequency' (GUD-WIP)");
  for (const auto& [name, hz] : {std::pair{"--cutoff", a.cutoff}, std::pair{"--detect-cutoff", a.detect_cutoff}})
    if (!(rate > 0) || !(hz > 0) || hz >= rate / 2)
      throw Error(std::string(name) + " " + std::to_string(hz) + " Hz must be between 0 and half the sample rate (" +
                  std::to_string(rate) + " Hz)");
  return p;
}

namespace {

// `legwork wip` makes its run in memory (tracker frames, per-frame figures,
// the legs' motion: about 4 KB a frame, 450 MB for an hour at 30 Hz), so a
// run is refused above this many tracker frames before any work: 4.6 hours
// at 30 Hz. (The runtime itself, wip::update, keeps no history.)
constexpr double kMaxRunFrames = 500'000;

void check_run_frames(double frames, const std::string& what) {
  if (frames <= kMaxRunFrames) return;
  char buf[300];
  std::snprintf(buf, sizeof buf, "%s makes %.0f tracker frames; the limit is %.0f frames (a run is made in memory)",
                what.c_str(), std::min(frames, 1e18), kMaxRunFrames);
  throw Error(buf);
}

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

TrackerInput load_input(const WipJob& a) {
  if (a.synthetic == !a.input.empty()) throw Error("give exactly one of --input FILE (.csv or .bvh) and --synthetic");
  if (a.synthetic) {
    check_run_frames(std::floor(a.syn.duration * a.rate) + 1,
                     "--duration " + number(a.syn.duration) + " s at --rate " + number(a.rate) + " Hz");
    SyntheticOptions o = a.syn;
    o.rate = a.rate;
    return tracker_input_synthetic(o);
  }
  const std::string ext = io::extension_of(a.input);
  if (ext == ".csv") {
    TrackerInput in = tracker_input_from_csv(a.input);
    check_run_frames(static_cast<double>(in.frames.size()), "--input '" + a.input + "'");
    return in;
  }
  if (ext == ".bvh") {
    const Motion m = load_bvh_motion(a.input, a.keep_first);
    check_run_frames(std::floor(m.duration() * a.rate) + 1, "--input '" + a.input + "' (" + number(m.duration()) +
                                                                 " s) at --rate " + number(a.rate) + " Hz");
    return tracker_input_from_motion(m, a.input, a.rate);
  }
  throw Error("--input '" + a.input + "' must be a tracker .csv or a .bvh motion");
}

void check_run_options(const WipJob& a) {
  if (a.out.empty()) throw Error("--out FILE (.glb or .bvh) is required");
  const std::string ext = io::extension_of(a.out);
  if (ext != ".glb" && ext != ".bvh") throw Error("--out '" + a.out + "' must end in .glb or .bvh");
  if (!a.baseline.empty() && a.baseline != "keyframe") throw Error("--baseline '" + a.baseline + "': the only baseline is 'keyframe'");
  if (a.calibrate != "on" && a.calibrate != "off" && a.calibrate != "auto")
    throw Error("--calibrate '" + a.calibrate + "': expected auto, on or off");
  if (!a.plot.empty() && io::extension_of(a.plot) != ".png") throw Error("--plot '" + a.plot + "' must end in .png");
}

}  // namespace

void run_wip_job(const WipJob& a) {
  check_run_options(a);
  const std::string avatar_path = a.avatar.empty() ? io::sample_walk_file("--avatar") : a.avatar;
  const Motion avatar_file = load_bvh_motion(avatar_path, a.keep_first);
  const TrackerInput in = load_input(a);
  const Settings settings = wip_settings(a, in.rate);
  LearnedMapping table;
  if (settings.mapping.depth == DepthMapping::Learned) table = load_learned_table(a);
  const Model model = [&] {
    try {
      return make_model(avatar_file.skeleton, settings, {}, &table);
    } catch (const Error& e) {
      throw Error("--avatar " + avatar_path + ": " + e.what());
    }
  }();
  std::cerr << "legwork wip: " << in.what << "\n";
  std::fprintf(stderr, "legwork wip: avatar %s, leg %.3f m, step length S %.3f m\n", avatar_path.c_str(),
               model.leg_length(), model.shape().S);
  RunOptions ro;
  ro.calibrate = a.calibrate == "on" || (a.calibrate == "auto" && in.still_start);
  Run run;
  try {
    run = run_wip(model, in.frames, ro);
  } catch (const Error& e) {
    throw Error(std::string(e.what()) + " [--calibrate off uses a rolling floor instead]");
  }
  if (run.frames.empty()) throw Error("--input: no tracker frame had a usable time");
  std::cerr << "legwork wip: " << (ro.calibrate ? run.calibration.message : "no calibration: rolling floor estimate") << "\n";
  Motion out = run.motion;
  BaselineRun base;
  if (!a.baseline.empty() || !a.plot.empty()) {
    const std::string clip_path = a.clip.empty() ? io::sample_walk_file("--clip") : a.clip;
    const Motion cycle = extract_walk_cycle(load_bvh_motion(clip_path, false));
    try {
      base = run_keyframe_baseline(model, cycle, run.frames, in.rate, a.baseline.empty() ? nullptr : &out);
    } catch (const Error& e) {
      throw Error("--baseline keyframe: clip " + clip_path + ": " + e.what() + "; pass --clip with a BVH on the avatar's skeleton");
    }
    if (!a.baseline.empty()) std::cerr << "legwork wip: output is the key-frame baseline (clip " << clip_path << ")\n";
  }
  if (io::extension_of(a.out) == ".glb") {
    io::GltfOptions g;
    g.animation_name = a.baseline.empty() ? "walking_in_place" : "keyframe_baseline";
    io::write_glb(a.out, out, g);
  } else {
    io::write_bvh(a.out, out);
  }
  std::printf("%s", describe_wip_run(run.frames, in.rate, in.truth).c_str());
  io::announce(a.baseline.empty() ? "legs" : "key-frame baseline", a.out);
  if (!a.csv.empty()) io::write_text_file(a.csv, format_info_csv(run.frames)), io::announce("frames", a.csv);
  if (!a.tracker_out.empty())
    io::write_tracker_csv(a.tracker_out, io::table_from_frames(in.frames)), io::announce("tracker input", a.tracker_out);
  if (!a.plot.empty()) {
    plot_wip_phases(a.plot, "walking in place: " + in.what, run.frames, run.motion,
                          strip_frames(a.strip, run.frames), base.z, settings.gait);
    io::announce("phase plot", a.plot);
  }
}

namespace {

// The sorted .bvh files of --data (default the shared walks), cut to --limit.
std::vector<std::string> walking_files(const WipJob& a, std::string& data_out, std::string& note, const char* tool) {
  const fs::path data = a.data.empty() ? io::walking_data(&note) : fs::path(a.data);
  if (!fs::is_directory(data)) throw Error("--data '" + data.string() + "' is not a directory");
  if (!note.empty()) std::cerr << "legwork " << tool << ": note: " << note << "\n";
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(data))
    if (io::extension_of(e.path().string()) == ".bvh") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  if (a.limit > 0 && static_cast<int>(files.size()) > a.limit) files.resize(static_cast<std::size_t>(a.limit));
  if (files.empty()) throw Error("--data '" + data.string() + "' holds no .bvh files");
  data_out = data.string();
  return files;
}

}  // namespace

void run_wip_learn_job(const WipJob& a) {
  if (a.out.empty()) throw Error("--out FILE is required (the learned table, e.g. data/wip/learned_mapping.txt)");
  std::string data, note;
  const auto files = walking_files(a, data, note, "wip learn");
  std::set<std::string> excluded;
  std::stringstream ss(a.exclude_subjects);
  for (std::string item; std::getline(ss, item, ',');)
    if (!item.empty()) excluded.insert(item);
  Settings settings = wip_settings(a, a.rate);
  settings.mapping.depth = DepthMapping::Document;
  std::vector<LearnSample> samples;
  std::set<std::string> subjects;
  int trials = 0;
  for (const auto& file : files) {
    const std::string name = fs::path(file).stem().string();
    if (excluded.count(subject_of(name))) continue;
    const Motion m = load_bvh_motion(file, false);
    const Model model = make_model(m.skeleton, settings);
    RunOptions ro;
    ro.calibrate = false;
    ro.keep_poses = false;
    const auto frames = run_wip(model, tracker_frames_from_motion(m, a.rate), ro).frames;
    const DepthTrack truth = true_depths(m, a.rate);
    const auto s = learning_samples(frames, truth.z[0], truth.z[1], model.leg_length());
    samples.insert(samples.end(), s.begin(), s.end());
    subjects.insert(subject_of(name));
    ++trials;
  }
  const LearnedMapping table = build_learned_mapping(samples);
  std::string who;
  for (const auto& s : subjects) who += (who.empty() ? "" : ",") + s;
  write_learned_mapping(a.out, table,
                        std::to_string(trials) + " trials of subjects " + who + " from " + fs::path(data).filename().string() +
                            " at " + std::to_string(static_cast<int>(a.rate)) + " Hz");
  std::printf("learned depth mapping from %d trials (subjects %s): %d frames; depth amplitude / leg = %.3f + %.2f x apex "
              "(m) + %.3f x cadence (strides/s), clamped to %.3f..%.3f; in turns x (%.2f %+.2f x head turn rate, rad/s)\n",
              trials, who.c_str(), table.samples, table.amplitude_intercept, table.amplitude_slope, table.cadence_slope,
              table.amplitude_min, table.amplitude_max, table.turn_intercept, table.turn_slope);
  io::announce("learned mapping", a.out);
}

void run_wip_tune_job(const WipJob& a) {
  if (a.eval_out.empty()) throw Error("--out DIR is required");
  std::string data, note;
  const auto files = walking_files(a, data, note, "wip tune");
  WipEvalOptions opt;
  opt.settings = wip_settings(a, a.rate);
  opt.noise = a.noise;
  opt.drop_rate = a.drop_rate;
  opt.seed = a.seed;
  std::vector<DetectionTrial> trials;
  for (std::size_t i = 0; i < files.size(); ++i)
    trials.push_back(prepare_detection_trial(load_bvh_motion(files[i], false), fs::path(files[i]).stem().string(), opt,
                                             static_cast<int>(i)));
  const auto progress = io::progress_printer("legwork wip tune: parameter set");
  const DetectorTuning t = tune_detector(trials, opt.settings, default_detector_grid(), [&](int i, int n) { progress(i, n, ""); });
  std::cerr << "\n";
  std::error_code ec;
  fs::create_directories(a.eval_out, ec);
  if (ec || !fs::is_directory(a.eval_out)) throw Error("cannot create the output folder '" + a.eval_out + "'");
  const std::string md = (fs::path(a.eval_out) / "report.md").string(), js = (fs::path(a.eval_out) / "report.json").string();
  io::write_text_file(md, "# Adaptive step detector: parameters by cross-validation by subject\n\nData: `" + data + "` (" +
                              std::to_string(trials.size()) + " trials).\n" + tuning_markdown(t));
  io::write_text_file(js, tuning_json(t));
  const auto& c = t.cross_validated;
  std::printf("%zu trials, %zu parameter sets; held out by subject: F1 %.3f, noisy F1 %.3f, latency median %.0f ms, false "
              "steps %d / %d (clean / noisy) over %.2f min\n",
              trials.size(), t.grid.size(), c.strict.f1, c.noisy.f1, c.strict.median_ms, c.false_steps,
              c.false_steps_noisy, c.still_minutes);
  if (t.chosen_all >= 0)
    std::printf("chosen on all subjects: %s\n", t.grid[static_cast<std::size_t>(t.chosen_all)].describe().c_str());
  io::announce("report", md);
  io::announce("report", js);
}

void run_wip_eval_job(const WipJob& a) {
  if (a.eval_out.empty()) throw Error("--out DIR is required");
  WipEvalRun run;
  if (fs::exists(a.eval_out) && !fs::is_directory(a.eval_out)) throw Error("--out '" + a.eval_out + "' is not a folder");
  run.files = walking_files(a, run.data, run.note, "wip eval");
  run.clip = a.clip.empty() ? io::sample_walk_file("--clip") : a.clip;
  run.out = a.eval_out;
  run.options.settings = wip_settings(a, a.rate);  // both depth mappings are scored (learned: by subject)
  run.options.noise = a.noise;
  run.options.drop_rate = a.drop_rate;
  run.options.seed = a.seed;
  run.options.truth.learned = a.truth == "learned";
  run.cross_validate_detector = a.cross_validate_detector;
  run.log = [](const std::string& s) { std::cerr << s << std::flush; };
  const auto s = run_wip_evaluation(run);
  std::printf("%d trials, strict foot-offs +-200 ms: %s\nnoisy F1 %.3f; lenient overlap F1 %.3f (secondary); depth r %.3f / "
              "RMS %.1f cm (document), learned (cross-validated by subject) r %.3f / RMS %.1f cm\n",
              s.trials, format_strict(s.strict).c_str(), s.strict_noisy.f1, s.steps.f1, s.depth.correlation,
              100 * s.depth.rms, s.learned.correlation, 100 * s.learned.rms);
  for (const auto& f : s.written) io::announce("report", f);
}

}  // namespace legwork::eval

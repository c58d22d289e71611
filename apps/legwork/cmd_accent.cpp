// legwork accent build / run / bench: full-body accentuation from headset + controllers.
#include "command.hpp"
#include "motion_input.hpp"

#include <legwork/accent/accentuator.hpp>
#include <legwork/accent/builder.hpp>
#include <legwork/accent/retarget.hpp>
#include <legwork/core/fk.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/core/measure.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/io/gltf.hpp>
#include <legwork/io/text.hpp>
#include <legwork/io/tracker_csv.hpp>
#include <legwork/render/render.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <sys/resource.h>
#include <ctime>
#include <filesystem>
#include <thread>

namespace legwork::cli {
namespace {

using namespace legwork::accent;
using accent::TrackerFrame;  // until the contract lands: legwork::TrackerFrame vs the old accent one
using json = nlohmann::json;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// A one-line progress bar on stderr.
Progress progress_bar(const std::string& what) {
  return [what](int done, int total, const std::string& item) {
    const int width = 30;
    const int filled = total > 0 ? done * width / total : width;
    std::fprintf(stderr, "\r%s [%s%s] %d/%d %-40.40s", what.c_str(), std::string(static_cast<std::size_t>(filled), '#').c_str(),
                 std::string(static_cast<std::size_t>(width - filled), '.').c_str(), done, total, item.c_str());
    if (done >= total) std::fprintf(stderr, "\n");
    std::fflush(stderr);
  };
}

std::vector<std::string> split_commas(const std::string& s) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : s) {
    if (c == ',') {
      if (!cur.empty()) out.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

SearchMode parse_mode(const std::string& m) {
  if (m == "fast") return SearchMode::Fast;
  if (m == "exact") return SearchMode::Exact;
  if (m == "brute") return SearchMode::BruteForce;
  throw Error("--mode '" + m + "': expected fast, exact or brute");
}
const char* mode_name(SearchMode m) { return m == SearchMode::Fast ? "fast" : m == SearchMode::Exact ? "exact" : "brute"; }

// ---------------------------------------------------------------- build

struct BuildArgs {
  std::string data, out, classes, json_path, weights;
  std::vector<std::string> exclude;
  BuildConfig cfg;
};

json build_report_json(const BuildReport& r, const Database& db, const BuildArgs& a) {
  json j;
  j["database"] = a.out;
  j["windows"] = r.windows;
  j["poses"] = r.poses;
  j["bytes"] = r.bytes;
  j["build_seconds"] = r.seconds;
  j["skeleton_from"] = r.skeleton_from;
  j["height_m"] = db.height();
  j["typical_distance"] = db.typical_distance();
  j["settings"] = {{"fps", a.cfg.fps}, {"hop", a.cfg.hop}, {"correlation_threshold", a.cfg.correlation_threshold},
                   {"speeds", speed_factors(a.cfg)}, {"mirror", a.cfg.mirror}, {"group_weight", a.cfg.group_weight}};
  json trials = json::array();
  for (const auto& t : r.trials)
    trials.push_back({{"file", t.file}, {"class", t.cls}, {"kept", t.kept}, {"correlation", t.correlation}, {"windows", t.windows}, {"reason", t.reason}});
  j["trials"] = trials;
  return j;
}

void print_class_table(const BuildReport& r) {
  struct Row {
    int kept = 0, dropped = 0, windows = 0;
    std::map<std::string, int> why;
  };
  std::map<std::string, Row> rows;
  for (const auto& t : r.trials) {
    auto& row = rows[t.cls];
    if (t.kept) {
      ++row.kept;
      row.windows += t.windows;
    } else {
      ++row.dropped;
      std::string why = t.reason;
      if (why.rfind("hand-foot correlation", 0) == 0) why = "hand-foot correlation below threshold";
      ++row.why[why];
    }
  }
  std::printf("%-18s %6s %8s %9s  %s\n", "class", "kept", "dropped", "windows", "why dropped");
  for (const auto& [cls, row] : rows) {
    std::string why;
    for (const auto& [w, n] : row.why) why += (why.empty() ? "" : "; ") + std::to_string(n) + "x " + w;
    std::printf("%-18s %6d %8d %9d  %s\n", cls.c_str(), row.kept, row.dropped, row.windows, why.c_str());
  }
  for (const auto& t : r.trials)
    if (t.kept && t.reason.find("roles") != std::string::npos)
      std::printf("note: %s %s\n", t.file.c_str(), t.reason.c_str());
}

void register_build(CLI::App& parent) {
  auto* cmd = parent.add_subcommand("build",
                                    "Build a motion database from BVH trials (classes from MANIFEST.tsv or bvh*/<class>/ folders).\n"
                                    "Example: legwork accent build --data ../shared/data/cmu --classes boxing,running --out box_run.lwdb");
  auto a = std::make_shared<BuildArgs>();
  cmd->add_option("--data", a->data, "folder laid out like data/cmu (MANIFEST.tsv, bvh/<class>/*.bvh)")->required();
  cmd->add_option("--out", a->out, "database file to write (.lwdb)")->required();
  cmd->add_option("--classes", a->classes, "comma-separated classes (default: every class present)");
  cmd->add_option("--exclude", a->exclude, "trial files to leave out (e.g. a held-out trial), by manifest path or name");
  cmd->add_option("--fps", a->cfg.fps, "tracker rate the trials are resampled to (Hz)")->check(CLI::PositiveNumber);
  cmd->add_option("--hop", a->cfg.hop, "samples between window ends (4 = 44 ms at 90 Hz)")->check(CLI::PositiveNumber);
  cmd->add_option("--correlation", a->cfg.correlation_threshold, "keep trials whose hand-foot |Pearson r| exceeds this");
  cmd->add_option("--speeds", a->cfg.speed_variants, "re-timed copies per window (0 = none; 2 = x0.5 and x1.5)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--speed-range", a->cfg.speed_range, "largest relative speed change of the re-timed copies")->check(CLI::Range(0.0, 0.9));
  cmd->add_flag("--mirror", a->cfg.mirror, "add left/right mirrored copies of every trial");
  cmd->add_option("--weights", a->weights, "feature group weights position,velocity,acceleration (default 1,1,0.5)");
  cmd->add_option("--json", a->json_path, "write the build report (per-trial verdicts) as JSON");
  cmd->callback([a] {
    if (io::extension_of(a->out) != ".lwdb") throw Error("--out '" + a->out + "' must end in .lwdb");
    if (!a->weights.empty()) {
      const auto w = split_commas(a->weights);
      if (w.size() != 3) throw Error("--weights '" + a->weights + "': expected three numbers p,v,a");
      for (std::size_t i = 0; i < 3; ++i) a->cfg.group_weight[i] = std::stod(w[i]);
    }
    const auto t0 = Clock::now();
    auto trials = load_trials(a->data, split_commas(a->classes), a->exclude, progress_bar("reading "));
    if (trials.empty()) throw Error("no trials selected in '" + a->data + "'");
    const double read_s = seconds_since(t0);
    BuildReport report;
    Database db;
    try {
      db = build_database(trials, a->cfg, &report, progress_bar("building"));
    } catch (const Error&) {
      print_class_table(report);
      throw;
    }
    save_database(a->out, db);
    print_class_table(report);
    int kept = 0;
    for (const auto& t : report.trials) kept += t.kept;
    std::printf("database: %d of %zu trials kept, %d classes, %d windows, %d poses, %.1f MB, built in %.2f s (+ %.2f s reading BVH)\n",
                kept, report.trials.size(), db.class_count(), report.windows, report.poses, report.bytes / 1e6, report.seconds, read_s);
    std::printf("skeleton: %s (%d joints, %.2f m tall)\n", report.skeleton_from.c_str(), db.joint_count(), db.height());
    announce("database", a->out);
    if (!a->json_path.empty()) {
      auto j = build_report_json(report, db, *a);
      j["read_seconds"] = read_s;
      io::write_text_file(a->json_path, j.dump(2) + "\n");
      announce("build report", a->json_path);
    }
  });
}

// ---------------------------------------------------------------- run

struct RunArgs {
  std::string db, out, video, json_path, classes, mode = "fast", target, save_session;
  MotionInput input;
  bool compare_ik = false, no_align = false, no_smooth = false, no_limits = false;
  int k = AccentConfig{}.k_left, k_left = -1, k_right = -1;
  double threshold = 6.0, height = 0, exaggerate = 1.0, hand_ik = AccentConfig{}.hand_ik, max_tilt = AccentConfig{}.max_head_tilt_deg;
  double smooth_halflife = AccentConfig{}.smooth_halflife;
};

// A headset session CSV: time, head_x/y/z + head_qw/qx/qy/qz, left_x/y/z, right_x/y/z.
std::vector<TrackerFrame> frames_from_csv(const std::string& path) {
  const io::TrackerTable t = io::read_tracker_csv(path);
  auto pick = [&](std::initializer_list<const char*> names) -> const io::TrackedPoint& {
    for (const char* n : names)
      if (t.has(n)) return t.point(n);
    return t.point(*names.begin());  // throws, listing the points present
  };
  const auto& head = pick({"head", "hmd", "headset"});
  const auto& left = pick({"left", "left_hand", "lhand"});
  const auto& right = pick({"right", "right_hand", "rhand"});
  if (!head.has_rotation) throw Error(path + ": the head needs orientation columns head_qw, head_qx, head_qy, head_qz");
  std::vector<TrackerFrame> out(static_cast<std::size_t>(t.sample_count()));
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i].time = t.time[i];
    out[i].head = {head.position[i], head.rotation[i], head.valid[i] != 0};
    out[i].left = {left.position[i], Quat::Identity(), left.valid[i] != 0};
    out[i].right = {right.position[i], Quat::Identity(), right.valid[i] != 0};
  }
  return out;
}

io::TrackerTable session_table(std::span<const TrackerFrame> frames) {
  io::TrackerTable t;
  t.points.resize(3);
  t.points[0].name = "head";
  t.points[0].has_rotation = true;
  t.points[1].name = "left";
  t.points[2].name = "right";
  for (const auto& f : frames) {
    t.time.push_back(f.time);
    const DeviceSample* d[3] = {&f.head, &f.left, &f.right};
    for (int i = 0; i < 3; ++i) {
      auto& p = t.points[static_cast<std::size_t>(i)];
      p.position.push_back(d[i]->position);
      if (p.has_rotation) p.rotation.push_back(d[i]->rotation);
      p.valid.push_back(d[i]->valid ? 1 : 0);
    }
  }
  return t;
}

// Frames at a uniform rate from timed samples (nearest earlier sample's data is
// carried by the Accentuator itself; here only the output clock is uniform).
Motion input_figure(std::span<const TrackerFrame> frames, double fps) {
  Skeleton s;
  s.add_joint("Head", -1, Vec3::Zero());
  s.add_joint("LeftHand", 0, Vec3(0.2, -0.5, 0));
  s.add_joint("RightHand", 0, Vec3(-0.2, -0.5, 0));
  Motion m(s, fps, static_cast<int>(frames.size()));
  // Lost samples show the last good position (as the engine holds them).
  Vec3 head = Vec3::Zero(), left(0.2, -0.5, 0), right(-0.2, -0.5, 0);
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const auto& fr = frames[f];
    if (fr.head.valid && fr.head.position.allFinite()) head = fr.head.position;
    if (fr.left.valid && fr.left.position.allFinite()) left = fr.left.position - head;
    if (fr.right.valid && fr.right.position.allFinite()) right = fr.right.position - head;
    auto p = m.frame(static_cast<int>(f));
    p.translations[0] = head;
    p.translations[1] = left;
    p.translations[2] = right;
  }
  return m;
}

void write_motion(const std::string& path, const Motion& m) {
  const auto ext = io::extension_of(path);
  if (ext == ".bvh")
    io::write_bvh(path, m);
  else
    io::write_glb(path, m);
}

void register_run(CLI::App& parent) {
  auto* cmd = parent.add_subcommand(
      "run",
      "Accentuate a session: a BVH trial (only its head and wrists are used as headset + controllers; the rest is\n"
      "ground truth for the video) or a headset CSV (time, head xyz + quaternion, hands xyz).\n"
      "Example: legwork accent run --db box_run.lwdb --input data/cmu/bvh/walking/07_02.bvh --drop-first --out walk.glb "
      "--video walk.mp4 --compare-ik");
  auto a = std::make_shared<RunArgs>();
  cmd->add_option("--db", a->db, "database built by 'legwork accent build'")->required()->check(CLI::ExistingFile);
  cmd->add_option("--input", a->input.path, "session: .bvh trial or .csv headset recording")->required()->check(CLI::ExistingFile);
  a->input.add_options(cmd, false);
  cmd->add_option("--out", a->out, "result: .glb or .bvh")->required();
  cmd->add_option("--video", a->video, "side-by-side MP4: input, accentuated body (and IK baseline, ground truth)");
  cmd->add_flag("--compare-ik", a->compare_ik, "add the IK baseline (direct mapping) to the video and the JSON");
  cmd->add_option("--json", a->json_path, "per-frame match statistics and summary as JSON");
  cmd->add_option("--mode", a->mode, "search: fast (KD-tree, approximate), exact (KD-tree) or brute");
  cmd->add_option("--k", a->k, "matches per hand (the paper used 5)")->capture_default_str()->check(CLI::Range(1, kMaxK));
  cmd->add_option("--k-left", a->k_left, "matches for the left hand (default --k)")->check(CLI::Range(0, kMaxK));
  cmd->add_option("--k-right", a->k_right, "matches for the right hand (default --k)")->check(CLI::Range(0, kMaxK));
  cmd->add_option("--threshold", a->threshold, "match distance limit in typical-distance units (0 = none)")->check(CLI::NonNegativeNumber);
  cmd->add_flag("--no-align", a->no_align, "skip the rotation alignment of candidates");
  cmd->add_flag("--no-smooth", a->no_smooth, "skip the temporal smoothing (both the paper's EWMA and the spring filter)");
  cmd->add_option("--smooth-halflife", a->smooth_halflife,
                  "seconds for the spring filter on the blended rotations to halve an error (0 = the paper's EWMA only)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--no-limits", a->no_limits, "skip the joint angle limits");
  cmd->add_option("--height", a->height, "user height in metres (default: the BVH's standing height, or the database's)")->check(CLI::PositiveNumber);
  cmd->add_option("--exaggerate", a->exaggerate, "scale the input hands about the head before matching")->check(CLI::PositiveNumber);
  cmd->add_option("--classes", a->classes, "comma-separated classes to match against (default: all in the database)");
  cmd->add_option("--hand-ik", a->hand_ik,
                  "0..1: pull the synthesized arms onto the real hands (needs legwork::ik); 1 = wrists on the controllers, "
                  "0 = the paper's pure synthesis")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--max-head-tilt", a->max_tilt, "reject candidates whose head tilt differs from the headset's by more than this (degrees, 0 = off)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--target", a->target, "retarget the result by joint roles onto this BVH's skeleton");
  cmd->add_option("--save-session", a->save_session, "also write the input as a headset session CSV (the format --input reads)");
  cmd->callback([a] {
    const auto out_ext = io::extension_of(a->out);
    if (out_ext != ".glb" && out_ext != ".bvh") throw Error("--out '" + a->out + "' must end in .glb or .bvh");
    if (!a->video.empty() && io::extension_of(a->video) != ".mp4") throw Error("--video '" + a->video + "' must end in .mp4");
    const auto t0 = Clock::now();
    const Database db = load_database(a->db);
    const double load_s = seconds_since(t0);
    AccentConfig cfg;
    cfg.search = parse_mode(a->mode);
    cfg.k_left = a->k_left >= 0 ? a->k_left : a->k;
    cfg.k_right = a->k_right >= 0 ? a->k_right : a->k;
    cfg.threshold = a->threshold;
    cfg.align = !a->no_align;
    cfg.smooth = !a->no_smooth;
    cfg.smooth_halflife = a->smooth_halflife;
    cfg.joint_limits = !a->no_limits;
    cfg.exaggeration = a->exaggerate;
    cfg.classes = split_commas(a->classes);
    cfg.hand_ik = a->hand_ik;
    cfg.max_head_tilt_deg = a->max_tilt;
    const double fps = db.feature_space().fps;
    std::vector<TrackerFrame> frames;
    Motion truth;
    const auto in_ext = io::extension_of(a->input.path);
    if (in_ext == ".bvh") {
      truth = resample(a->input.load().motion, fps);
      frames = accent::tracker_frames_from_motion(truth);
      cfg.user_height = a->height > 0 ? a->height : measure_body(truth.skeleton).standing_height;
    } else if (in_ext == ".csv") {
      frames = frames_from_csv(a->input.path);
      cfg.user_height = a->height;
    } else {
      throw Error("--input '" + a->input.path + "' must be a .bvh trial or a .csv headset session");
    }
    if (frames.empty()) throw Error("--input '" + a->input.path + "' has no samples");
    if (!a->save_session.empty()) {
      io::write_tracker_csv(a->save_session, session_table(frames));
      announce("headset session", a->save_session);
    }
    AccentRun run = accentuate(db, cfg, frames, fps);
    std::map<std::string, int> statuses;
    double weight = 0;
    for (const auto& i : run.info) {
      ++statuses[status_name(i.status)];
      weight += i.match_weight;
    }
    std::printf("database: %s (%d windows, loaded in %.1f ms)\n", a->db.c_str(), db.window_count(), load_s * 1e3);
    std::printf("frames: %d at %.4g Hz; %.0f frames/s in update() (%s search); mean match weight %.2f\n", run.output.frame_count(), fps,
                run.output.frame_count() / std::max(run.seconds, 1e-9), mode_name(cfg.search), weight / run.info.size());
    for (const auto& [s, n] : statuses) std::printf("  %-14s %d frames\n", s.c_str(), n);
    Motion result = run.output;
    if (!a->target.empty()) {
      io::BvhReadOptions opt;
      Motion tgt = io::load_bvh(a->target, opt);
      require_roles(tgt.skeleton, a->target);
      tgt.skeleton.scale(cfg.user_height > 0 ? cfg.user_height / std::max(measure_body(tgt.skeleton).standing_height, 1e-6) : 1.0);
      result = retarget_motion(run.output, tgt.skeleton);
      // Keep the target's head at the headset, as the engine does for its own rig.
      const int hs = run.output.skeleton.roles[Role::Head], ht = result.skeleton.roles[Role::Head];
      for (int f = 0; f < result.frame_count(); ++f) {
        const auto ps = joint_positions(run.output.skeleton, run.output.frame(f));
        const auto pt = joint_positions(result.skeleton, result.frame(f));
        result.frame(f).translations[0] += ps[static_cast<std::size_t>(hs)] - pt[static_cast<std::size_t>(ht)];
      }
    }
    write_motion(a->out, result);
    announce("accentuated motion", a->out);
    AccentRun ik;
    if (a->compare_ik) {
      AccentConfig icfg = cfg;
      icfg.direct_only = true;
      ik = accentuate(db, icfg, frames, fps);
      if (!have_arm_ik()) std::printf("note: this build has no legwork::ik; the baseline's arms hang neutral\n");
    }
    json j;
    j["input"] = a->input.path;
    j["database"] = a->db;
    j["frames"] = run.output.frame_count();
    j["fps"] = fps;
    j["frames_per_second"] = run.output.frame_count() / std::max(run.seconds, 1e-9);
    j["load_ms"] = load_s * 1e3;
    j["statuses"] = statuses;
    if (!truth.skeleton.names.empty()) {
      // Ground-truth comparison of the role joints (cm), when the input was a full-body trial.
      auto err = [&](const Motion& m) {
        double sum_hands[2] = {0, 0}, sum_all = 0;
        int n_all = 0;
        const auto& rt = truth.skeleton.roles;
        const auto& rm = m.skeleton.roles;
        for (int f = 0; f < m.frame_count(); ++f) {
          const auto pt = joint_positions(truth.skeleton, truth.frame(f));
          const auto pm = joint_positions(m.skeleton, m.frame(f));
          for (int r = 0; r < kRoleCount; ++r) {
            const int a1 = rt.joint[static_cast<std::size_t>(r)], b1 = rm.joint[static_cast<std::size_t>(r)];
            if (a1 < 0 || b1 < 0) continue;
            const double e = (pt[static_cast<std::size_t>(a1)] - pm[static_cast<std::size_t>(b1)]).norm();
            sum_all += e;
            ++n_all;
            if (static_cast<Role>(r) == Role::LeftHand) sum_hands[0] += e;
            if (static_cast<Role>(r) == Role::RightHand) sum_hands[1] += e;
          }
        }
        const double n = std::max(m.frame_count(), 1);
        return json{{"left_hand_cm", 100 * sum_hands[0] / n}, {"right_hand_cm", 100 * sum_hands[1] / n},
                    {"role_joints_cm", 100 * sum_all / std::max(n_all, 1)}};
      };
      j["accent_error"] = err(run.output);
      std::printf("vs ground truth (role joints): accent %.1f cm, hands %.1f / %.1f cm\n", j["accent_error"]["role_joints_cm"].get<double>(),
                  j["accent_error"]["left_hand_cm"].get<double>(), j["accent_error"]["right_hand_cm"].get<double>());
      if (a->compare_ik) {
        j["ik_error"] = err(ik.output);
        std::printf("                               IK baseline %.1f cm, hands %.1f / %.1f cm\n", j["ik_error"]["role_joints_cm"].get<double>(),
                    j["ik_error"]["left_hand_cm"].get<double>(), j["ik_error"]["right_hand_cm"].get<double>());
      }
    }
    if (!a->json_path.empty()) {
      json per = json::array();
      for (const auto& i : run.info)
        per.push_back({{"status", status_name(i.status)}, {"match_weight", i.match_weight}, {"fallback", i.fallback},
                       {"matches", i.matches}, {"best_distance", i.best_distance}});
      j["per_frame"] = per;
      io::write_text_file(a->json_path, j.dump(1) + "\n");
      announce("run report", a->json_path);
    }
    if (!a->video.empty()) {
      const Motion input = input_figure(frames, fps);
      std::vector<const Motion*> panels{&input, &run.output};
      std::vector<std::string> labels{"input (head, hands)", "accentuated"};
      if (a->compare_ik) {
        panels.push_back(&ik.output);
        labels.push_back(have_arm_ik() ? "IK baseline" : "no-IK baseline");
      }
      if (!truth.skeleton.names.empty()) {
        panels.push_back(&truth);
        labels.push_back("ground truth");
      }
      render::VideoOptions vo;
      vo.fps = 30;
      vo.camera.view = render::View::ThreeQuarter;
      vo.camera.width = 280 * static_cast<int>(panels.size());
      vo.camera.height = 420;
      vo.title = "legwork accent: " + std::filesystem::path(a->input.path).filename().string();
      render::render_video_side_by_side(panels, labels, vo, a->video);
      announce("video", a->video);
    }
  });
}

// ---------------------------------------------------------------- bench

struct BenchArgs {
  std::string db, json_path, data, classes;
  MotionInput input;
  int repeat = 3, k = AccentConfig{}.k_left, max_checks = AccentConfig{}.fast_max_checks;
  float eps = 5.0f;
};

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(p * static_cast<double>(v.size())))];
}

// CPU time of this thread (excludes time the machine gave to other processes).
double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

long peak_rss_kb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

void register_bench(CLI::App& parent) {
  auto* cmd = parent.add_subcommand(
      "bench",
      "Measure load time, per-frame latency (mean, p99) and frames/s of exact vs fast search, fast-mode recall and memory,\n"
      "driving one avatar with a real held-out trial on one core.\n"
      "Example: legwork accent bench --db table1.lwdb --input ../shared/data/cmu/bvh/running/09_01.bvh --drop-first --json bench.json");
  auto a = std::make_shared<BenchArgs>();
  cmd->add_option("--db", a->db, "database file")->required()->check(CLI::ExistingFile);
  cmd->add_option("--input", a->input.path, "held-out BVH trial driving the avatar")->required()->check(CLI::ExistingFile);
  a->input.add_options(cmd, false);
  cmd->add_option("--repeat", a->repeat, "passes over the trial per mode")->check(CLI::PositiveNumber);
  cmd->add_option("--k", a->k, "matches per hand")->check(CLI::Range(1, kMaxK));
  cmd->add_option("--eps", a->eps, "fast-mode approximation (neighbours within (1+eps) x the true distance)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--data", a->data, "also time a database build from this folder (the --input file excluded)");
  cmd->add_option("--classes", a->classes, "classes for the timed build (default: all)");
  cmd->add_option("--max-checks", a->max_checks, "fast-mode budget of candidates per search (0 = unlimited)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--json", a->json_path, "write the figures as JSON");
  cmd->callback([a] {
    json j;
    j["database"] = a->db;
    j["input"] = a->input.path;
    {
      double load[3] = {0, 0, 0};
      if (std::FILE* f = std::fopen("/proc/loadavg", "r")) {
        if (std::fscanf(f, "%lf %lf %lf", &load[0], &load[1], &load[2]) != 3) load[0] = -1;
        std::fclose(f);
      }
      j["machine_load_1min"] = load[0];
      std::printf("machine load (1 min): %.1f on %u cores - wall-clock figures include time given to other processes\n", load[0],
                  std::thread::hardware_concurrency());
    }
    // Load: mapping + header/metadata checks, checksum, KD-tree build, each timed.
    LoadOptions lo;
    lo.verify_checksum = false;
    lo.build_index = false;
    auto t0 = Clock::now();
    { const Database quick = load_database(a->db, lo); }
    const double map_ms = seconds_since(t0) * 1e3;
    lo.verify_checksum = true;
    t0 = Clock::now();
    Database db = load_database(a->db, lo);
    const double verified_ms = seconds_since(t0) * 1e3;
    t0 = Clock::now();
    db.build_index();
    const double index_ms = seconds_since(t0) * 1e3;
    std::printf("database: %d windows, %d classes, %.1f MB\n", db.window_count(), db.class_count(), db.bytes().size() / 1e6);
    std::printf("load: %.2f ms mmap + checks, %.2f ms with checksum, KD-trees %.1f ms\n", map_ms, verified_ms, index_ms);
    j["windows"] = db.window_count();
    j["database_bytes"] = db.bytes().size();
    j["load_ms_mmap"] = map_ms;
    j["load_ms_verified"] = verified_ms;
    j["index_build_ms"] = index_ms;

    const double fps = db.feature_space().fps;
    Motion truth = resample(a->input.load().motion, fps);
    const auto frames = accent::tracker_frames_from_motion(truth);
    j["input_frames"] = frames.size();
    json modes = json::object();
    for (SearchMode mode : {SearchMode::BruteForce, SearchMode::Exact, SearchMode::Fast}) {
      AccentConfig cfg;
      cfg.search = mode;
      cfg.fast_eps = a->eps;
      cfg.fast_max_checks = a->max_checks;
      cfg.k_left = cfg.k_right = a->k;
      cfg.user_height = measure_body(truth.skeleton).standing_height;
      std::vector<double> lat;
      lat.reserve(frames.size() * static_cast<std::size_t>(a->repeat));
      double total = 0, cpu = 0;
      std::size_t bytes = 0;
      for (int r = 0; r < a->repeat; ++r) {
        Accentuator acc(db, cfg);
        bytes = acc.state_bytes();
        const double c0 = thread_cpu_seconds();
        for (const auto& f : frames) {
          const auto s = Clock::now();
          acc.update(f);
          const double dt = seconds_since(s);
          lat.push_back(dt);
          total += dt;
        }
        cpu += thread_cpu_seconds() - c0;
      }
      const double mean_us = 1e6 * total / static_cast<double>(lat.size());
      const double p99_us = 1e6 * percentile(lat, 0.99);
      const double fps_run = static_cast<double>(lat.size()) / total;
      const double fps_cpu = static_cast<double>(lat.size()) / cpu;
      std::printf("%-6s wall: mean %7.2f us, p99 %7.2f us, %8.0f frames/s | CPU time: %8.0f frames/s (%.0fx the document's 152 Hz)\n",
                  mode_name(mode), mean_us, p99_us, fps_run, fps_cpu, fps_cpu / 152.0);
      modes[mode_name(mode)] = {{"mean_us", mean_us}, {"p99_us", p99_us}, {"frames_per_second", fps_run},
                                {"frames_per_cpu_second", fps_cpu}, {"cpu_us_per_frame", 1e6 * cpu / static_cast<double>(lat.size())},
                                {"speedup_vs_152hz", fps_cpu / 152.0}, {"avatar_state_bytes", bytes}};
    }
    j["modes"] = modes;
    // Fast-mode recall: the live queries of this trial, fast vs brute force.
    {
      AccentConfig cfg;
      cfg.user_height = measure_body(truth.skeleton).standing_height;
      cfg.fast_max_checks = a->max_checks;
      Accentuator acc(db, cfg);
      std::array<Match, kMaxK> brute{}, fast{};
      const double scale = db.height() / cfg.user_height;
      std::vector<float> eps_list{0.5f, 1.0f, 2.0f, 5.0f, 10.0f};
      if (std::find(eps_list.begin(), eps_list.end(), a->eps) == eps_list.end()) eps_list.push_back(a->eps);
      json by_eps = json::object();
      for (float eps : eps_list) {
        std::size_t hits = 0, total = 0;
        for (std::size_t f = kWindow - 1; f < frames.size(); ++f) {
          for (int h = 0; h < 2; ++h) {
            HandWindow w;
            for (int i = 0; i < kWindow; ++i) {
              const auto& fr = frames[f - static_cast<std::size_t>(kWindow - 1 - i)];
              w[static_cast<std::size_t>(i)] = ((h == 0 ? fr.left.position : fr.right.position) - fr.head.position) * scale;
            }
            Feature q;
            db.feature_space().project(w, q);
            const int nb = search_knn(db, h, q, a->k, SearchMode::BruteForce, 0, {}, brute);
            const int nf = search_knn(db, h, q, a->k, SearchMode::Fast, eps, {}, fast, {}, cfg.fast_max_checks);
            for (int x = 0; x < nf; ++x)
              for (int y = 0; y < nb; ++y) hits += fast[static_cast<std::size_t>(x)].window == brute[static_cast<std::size_t>(y)].window;
            total += static_cast<std::size_t>(nb);
          }
        }
        const double recall = total ? static_cast<double>(hits) / static_cast<double>(total) : 0.0;
        by_eps[std::to_string(eps).substr(0, 4)] = recall;
        if (eps == a->eps) j["fast_recall"] = recall;
        std::printf("fast-mode recall@%d (eps %.2g, max %d checks) vs brute force on this trial: %.3f\n", a->k, eps,
                    cfg.fast_max_checks, recall);
      }
      j["fast_recall_by_eps"] = by_eps;
      j["avatar_state_bytes"] = acc.state_bytes();
    }
    if (!a->data.empty()) {
      auto t1 = Clock::now();
      const auto trials = load_trials(a->data, split_commas(a->classes), {a->input.path});
      const double read_s = seconds_since(t1);
      t1 = Clock::now();
      const Database built = build_database(trials, BuildConfig{});
      const double build_s = seconds_since(t1);
      std::printf("build: %zu trials read in %.2f s, database (%d windows) built in %.2f s\n", trials.size(), read_s,
                  built.window_count(), build_s);
      j["build"] = {{"data", a->data}, {"trials", trials.size()}, {"read_seconds", read_s}, {"build_seconds", build_s},
                    {"windows", built.window_count()}};
    }
    j["peak_rss_kb"] = peak_rss_kb();
    std::printf("memory: database %.1f MB (mapped, shared by all avatars), %zu bytes per avatar, peak RSS %.1f MB\n",
                db.bytes().size() / 1e6, j["avatar_state_bytes"].get<std::size_t>(), peak_rss_kb() / 1e3);
    if (!a->json_path.empty()) {
      io::write_text_file(a->json_path, j.dump(2) + "\n");
      announce("bench figures", a->json_path);
    }
  });
}

void register_accent(CLI::App& app) {
  auto* cmd = app.add_subcommand("accent",
                                 "Full-body accentuation from headset + two controllers by nearest-neighbour synthesis over a mocap\n"
                                 "database (CoolMoves). Subcommands: build, run, bench.");
  cmd->require_subcommand(1);
  register_build(*cmd);
  register_run(*cmd);
  register_bench(*cmd);
}

LEGWORK_COMMAND(register_accent, 50);

}  // namespace
}  // namespace legwork::cli

#include <legwork/eval/run.hpp>

#include <legwork/accent/search.hpp>
#include <legwork/core/fk.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/core/measure.hpp>
#include <legwork/core/stats.hpp>
#include <legwork/ik/full_body.hpp>
#include <legwork/io/bvh.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <mutex>
#include <set>
#include <tuple>
#include <thread>
#include <unistd.h>

namespace legwork::eval {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Runs fn(i) for i in [0, n) on `threads` threads, largest-first order given.
// The first exception is rethrown after all workers stop.
void parallel_for(const std::vector<int>& order, int threads, const std::function<void(int)>& fn) {
  std::atomic<std::size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto worker = [&] {
    for (;;) {
      const std::size_t k = next.fetch_add(1);
      if (k >= order.size()) return;
      try {
        fn(order[k]);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        next = order.size();
      }
    }
  };
  std::vector<std::thread> pool;
  const int t = std::max(1, std::min<int>(threads, static_cast<int>(order.size())));
  for (int i = 1; i < t; ++i) pool.emplace_back(worker);
  worker();
  for (auto& th : pool) th.join();
  if (error) std::rethrow_exception(error);
}

std::vector<int> iota(int n) {
  std::vector<int> v(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) v[static_cast<std::size_t>(i)] = i;
  return v;
}

// Build settings that change the database (variants sharing them share one).
std::string build_key(const accent::BuildConfig& b) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%g/%d/%g/%d/%g/%d/%g/%g/%g", b.fps, b.hop, b.correlation_threshold, b.speed_variants,
                b.speed_range, b.mirror ? 1 : 0, b.group_weight[0], b.group_weight[1], b.group_weight[2]);
  return buf;
}
std::string prepare_key(const accent::BuildConfig& b) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%g/%g/%d", b.fps, b.correlation_threshold, b.mirror ? 1 : 0);
  return buf;
}

std::vector<accent::TrialInput> load_all(const Catalogue& c, bool drop_first, int threads,
                                         const std::function<void(const std::string&)>& progress) {
  std::vector<accent::TrialInput> out(c.trials.size());
  std::atomic<int> done{0};
  std::mutex m;
  parallel_for(iota(static_cast<int>(c.trials.size())), threads, [&](int i) {
    const auto& e = c.trials[static_cast<std::size_t>(i)];
    io::BvhReadOptions opt;
    opt.drop_first_frame = drop_first;
    auto& t = out[static_cast<std::size_t>(i)];
    t.file = e.file;
    t.cls = e.cls;
    t.subject = e.subject;
    t.trial = e.trial;
    t.motion = io::load_bvh(e.path, opt);
    const int d = ++done;
    if (progress) {
      std::lock_guard<std::mutex> lock(m);
      progress("loading " + c.root + ": " + std::to_string(d) + "/" + std::to_string(out.size()) + " trials");
    }
  });
  return out;
}

struct TestTrack {
  Motion motion;  // at the database rate, clipped
  RoleTrack truth;
  std::string id;
};

TestTrack make_test(const accent::TrialInput& t, double fps, double max_seconds) {
  TestTrack r;
  r.motion = resample(t.motion, fps);
  if (max_seconds > 0) {
    const int keep = static_cast<int>(std::floor(max_seconds * fps)) + 1;
    if (r.motion.frame_count() > keep) r.motion = trim(r.motion, 0, keep - 1);
  }
  r.truth = role_track(r.motion);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%02d_%02d", t.subject, t.trial);
  r.id = buf;
  return r;
}

std::string leak_in_database(const Fold& f, const accent::Database& db, const std::vector<std::string>& test_files) {
  for (const auto& info : db.trials()) {
    if (f.protocol == Protocol::CrossSubject && info.subject == f.held_out_subject)
      return "database of fold '" + f.cls + " " + f.held_out + "' holds " + info.file;
    for (const auto& tf : test_files)
      if (info.file == tf) return "database of fold '" + f.cls + " " + f.held_out + "' holds the test trial " + tf;
  }
  return "";
}

double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Members of a fold's no-class database: every trial of the catalogue except
// the held-out subject's (cross-subject) and the fold's test trials.
std::vector<int> no_class_members(const Fold& f, const Catalogue& data) {
  std::vector<int> out;
  for (int i = 0; i < static_cast<int>(data.trials.size()); ++i) {
    if (f.protocol == Protocol::CrossSubject && data.trials[static_cast<std::size_t>(i)].subject == f.held_out_subject) continue;
    if (std::find(f.test.begin(), f.test.end(), i) != f.test.end()) continue;
    out.push_back(i);
  }
  return out;
}

accent::Settings no_class_settings(accent::Settings cfg) {
  cfg.classes.clear();
  cfg.recognize_class = true;
  return cfg;
}

// Fast-mode recall@k against brute force on a motion's live queries (the
// engine's k, eps and check budget), within class `cls` (-1 = all): {without
// seeds, seeded with the previous frame's fast results as the engine does}.
std::pair<double, double> fast_recall(const accent::Database& db, const accent::Settings& cfg, const Motion& m, int cls) {
  const auto frames = tracker_frames_from_motion(m);
  const double scale = db.height() / measure_body(m.skeleton).standing_height;
  std::vector<unsigned char> mask;
  if (cls >= 0) {
    mask.assign(static_cast<std::size_t>(db.class_count()), 0);
    mask[static_cast<std::size_t>(cls)] = 1;
  }
  std::array<accent::Match, accent::kMaxK> brute{}, fast{};
  std::array<std::array<int, accent::kMaxK>, 2> seeds{};
  std::array<int, 2> seeded_n{0, 0};
  std::size_t hits = 0, seeded_hits = 0, total = 0;
  for (std::size_t f = accent::window_lag(0); f < frames.size(); ++f)
    for (int h = 0; h < 2; ++h) {
      accent::HandWindow w;
      accent::window_from_frames(frames, f, h, scale, w);
      accent::Feature q;
      db.feature_space().project(w, q);
      const int k = h == 0 ? cfg.k_left : cfg.k_right;
      const int nb = accent::search_knn(db, h, q, k, accent::SearchMode::BruteForce, 0, mask, brute);
      const auto hu = static_cast<std::size_t>(h);
      auto count = [&](int nf) {
        std::size_t c = 0;
        for (int x = 0; x < nf; ++x)
          for (int y = 0; y < nb; ++y) c += fast[static_cast<std::size_t>(x)].window == brute[static_cast<std::size_t>(y)].window;
        return c;
      };
      hits += count(accent::search_knn(db, h, q, k, accent::SearchMode::Fast, cfg.fast_eps, mask, fast, {}, cfg.fast_max_checks));
      const int ns = accent::search_knn(db, h, q, k, accent::SearchMode::Fast, cfg.fast_eps, mask, fast,
                                        std::span<const int>(seeds[hu].data(), static_cast<std::size_t>(seeded_n[hu])),
                                        cfg.fast_max_checks);
      seeded_hits += count(ns);
      for (int x = 0; x < ns; ++x) seeds[hu][static_cast<std::size_t>(x)] = fast[static_cast<std::size_t>(x)].window;
      seeded_n[hu] = ns;
      total += static_cast<std::size_t>(nb);
    }
  if (!total) return {0.0, 0.0};
  return {static_cast<double>(hits) / static_cast<double>(total), static_cast<double>(seeded_hits) / static_cast<double>(total)};
}

// Saves the database and times loading it with its index (best of 5), with
// and without the checksum pass: {verified ms, unverified ms, file bytes}.
std::tuple<double, double, std::size_t> time_load(const accent::Database& db) {
  const std::string path =
      (std::filesystem::temp_directory_path() / ("legwork_eval_load_" + std::to_string(::getpid()) + ".lwdb")).string();
  accent::save_database(path, db);
  double best[2] = {1e30, 1e30};
  for (int pass = 0; pass < 5; ++pass)
    for (int verify = 0; verify < 2; ++verify) {
      accent::LoadOptions lo;
      lo.verify_checksum = verify == 0;
      const auto t0 = Clock::now();
      const accent::Database loaded = accent::load_database(path, lo);
      best[verify] = std::min(best[verify], since(t0) * 1e3);
    }
  std::filesystem::remove(path);
  return {best[0], best[1], db.bytes().size()};
}

// Best of three passes: {wall frames/s, CPU frames/s, p99 us} and the first pass's output.
struct SpeedPass {
  double fps = 0, cpu_fps = 0, p99_us = 0;
  Motion output;
};
SpeedPass speed_pass(const accent::Database& db, const accent::Settings& cfg, const Motion& motion) {
  SpeedPass out;
  double best = 1e30, best_cpu = 1e30;
  for (int pass = 0; pass < 3; ++pass) {
    const double c0 = thread_cpu_seconds();
    accent::AccentRun run = accent::accentuate_motion(db, cfg, motion);
    best_cpu = std::min(best_cpu, thread_cpu_seconds() - c0);
    if (run.seconds < best) {
      const std::vector<double> us(run.frame_seconds.begin(), run.frame_seconds.end());
      out.p99_us = 1e6 * percentile(us, 0.99);
      best = run.seconds;
    }
    if (pass == 0) out.output = std::move(run.output);
  }
  out.fps = best > 0 ? motion.frame_count() / best : 0;
  out.cpu_fps = best_cpu > 0 ? motion.frame_count() / best_cpu : 0;
  return out;
}

// See SpeedResult: the first protocol's fold with the longest test trial.
void measure_speed(EvalResult& res, const std::vector<accent::PreparedTrial>& prepared, const Skeleton& reference,
                   const std::vector<TestTrack>& tests, const Catalogue& data, const RunOptions& opt) {
  const FoldResult* best = nullptr;
  int best_test = -1;
  for (const auto& p : res.protocols)
    for (const auto& f : p.folds) {
      const auto it = f.methods.find("accent");
      if (it == f.methods.end() || !it->second.ok) continue;
      for (int t : f.fold.test)
        if (best_test < 0 || tests[static_cast<std::size_t>(t)].motion.frame_count() >
                                 tests[static_cast<std::size_t>(best_test)].motion.frame_count()) {
          best = &f;
          best_test = t;
        }
    }
  if (!best) return;
  SpeedResult& sp = res.speed;
  std::vector<const accent::PreparedTrial*> members;
  for (int d : best->fold.database) members.push_back(&prepared[static_cast<std::size_t>(d)]);
  accent::Database db = accent::assemble_database(members, reference, opt.build);
  const TestTrack& tt = tests[static_cast<std::size_t>(best_test)];
  SpeedPass pass = speed_pass(db, opt.config, tt.motion);
  double k = 1e30;
  for (int i = 0; i < 3; ++i) {
    double s = 0;
    Motion ik = run_ik_baseline_at_height(reference, tt.motion, &s);
    k = std::min(k, s);
    if (i == 0) sp.ik = std::move(ik);
  }
  sp.accent = std::move(pass.output);
  sp.accent_frames_per_second = pass.fps;
  sp.accent_cpu_frames_per_second = pass.cpu_fps;
  sp.accent_p99_us = pass.p99_us;
  std::tie(sp.fast_recall_unseeded, sp.fast_recall) = fast_recall(db, opt.config, tt.motion, -1);
  std::tie(sp.load_ms, sp.load_ms_unverified, sp.database_bytes) = time_load(db);
  sp.truth = tt.motion;
  sp.trial = tt.id;
  sp.fold = std::string(protocol_key(best->fold.protocol)) + " " + best->fold.cls + " " + best->fold.held_out;
  sp.frames = tt.motion.frame_count();
  sp.database_windows = db.window_count();
  sp.ik_frames_per_second = k > 0 ? tt.motion.frame_count() / k : 0;
  if (!opt.no_class || best->fold.protocol == Protocol::CrossDataset) return;
  members.clear();
  for (int d : no_class_members(best->fold, data)) members.push_back(&prepared[static_cast<std::size_t>(d)]);
  const accent::Database all = accent::assemble_database(members, reference, opt.build);
  const SpeedPass nc = speed_pass(all, no_class_settings(opt.config), tt.motion);
  sp.no_class_windows = all.window_count();
  sp.no_class_frames_per_second = nc.fps;
  sp.no_class_cpu_frames_per_second = nc.cpu_fps;
  sp.no_class_p99_us = nc.p99_us;
  std::tie(sp.no_class_fast_recall_unseeded, sp.no_class_fast_recall) =
      fast_recall(all, opt.config, tt.motion, all.find_class(best->fold.cls));
  std::tie(sp.no_class_load_ms, sp.no_class_load_ms_unverified, sp.no_class_database_bytes) = time_load(all);
}

}  // namespace

std::vector<Variant> ablation_variants(const accent::BuildConfig& build, const accent::Settings& config, bool quick) {
  std::vector<Variant> v;
  auto add = [&](std::string key, std::string label, auto tweak) {
    Variant x{std::move(key), std::move(label), build, config};
    tweak(x);
    v.push_back(std::move(x));
  };
  // The document's steps run on the document's settings (k = 5, EWMA only,
  // hands not pinned, no foot locking, no IK blend), so they compare with its
  // 16.5 -> 13.2 -> 11.4 cm.
  const auto paper = [](Variant& x) {
    x.config.k_left = x.config.k_right = 5;
    x.config.smooth_halflife = 0;
    x.config.smooth_feedforward = 0;
    x.config.lying_root_smoothing = 1;
    x.config.lying_crown = 0;
    x.config.hand_ik = 0;
    x.config.foot_lock = false;
    x.config.ik_blend_min = x.config.ik_blend_max = 0;
    x.config.travel_weight = 0;
    x.config.max_head_height_diff = 0;
  };
  add("nn", "NN only (document's settings, no alignment, no smoothing)", [&](Variant& x) {
    paper(x);
    x.config.align = false;
    x.config.smooth = false;
  });
  add("nn_align", "NN + rotation alignment", [&](Variant& x) {
    paper(x);
    x.config.smooth = false;
  });
  add("paper", "+ EWMA smoothing (the document's method)", [&](Variant& x) { paper(x); });
  // legwork's additions, one at a time on top of the document's method; the
  // full engine ("accent") adds hand IK last.
  add("spring", "+ spring smoothing", [&](Variant& x) {
    paper(x);
    x.config.smooth_halflife = config.smooth_halflife;
  });
  add("spring_k", "+ spring smoothing + engine k", [&](Variant& x) {
    paper(x);
    x.config.smooth_halflife = config.smooth_halflife;
    x.config.k_left = config.k_left;
    x.config.k_right = config.k_right;
  });
  if (quick) return v;
  // Each other choice changed alone from the engine's defaults.
  add("hop_1", "hop 1 sample (11 ms)", [](Variant& x) { x.build.hop = 1; });
  add("hop_9", "hop 9 samples (100 ms)", [](Variant& x) { x.build.hop = 9; });
  add("no_augmentation", "no speed augmentation", [](Variant& x) { x.build.speed_variants = 0; });
  add("mirrored", "+ mirrored trials", [](Variant& x) { x.build.mirror = true; });
  add("k_1", "k = 1", [](Variant& x) { x.config.k_left = x.config.k_right = 1; });
  add("k_5", "k = 5", [](Variant& x) { x.config.k_left = x.config.k_right = 5; });
  add("threshold_off", "no distance threshold", [](Variant& x) { x.config.threshold = 0; });
  add("threshold_2", "threshold 2 x typical distance", [](Variant& x) { x.config.threshold = 2; });
  add("exact_search", "exact k-NN search", [](Variant& x) { x.config.search = accent::SearchMode::Exact; });
  add("no_hand_ik", "hands not pinned (hand_ik = 0)", [](Variant& x) { x.config.hand_ik = 0.0; });
  add("ewma_only", "EWMA smoothing only (no spring)", [](Variant& x) { x.config.smooth_halflife = 0; });
  add("no_feedforward", "smoothing pulls toward a still target (smooth_feedforward = 0: the candidates' motion not played forward)",
      [](Variant& x) { x.config.smooth_feedforward = 0; });
  add("no_lying_root_smoothing", "a lying user's root smoothed like every joint (lying_root_smoothing = 1)",
      [](Variant& x) { x.config.lying_root_smoothing = 1; });
  add("no_lying_crown", "a lying user's candidates turned by the hands alone (no yaw from the headset's crown, no roll from its face), the standing IK body kept (lying_crown = 0)",
      [](Variant& x) { x.config.lying_crown = 0; });
  add("no_foot_lock", "no foot locking", [](Variant& x) { x.config.foot_lock = false; });
  add("no_ik_blend", "no confidence blend toward the IK body", [](Variant& x) { x.config.ik_blend_min = x.config.ik_blend_max = 0; });
  add("foot_lock_held", "feet held still while planted (no creep)", [](Variant& x) { x.config.foot_lock_follow_seconds = 0; });
  add("no_foot_lock_hold", "planted feet creep from touch-down (foot_lock_hold_seconds = 0)",
      [](Variant& x) { x.config.foot_lock_hold_seconds = 0; });
  add("no_foot_lift", "released feet slide back along the floor (foot_lift_height = 0)",
      [](Variant& x) { x.config.foot_lift_height = 0; });
  add("foot_slack", "planted feet hold within 0.1 m before creeping (foot_lock_slack = 0.1)",
      [](Variant& x) { x.config.foot_lock_slack = 0.1; });
  // Issue 12, "where IK wins": a floor under the IK body's share (helps the
  // cross-subject folds whose databases hold one or two trials, costs the
  // well-covered cross-trial folds; docs/accent.md).
  add("ik_floor_0.3", "IK body's share at least 0.3 (ik_blend_min = 0.3)", [](Variant& x) { x.config.ik_blend_min = 0.3; });
  add("ik_floor_0.5", "IK body's share at least 0.5 (ik_blend_min = 0.5)", [](Variant& x) { x.config.ik_blend_min = 0.5; });
  add("no_travel", "no travel terms in the match (travel_weight = 0: hand features only)",
      [](Variant& x) { x.config.travel_weight = 0; });
  add("no_height_gate", "no head-height gate (max_head_height_diff = 0: lying bodies may go under a standing user)",
      [](Variant& x) { x.config.max_head_height_diff = 0; });
  add("no_swing_clearance", "swinging feet not lifted clear of the floor (foot_swing_speed = 0)",
      [](Variant& x) { x.config.foot_swing_speed = 0; });
  add("no_floor", "feet may go through the floor (floor = false: no knee bend to keep them above it, feet pushed into it not planted)",
      [](Variant& x) { x.config.floor = false; });
  return v;
}

namespace {
// Head and hands only: the baseline, like the engine, sees no foot trackers.
std::vector<TrackerFrame> head_and_hands(const Motion& truth) {
  std::vector<TrackerFrame> frames = tracker_frames_from_motion(truth);
  for (TrackerFrame& f : frames) f.foot(kLeft) = f.foot(kRight) = DevicePose{};
  return frames;
}
}  // namespace

Motion run_ik_baseline(const Motion& truth, double* seconds) {
  return run_ik_baseline(truth.skeleton, head_and_hands(truth), truth.fps, seconds);
}

Motion run_ik_baseline_at_height(const Skeleton& reference, const Motion& truth, double* seconds) {
  // The engine's rule (accent::make_model): user height / database skeleton height.
  Skeleton skel = reference;
  const double h_ref = measure_body(reference).standing_height, h = measure_body(truth.skeleton).standing_height;
  if (h_ref > 0 && h > 0) skel.scale(h / h_ref);
  return run_ik_baseline(skel, head_and_hands(truth), truth.fps, seconds);
}

namespace {

using Prepared = std::map<std::string, std::vector<accent::PreparedTrial>>;  // by prepare_key
using Say = std::function<void(const std::string&)>;

// Every trial prepared once per distinct preparation of the variants.
Prepared prepare_all(const std::vector<accent::TrialInput>& inputs, const Skeleton& reference,
                     const std::vector<Variant>& variants, int threads, const Say& say) {
  Prepared prepared;
  std::map<std::string, accent::BuildConfig> prepare_cfg;
  for (const auto& v : variants) prepare_cfg.emplace(prepare_key(v.build), v.build);
  for (const auto& [key, cfg] : prepare_cfg) {
    auto& set = prepared[key];
    set.resize(inputs.size());
    std::atomic<int> done{0};
    std::mutex m;
    parallel_for(iota(static_cast<int>(inputs.size())), threads, [&](int i) {
      set[static_cast<std::size_t>(i)] = accent::prepare_trial(inputs[static_cast<std::size_t>(i)], reference, cfg);
      const int d = ++done;
      std::lock_guard<std::mutex> lock(m);
      say("preparing trials" + std::string(cfg.mirror ? " (with mirrored copies)" : "") + ": " + std::to_string(d) +
          "/" + std::to_string(inputs.size()));
    });
  }
  return prepared;
}

// Trials and subjects per class, and the trials the build drops (with why).
DatasetSummary summarize_data(const Catalogue& data, const std::vector<accent::PreparedTrial>& base) {
  DatasetSummary out;
  out.root = data.root;
  out.trials = static_cast<int>(data.trials.size());
  std::map<std::string, std::set<int>> subjects;
  for (const auto& e : data.trials) {
    ++out.trials_per_class[e.cls];
    subjects[e.cls].insert(e.subject);
  }
  for (const auto& [c, s] : subjects) out.subjects_per_class[c] = static_cast<int>(s.size());
  for (std::size_t i = 0; i < base.size(); ++i)
    if (!base[i].kept) out.dropped[data.trials[i].id() + " (" + data.trials[i].cls + ")"] = base[i].reason;
  return out;
}

// Each protocol's folds (checked for leaks) and the methods it scores.
void plan_protocols(EvalResult& res, const Catalogue& data, const Catalogue* test, const RunOptions& opt) {
  for (Protocol p : opt.protocols) {
    ProtocolResult pr;
    pr.protocol = p;
    pr.plan = p == Protocol::CrossDataset ? plan_cross_dataset(data, *test) : plan_folds(data, p);
    const Catalogue& tc = p == Protocol::CrossDataset ? *test : data;
    for (const auto& f : pr.plan.folds) {
      const std::string leak = fold_leak(f, data, tc);
      if (!leak.empty()) throw Error("fold plan leaks: " + leak);
      FoldResult fr;
      fr.fold = f;
      for (int t : f.test) fr.test_ids.push_back(tc.trials[static_cast<std::size_t>(t)].id());
      pr.folds.push_back(std::move(fr));
    }
    if (opt.ik) pr.methods.push_back("ik");
    if (opt.ik_own_skeleton) pr.methods.push_back("ik_own");
    if (opt.no_class && p != Protocol::CrossDataset) pr.methods.push_back("no_class");
    for (const auto& v : res.variants)
      if (v.key == "accent" || p == Protocol::CrossSubject) pr.methods.push_back(v.key);
    res.protocols.push_back(std::move(pr));
  }
}

// One task per fold, with a cost estimate (database frames + 20 x test frames, x methods).
struct Task {
  int protocol, fold;
  double cost;
};
std::vector<Task> plan_tasks(const EvalResult& res, const std::vector<accent::TrialInput>& inputs,
                             const std::vector<TestTrack>& tests) {
  std::vector<Task> tasks;
  for (int p = 0; p < static_cast<int>(res.protocols.size()); ++p)
    for (int f = 0; f < static_cast<int>(res.protocols[static_cast<std::size_t>(p)].folds.size()); ++f) {
      const Fold& fold = res.protocols[static_cast<std::size_t>(p)].folds[static_cast<std::size_t>(f)].fold;
      double cost = 0;
      for (int d : fold.database) cost += inputs[static_cast<std::size_t>(d)].motion.frame_count();
      for (int t : fold.test) cost += 20.0 * tests[static_cast<std::size_t>(t)].motion.frame_count();
      cost *= static_cast<double>(res.protocols[static_cast<std::size_t>(p)].methods.size());
      tasks.push_back({p, f, cost});
    }
  return tasks;
}

// What one fold needs to score its methods.
struct FoldContext {
  const Catalogue& data;
  const std::vector<Variant>& variants;
  const Prepared& prepared;
  const Skeleton& reference;
  const std::vector<TestTrack>& tests;
  const RunOptions& opt;
};

// The accent variants of a fold, grouped by the database they need.
void score_accent(const FoldContext& c, const ProtocolResult& pr, const std::vector<std::string>& test_files,
                  FoldResult& fr) {
  const Fold& fold = fr.fold;
  std::map<std::string, std::vector<const Variant*>> by_db;
  for (const auto& v : c.variants)
    if (std::find(pr.methods.begin(), pr.methods.end(), v.key) != pr.methods.end()) by_db[build_key(v.build)].push_back(&v);
  for (const auto& [key, variants] : by_db) {
    const accent::BuildConfig& bc = variants.front()->build;
    const auto& set = c.prepared.at(prepare_key(bc));
    std::vector<const accent::PreparedTrial*> members;
    for (int d : fold.database) members.push_back(&set[static_cast<std::size_t>(d)]);
    accent::Database db;
    try {
      db = accent::assemble_database(members, c.reference, bc);
      db.build_index();
    } catch (const Error& e) {
      for (const Variant* v : variants) fr.methods[v->key].error = e.what();
      continue;
    }
    const std::string leak = leak_in_database(fold, db, test_files);
    if (!leak.empty()) throw Error("fold leak: " + leak);
    for (const Variant* v : variants) {
      MethodFold& mf = fr.methods[v->key];
      mf.database_windows = db.window_count();
      std::vector<TrialMetrics> per;
      for (int t : fold.test) {
        const TestTrack& tt = c.tests[static_cast<std::size_t>(t)];
        const accent::AccentRun run = accent::accentuate_motion(db, v->config, tt.motion);
        per.push_back(evaluate_trial(role_track(run.output), tt.truth, c.opt.metrics));
        mf.frames += tt.motion.frame_count();
        mf.seconds += run.seconds;
      }
      mf.metrics = combine(per);
      mf.ok = true;
    }
  }
}

// The no-class setting on a fold: one database of every class (held-out
// subject / test trials left out), the engine recognising the class.
void score_no_class(const FoldContext& c, const std::vector<std::string>& test_files, FoldResult& fr) {
  MethodFold& mf = fr.methods["no_class"];
  const auto& set = c.prepared.at(prepare_key(c.opt.build));
  std::vector<const accent::PreparedTrial*> members;
  for (int d : no_class_members(fr.fold, c.data)) members.push_back(&set[static_cast<std::size_t>(d)]);
  accent::Database db;
  try {
    db = accent::assemble_database(members, c.reference, c.opt.build);
  } catch (const Error& e) {
    mf.error = e.what();
    return;
  }
  const std::string leak = leak_in_database(fr.fold, db, test_files);
  if (!leak.empty()) throw Error("fold leak (no-class database): " + leak);
  const accent::Settings cfg = no_class_settings(c.opt.config);
  const int want = db.find_class(fr.fold.cls);
  mf.database_windows = db.window_count();
  std::vector<TrialMetrics> per;
  for (int t : fr.fold.test) {
    const TestTrack& tt = c.tests[static_cast<std::size_t>(t)];
    const accent::AccentRun run = accent::accentuate_motion(db, cfg, tt.motion);
    per.push_back(evaluate_trial(role_track(run.output), tt.truth, c.opt.metrics));
    mf.frames += tt.motion.frame_count();
    mf.seconds += run.seconds;
    int last = -1;
    for (const auto& info : run.info) {
      mf.class_frames_right += info.active_class == want;
      mf.class_switches += last >= 0 && info.active_class >= 0 && info.active_class != last;
      if (info.active_class >= 0) last = info.active_class;
    }
  }
  mf.metrics = combine(per);
  mf.ok = true;
}

// The IK baseline on a fold's test trials: "ik" on the reference skeleton at
// the user's height (what the engine gets), "ik_own" on the subject's own.
void score_ik(const FoldContext& c, FoldResult& fr, bool own_skeleton) {
  MethodFold& mf = fr.methods[own_skeleton ? "ik_own" : "ik"];
  std::vector<TrialMetrics> per;
  try {
    for (int t : fr.fold.test) {
      const TestTrack& tt = c.tests[static_cast<std::size_t>(t)];
      const Motion out = own_skeleton ? run_ik_baseline(tt.motion, &mf.seconds)
                                      : run_ik_baseline_at_height(c.reference, tt.motion, &mf.seconds);
      per.push_back(evaluate_trial(role_track(out), tt.truth, c.opt.metrics));
      mf.frames += tt.motion.frame_count();
    }
    mf.metrics = combine(per);
    mf.ok = true;
  } catch (const Error& e) {
    mf.error = e.what();
  }
}

// "d/n folds  protocol class held-out: accent x cm, ik y cm  (s)"
std::string fold_line(int d, std::size_t n, const ProtocolResult& pr, const FoldResult& fr, double seconds) {
  char line[256];
  const auto a = fr.methods.find("accent"), i = fr.methods.find("ik");
  std::snprintf(line, sizeof line, "%d/%zu folds  %s %s %s: accent %.1f cm, ik %.1f cm  (%.0f s)", d, n,
                protocol_key(pr.protocol), fr.fold.cls.c_str(), fr.fold.held_out.c_str(),
                a != fr.methods.end() && a->second.ok ? a->second.metrics.mpjpe_cm : NAN,
                i != fr.methods.end() && i->second.ok ? i->second.metrics.mpjpe_cm : NAN, seconds);
  return line;
}

}  // namespace

EvalResult run_evaluation(const Catalogue& data, const Catalogue* test, const RunOptions& opt) {
  const auto t_start = Clock::now();
  EvalResult res;
  res.threads = opt.threads > 0 ? opt.threads : std::max(1u, std::thread::hardware_concurrency());
  const Say say = [&](const std::string& s) {
    if (opt.progress) opt.progress(s);
  };

  // Variants: the engine first, then the ablation.
  res.variants.push_back({"accent", "accent engine", opt.build, opt.config});
  if (opt.ablation)
    for (auto& v : ablation_variants(opt.build, opt.config, opt.quick_ablation)) res.variants.push_back(std::move(v));

  // Load and prepare every trial once; folds assemble databases from them.
  const std::vector<accent::TrialInput> inputs = load_all(data, opt.drop_first_frame, res.threads, opt.progress);
  const bool cross_dataset =
      std::find(opt.protocols.begin(), opt.protocols.end(), Protocol::CrossDataset) != opt.protocols.end();
  if (cross_dataset && !test) throw Error("cross-dataset evaluation needs a test folder");
  std::vector<accent::TrialInput> test_inputs;
  if (cross_dataset) test_inputs = load_all(*test, opt.drop_first_frame, res.threads, opt.progress);
  const Skeleton reference = accent::reference_skeleton(inputs);
  const Prepared prepared = prepare_all(inputs, reference, res.variants, res.threads, say);
  res.data = summarize_data(data, prepared.at(prepare_key(opt.build)));

  // Test tracks at the database rate.
  const std::vector<accent::TrialInput>& test_src = cross_dataset ? test_inputs : inputs;
  std::vector<TestTrack> tests(test_src.size());
  parallel_for(iota(static_cast<int>(test_src.size())), res.threads, [&](int i) {
    tests[static_cast<std::size_t>(i)] = make_test(test_src[static_cast<std::size_t>(i)], opt.build.fps, opt.max_test_seconds);
  });

  // Plan every protocol's folds; one task per fold, the costliest first.
  plan_protocols(res, data, test, opt);
  const std::vector<Task> tasks = plan_tasks(res, inputs, tests);
  std::vector<int> order = iota(static_cast<int>(tasks.size()));
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return tasks[static_cast<std::size_t>(a)].cost > tasks[static_cast<std::size_t>(b)].cost;
  });

  const FoldContext context{data, res.variants, prepared, reference, tests, opt};
  std::atomic<int> done{0};
  std::mutex say_mutex;
  parallel_for(order, res.threads, [&](int k) {
    const Task& task = tasks[static_cast<std::size_t>(k)];
    ProtocolResult& pr = res.protocols[static_cast<std::size_t>(task.protocol)];
    FoldResult& fr = pr.folds[static_cast<std::size_t>(task.fold)];
    const Catalogue& tc = pr.protocol == Protocol::CrossDataset ? *test : data;
    std::vector<std::string> test_files;
    for (int t : fr.fold.test) test_files.push_back(tc.trials[static_cast<std::size_t>(t)].file);
    score_accent(context, pr, test_files, fr);
    if (opt.no_class && pr.protocol != Protocol::CrossDataset) score_no_class(context, test_files, fr);
    if (opt.ik) score_ik(context, fr, false);
    if (opt.ik_own_skeleton) score_ik(context, fr, true);
    const int d = ++done;
    const std::string line = fold_line(d, tasks.size(), pr, fr, since(t_start));
    std::lock_guard<std::mutex> lock(say_mutex);
    say(line);
  });
  measure_speed(res, prepared.at(prepare_key(opt.build)), reference, tests, data, opt);
  res.seconds = since(t_start);
  return res;
}

}  // namespace legwork::eval

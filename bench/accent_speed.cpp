// Accentuation speed, recall and memory figures (printed and as JSON): load
// time, per-frame latency (mean, p99) and frames/s of brute/exact/fast search
// on one core, fast-mode recall against brute force, bytes per avatar, and
// optionally a timed database build. Google Benchmark's view of the same loop
// is accent_bench; this program reports the figures the README quotes.
#include <legwork/accent/accent.hpp>
#include <legwork/core/stats.hpp>
#include <legwork/accent/offline/builder.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/core/measure.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/io/text.hpp>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <memory>
#include <sys/resource.h>
#include <thread>

namespace {

using namespace legwork;
using namespace legwork::accent;
using json = nlohmann::json;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

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

const char* mode_name(SearchMode m) { return m == SearchMode::Fast ? "fast" : m == SearchMode::Exact ? "exact" : "brute"; }

// --modes: comma-separated search mode names.
std::vector<SearchMode> parse_modes(const std::string& list) {
  std::vector<SearchMode> timed;
  for (const auto& name : split_commas(list)) {
    if (name == "brute") timed.push_back(SearchMode::BruteForce);
    else if (name == "exact") timed.push_back(SearchMode::Exact);
    else if (name == "fast") timed.push_back(SearchMode::Fast);
    else throw std::runtime_error("--modes: unknown search mode '" + name + "' (expected brute, exact or fast)");
  }
  return timed;
}

struct BenchArgs {
  std::string db, json_path, data, classes;
  std::string input;
  bool drop_first = false, no_foot_lock = false, no_ik_blend = false, no_class_recognition = false;
  std::string classes_run;  // --run-classes: classes the timed avatar matches (default: all)
  std::string modes = "brute,exact,fast";  // --modes: search modes timed
  std::vector<SearchMode> timed;           // the same, parsed
  bool no_recall = false;                   // --no-recall: skip the recall pass
  double scale = 0, other_class_cost = Settings{}.other_class_cost, search_interval = Settings{}.search_interval;
  int repeat = 3, k = Settings{}.k_left, max_checks = Settings{}.fast_max_checks;
  int avatars = 1;  // --avatars: updated round robin on this core (a server's sessions)
  float eps = Settings{}.fast_eps;
};

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

Motion load_input(const BenchArgs& a) {
  io::BvhReadOptions o;
  o.drop_first_frame = a.drop_first;
  o.scale = a.scale;
  return io::load_bvh(a.input, o);
}

// Load (best of 5 each): mapping + header/metadata checks; + the stored
// search index; + the checksum; and rebuilding the KD-trees instead.
Database measure_load(const BenchArgs* a, json& j) {
  auto best_load = [&](bool verify, bool index) {
    double best = 1e30;
    for (int i = 0; i < 5; ++i) {
      LoadOptions lo;
      lo.verify_checksum = verify;
      lo.build_index = index;
      const auto t0 = Clock::now();
      const Database d = load_database(a->db, lo);
      best = std::min(best, seconds_since(t0) * 1e3);
    }
    return best;
  };
  const double map_ms = best_load(false, false), indexed_ms = best_load(false, true), verified_ms = best_load(true, true);
  LoadOptions lo;
  lo.build_index = false;
  Database db = load_database(a->db, lo);
  auto t0 = Clock::now();
  db.build_index(8);  // another leaf size than the stored trees': a real rebuild
  const double index_ms = seconds_since(t0) * 1e3;
  db = load_database(a->db);
  std::printf("database: %d windows, %d classes, %.1f MB\n", db.window_count(), db.class_count(), db.bytes().size() / 1e6);
  std::printf("load (best of 5): %.2f ms mmap + checks, %.2f ms with the stored search index, %.2f ms with index and checksum; "
              "rebuilding the KD-trees instead: %.1f ms\n",
              map_ms, indexed_ms, verified_ms, index_ms);
  j["windows"] = db.window_count();
  j["database_bytes"] = db.bytes().size();
  j["load_ms_mmap"] = map_ms;
  j["load_ms_with_index"] = indexed_ms;
  j["load_ms_verified"] = verified_ms;
  j["index_build_ms"] = index_ms;
  return db;
}

// Fast-mode recall: the live queries of this trial, fast vs brute force.
void measure_recall(const Database& db, const BenchArgs* a, const Motion& truth, const std::vector<TrackerFrame>& frames,
                    json& j) {
  Settings cfg;
  cfg.user_height = measure_body(truth.skeleton).standing_height;
  cfg.fast_max_checks = a->max_checks;
  const Model model = make_model(db, cfg);
  const State state(model);
  std::array<Match, kMaxK> brute{}, fast{};
  const double scale = db.height() / cfg.user_height;
  std::vector<float> eps_list{0.5f, 1.0f, 2.0f, 5.0f, 10.0f};
  if (std::find(eps_list.begin(), eps_list.end(), a->eps) == eps_list.end()) eps_list.push_back(a->eps);
  json by_eps = json::object();
  for (float eps : eps_list) {
    std::size_t hits = 0, total = 0;
    for (std::size_t f = window_lag(0); f < frames.size(); ++f) {
      for (int h = 0; h < 2; ++h) {
        HandWindow w;
        window_from_frames(frames, f, h, scale, w);
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
  j["avatar_state_bytes"] = state.bytes();
  j["model_bytes"] = model.bytes();
}
// The machine's load, printed and recorded: wall-clock figures include the
// time the machine gave to other processes.
void record_load(json& j) {
  double load[3] = {0, 0, 0};
  if (std::FILE* f = std::fopen("/proc/loadavg", "r")) {
    if (std::fscanf(f, "%lf %lf %lf", &load[0], &load[1], &load[2]) != 3) load[0] = -1;
    std::fclose(f);
  }
  j["machine_load_1min"] = load[0];
  std::printf("machine load (1 min): %.1f on %u cores - wall-clock figures include time given to other processes\n", load[0],
              std::thread::hardware_concurrency());
}

// Frames between two avatars' starting points in the trial (--avatars; as serve_load's clients).
constexpr std::size_t kAvatarOffset = 7;

// Per-frame latency (mean, p99) and frames/s (wall and thread CPU) of one
// avatar (or --avatars round robin) over the trial, per search mode.
void measure_modes(const Database& db, const BenchArgs* a, const Motion& truth, const std::vector<TrackerFrame>& frames,
                   json& j) {
  json modes = json::object();
  const std::vector<SearchMode>& timed = a->timed;
  for (SearchMode mode : timed) {
    Settings cfg;
    cfg.search = mode;
    cfg.fast_eps = a->eps;
    cfg.fast_max_checks = a->max_checks;
    cfg.k_left = cfg.k_right = a->k;
    cfg.user_height = measure_body(truth.skeleton).standing_height;
    cfg.foot_lock = !a->no_foot_lock;
    cfg.recognize_class = !a->no_class_recognition;
    cfg.other_class_cost = a->other_class_cost;
    cfg.search_interval = a->search_interval;
    cfg.classes = split_commas(a->classes_run);
    if (a->no_ik_blend) cfg.ik_blend_min = cfg.ik_blend_max = 0;
    std::vector<double> lat;
    lat.reserve(frames.size() * static_cast<std::size_t>(a->repeat * a->avatars));
    double total = 0, cpu = 0;
    std::size_t bytes = 0;
    for (int r = 0; r < a->repeat; ++r) {
      // --avatars: each its own model and state (as a server's sessions), avatar i
      // kAvatarOffset x i frames into the trial, all updated once per input frame.
      std::vector<Model> models;
      std::vector<State> states;
      std::vector<Pose> poses;
      models.reserve(static_cast<std::size_t>(a->avatars));
      states.reserve(static_cast<std::size_t>(a->avatars));
      for (int i = 0; i < a->avatars; ++i) {
        models.push_back(make_model(db, cfg));
        states.emplace_back(models.back());
        poses.emplace_back(models.back().skeleton());
      }
      bytes = states[0].bytes();
      const double c0 = thread_cpu_seconds();
      for (std::size_t f = 0; f < frames.size(); ++f) {
        for (std::size_t i = 0; i < models.size(); ++i) {
          TrackerFrame in = frames[(f + kAvatarOffset * i) % frames.size()];
          in.time = frames[f].time;
          const auto s = Clock::now();
          update(models[i], in, states[i], poses[i].ref());
          const double dt = seconds_since(s);
          lat.push_back(dt);
          total += dt;
        }
      }
      cpu += thread_cpu_seconds() - c0;
    }
    const double mean_us = 1e6 * total / static_cast<double>(lat.size());
    const double p99_us = 1e6 * percentile(lat, 0.99);
    const double fps_run = static_cast<double>(lat.size()) / total;
    const double fps_cpu = static_cast<double>(lat.size()) / cpu;
    std::printf("%-6s wall: mean %7.2f us, p99 %7.2f us, %8.0f frames/s | CPU time: %8.0f frames/s (%.0fx the document's 152 Hz)%s\n",
                mode_name(mode), mean_us, p99_us, fps_run, fps_cpu, fps_cpu / 152.0,
                a->avatars > 1 ? (", " + std::to_string(a->avatars) + " avatars round robin").c_str() : "");
    modes[mode_name(mode)] = {{"mean_us", mean_us}, {"p99_us", p99_us}, {"frames_per_second", fps_run},
                              {"frames_per_cpu_second", fps_cpu}, {"cpu_us_per_frame", 1e6 * cpu / static_cast<double>(lat.size())},
                              {"speedup_vs_152hz", fps_cpu / 152.0}, {"avatar_state_bytes", bytes}};
  }
  j["modes"] = modes;
  j["avatars"] = a->avatars;
  if (!timed.empty()) j["avatar_state_bytes"] = modes[mode_name(timed.back())]["avatar_state_bytes"];
}

// A timed database build from --data (the --input trial excluded).
void measure_build(const BenchArgs* a, json& j) {
  auto t1 = Clock::now();
  const auto trials = load_trials(a->data, split_commas(a->classes), {a->input});
  const double read_s = seconds_since(t1);
  t1 = Clock::now();
  const Database built = build_database(trials, BuildConfig{});
  const double build_s = seconds_since(t1);
  std::printf("build: %zu trials read in %.2f s, database (%d windows) built in %.2f s\n", trials.size(), read_s,
              built.window_count(), build_s);
  j["build"] = {{"data", a->data}, {"trials", trials.size()}, {"read_seconds", read_s}, {"build_seconds", build_s},
                {"windows", built.window_count()}};
}
}  // namespace

int run(int argc, char** argv) {
  CLI::App app{
      "Measure load time, per-frame latency (mean, p99) and frames/s of exact vs fast search, fast-mode recall and memory,\n"
      "driving one avatar with a real held-out trial on one core.\n"
      "Example: build/bench/accent_speed --db table1.lwdb --input ../shared/data/cmu/bvh/running/09_01.bvh --drop-first --json bench.json"};
  auto* cmd = &app;
  auto a = std::make_shared<BenchArgs>();
  cmd->add_option("--db", a->db, "database file")->required()->check(CLI::ExistingFile);
  cmd->add_option("--input", a->input, "held-out BVH trial driving the avatar")->required()->check(CLI::ExistingFile);
  cmd->add_flag("--drop-first", a->drop_first, "drop frame 0 (the CMU T-pose)");
  cmd->add_option("--scale", a->scale, "metres per BVH unit (default: detected)");
  cmd->add_option("--repeat", a->repeat, "passes over the trial per mode")->check(CLI::PositiveNumber);
  cmd->add_option("--k", a->k, "matches per hand")->check(CLI::Range(1, kMaxK));
  cmd->add_option("--eps", a->eps, "fast-mode approximation (neighbours within (1+eps) x the true distance)")->check(CLI::Range(0.0f, 100.0f));
  cmd->add_option("--data", a->data, "also time a database build from this folder (the --input file excluded)");
  cmd->add_option("--classes", a->classes, "classes for the timed build (default: all)");
  cmd->add_option("--max-checks", a->max_checks, "fast-mode budget of candidates per search (0 = unlimited)")->check(CLI::Range(0, 100000000));
  cmd->add_option("--json", a->json_path, "write the figures as JSON");
  cmd->add_flag("--no-foot-lock", a->no_foot_lock, "time the engine without foot locking");
  cmd->add_flag("--no-ik-blend", a->no_ik_blend, "time the engine without the IK blend");
  cmd->add_flag("--no-class-recognition", a->no_class_recognition,
                "with several classes allowed, search all of them every frame (default: recognise the class, search its index)");
  cmd->add_option("--search-interval", a->search_interval,
                  "seconds between two searches of the database (0 = every frame)")->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--other-class-cost", a->other_class_cost,
                 "while recognising the class, also search the others at this factor on their distances (0 = off)")
      ->check(CLI::Range(0.0, 1e6));
  cmd->add_option("--run-classes", a->classes_run, "comma-separated classes the timed avatar matches (default: all)");
  cmd->add_option("--modes", a->modes, "comma-separated search modes to time: brute, exact, fast (default: all three)");
  cmd->add_flag("--no-recall", a->no_recall, "skip the fast-mode recall pass");
  cmd->add_option("--avatars", a->avatars,
                  "time this many avatars updated round robin on this core, each its own model and state and 7 frames "
                  "further into the trial (a server's sessions: their states compete for the cache)")
      ->check(CLI::Range(1, 5000));
  CLI11_PARSE(app, argc, argv);
  a->timed = parse_modes(a->modes);  // a bad --modes fails before the database loads
  {
    json j;
    j["database"] = a->db;
    j["input"] = a->input;
    record_load(j);
    Database db = measure_load(a.get(), j);

    const double fps = db.feature_space().fps;
    Motion truth = resample(load_input(*a), fps);
    const auto frames = tracker_frames_from_motion(truth);
    j["input_frames"] = frames.size();
    measure_modes(db, a.get(), truth, frames, j);
    if (!a->no_recall) measure_recall(db, a.get(), truth, frames, j);
    if (!a->data.empty()) measure_build(a.get(), j);
    j["peak_rss_kb"] = peak_rss_kb();
    std::printf("memory: database %.1f MB (mapped, shared by all avatars), %zu bytes per avatar, peak RSS %.1f MB\n",
                db.bytes().size() / 1e6, j.value("avatar_state_bytes", std::size_t{0}), peak_rss_kb() / 1e3);
    if (!a->json_path.empty()) {
      io::write_text_file(a->json_path, j.dump(2) + "\n");
      std::printf("wrote %s\n", a->json_path.c_str());
    }
  }
  return 0;
}


int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}

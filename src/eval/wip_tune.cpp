// The adaptive step detector's parameters chosen by cross-validation by subject.
#include <legwork/eval/wip_tune.hpp>

#include <legwork/wip/offline/run.hpp>
#include <legwork/wip/offline/synthetic.hpp>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <map>
#include <sstream>

namespace legwork::eval {

void DetectorParams::apply(wip::Settings& s) const {
  s.gait.detector = wip::StepDetector::Adaptive;
  s.signal.detect_cutoff = detect_cutoff;
  s.gait.lift_fraction = lift_fraction;
  s.gait.min_lift = min_lift;
  s.gait.min_rise = min_rise;
  s.gait.noise_factor = noise_factor;
  s.gait.rise_noise_factor = rise_noise_factor;
  s.gait.rise_fraction = rise_fraction;
  s.gait.rest_time = rest_time;
  s.gait.rest_noise_factor = rest_noise_factor;
  s.gait.settle_time = settle_time;
  s.gait.min_swing_time = min_swing_time;
}

DetectorParams DetectorParams::of(const wip::Settings& s) {
  return {s.signal.detect_cutoff, s.gait.lift_fraction, s.gait.min_lift, s.gait.min_rise, s.gait.noise_factor,
          s.gait.rise_noise_factor, s.gait.rise_fraction, s.gait.rest_time, s.gait.rest_noise_factor, s.gait.settle_time,
          s.gait.min_swing_time};
}

std::string DetectorParams::describe() const {
  char b[384];
  char rest[128] = "no start steps";
  if (rest_time > 0)
    std::snprintf(rest, sizeof rest, "start steps after %g s at rest (>= %g x jitter)", rest_time, rest_noise_factor);
  std::snprintf(b, sizeof b,
                "cutoff %g Hz, lift >= max(%g x apex, %g x jitter, %g cm), rise >= max(%g x peak rise, %g x jitter /s, %g m/s), "
                "%s, settle %g s, min swing %g s",
                detect_cutoff, lift_fraction, noise_factor, 100 * min_lift, rise_fraction, rise_noise_factor, min_rise, rest,
                settle_time, min_swing_time);
  return b;
}

std::vector<DetectorParams> default_detector_grid() {
  // The walking thresholds (min lift 1 cm, min rise 0.05 m/s: their alternatives 1.5 cm, 0.1 m/s changed
  // almost nothing in the former 972-point grid) x the start steps: off (the former detector), after 0.5 s
  // at rest above 3.5 or 4 x jitter, after 1 s above 3.5 x jitter (with the steady landing) x the minimum swing
  // time: off, 0.1 s, 0.15 s.
  struct Rest {
    double time, noise, settle;
  };
  const Rest rests[] = {{0, 3.5, 0}, {0.5, 3.5, 0.3}, {0.5, 4.0, 0.3}, {1.0, 3.5, 0.3}};
  std::vector<DetectorParams> g;
  for (const Rest& r : rests)
    for (double dc : {6.0, 8.0, 10.0})
      for (double lf : {0.1, 0.15, 0.2})
        for (double nf : {2.5, 3.0, 3.5})
          for (double rn : {10.0, 20.0, 30.0})
            for (double rf : {0.2, 0.3, 0.4})
              for (double ms : {0.0, 0.1, 0.15})
                g.push_back({dc, lf, 0.01, 0.05, nf, rn, rf, r.time, r.noise, r.settle, ms});
  return g;
}

DetectionTrial prepare_detection_trial(const Motion& trial, const std::string& name, const WipEvalOptions& opt,
                                       int trial_index) {
  DetectionTrial t;
  t.name = name;
  t.subject = subject_of(name);
  t.skeleton = trial.skeleton;
  t.truth = foot_swings(trial, opt.truth);
  t.t_begin = opt.settle;
  t.t_end = trial.duration() - 0.1;  // as evaluate_wip_trial
  t.still = still_segments(trial, name, opt.truth, {}, opt.min_still, t.t_begin, t.t_end);
  t.clean = tracker_frames_from_motion(trial, opt.settings.signal.rate);
  t.noisy = t.clean;
  wip::add_tracker_noise(t.noisy, opt.noise, opt.drop_rate, opt.seed * 1000003ULL + static_cast<std::uint64_t>(trial_index));
  return t;
}

DetectionCounts score_detection(const DetectionTrial& t, const wip::Settings& settings) {
  wip::Settings s = settings;
  s.mapping.depth = wip::DepthMapping::Document;
  const wip::Model model = wip::make_model(t.skeleton, s);
  wip::RunOptions ro;
  ro.calibrate = false;
  ro.keep_poses = false;
  DetectionCounts c;
  const auto clean = detected_swings(wip::run_wip(model, t.clean, ro).frames);
  const auto noisy = detected_swings(wip::run_wip(model, t.noisy, ro).frames);
  c.strict = match_foot_offs(clean, t.truth, 0.2, t.t_begin, t.t_end);
  c.strict_100 = match_foot_offs(clean, t.truth, 0.1, t.t_begin, t.t_end);
  c.noisy = match_foot_offs(noisy, t.truth, 0.2, t.t_begin, t.t_end);
  const auto false_clean = unmatched_detections(clean, t.truth, 0.2), false_noisy = unmatched_detections(noisy, t.truth, 0.2);
  for (const auto& g : t.still) {
    c.still_minutes += (g.end - g.begin) / 60;
    for (const auto& d : false_clean) c.false_steps += d.off >= g.begin && d.off <= g.end ? 1 : 0;
    for (const auto& d : false_noisy) c.false_steps_noisy += d.off >= g.begin && d.off <= g.end ? 1 : 0;
  }
  return c;
}

DetectionCounts pool(std::span<const DetectionCounts> parts) {
  DetectionCounts c;
  std::vector<StrictScore> s, s100, n;
  for (const auto& p : parts) {
    s.push_back(p.strict);
    s100.push_back(p.strict_100);
    n.push_back(p.noisy);
    c.false_steps += p.false_steps;
    c.false_steps_noisy += p.false_steps_noisy;
    c.still_minutes += p.still_minutes;
  }
  c.strict = combine(s);
  c.strict_100 = combine(s100);
  c.noisy = combine(n);
  return c;
}

namespace {

bool acceptable(const DetectionCounts& c, const DetectorTuning& t) {
  const bool still_ok = !(c.still_minutes > 0) || (c.false_per_minute() <= t.max_false_per_minute &&
                                                   c.false_per_minute_noisy() <= t.max_false_per_minute);
  return still_ok && c.strict.median_ms <= t.max_latency_ms;
}

double objective(const DetectionCounts& c) {
  const double a = std::isfinite(c.strict.f1) ? c.strict.f1 : 0, b = std::isfinite(c.noisy.f1) ? c.noisy.f1 : 0;
  return a + b;
}

// The best grid point on the trials `use` marks (the selection rule above).
int choose(const std::vector<std::vector<DetectionCounts>>& per_point, const std::vector<char>& use,
           const DetectorTuning& t) {
  int best = -1, best_any = -1;
  double score = -1, score_any = -1;
  for (std::size_t g = 0; g < per_point.size(); ++g) {
    std::vector<DetectionCounts> parts;
    for (std::size_t i = 0; i < use.size(); ++i)
      if (use[i]) parts.push_back(per_point[g][i]);
    const DetectionCounts c = pool(parts);
    const double o = objective(c);
    if (o > score_any) score_any = o, best_any = static_cast<int>(g);
    if (acceptable(c, t) && o > score) score = o, best = static_cast<int>(g);
  }
  return best >= 0 ? best : best_any;
}

}  // namespace

DetectorTuning tune_detector(std::span<const DetectionTrial> trials, const wip::Settings& settings,
                             std::vector<DetectorParams> grid, const std::function<void(int, int)>& progress) {
  if (trials.empty()) throw Error("detector tuning: no trials");
  if (grid.empty()) throw Error("detector tuning: empty parameter grid");
  DetectorTuning t;
  t.grid = std::move(grid);
  std::vector<std::vector<DetectionCounts>> per_point(t.grid.size());
  for (std::size_t g = 0; g < t.grid.size(); ++g) {
    if (progress) progress(static_cast<int>(g) + 1, static_cast<int>(t.grid.size()));
    wip::Settings s = settings;
    t.grid[g].apply(s);
    for (const auto& trial : trials) per_point[g].push_back(score_detection(trial, s));
    t.all.push_back(pool(per_point[g]));
  }
  std::map<std::string, std::vector<std::size_t>> by_subject;
  for (std::size_t i = 0; i < trials.size(); ++i) by_subject[trials[i].subject].push_back(i);
  std::vector<DetectionCounts> held;
  for (const auto& [subject, members] : by_subject) {
    std::vector<char> train(trials.size(), 1);
    for (std::size_t i : members) train[i] = 0;
    DetectorFold f;
    f.subject = subject;
    f.trials = static_cast<int>(members.size());
    if (by_subject.size() < 2) continue;  // nothing to train on
    f.chosen = choose(per_point, train, t);
    std::vector<DetectionCounts> parts;
    for (std::size_t i : members) parts.push_back(per_point[static_cast<std::size_t>(f.chosen)][i]);
    f.held_out = pool(parts);
    held.push_back(f.held_out);
    t.folds.push_back(f);
  }
  t.cross_validated = pool(held);
  t.chosen_all = choose(per_point, std::vector<char>(trials.size(), 1), t);
  return t;
}

namespace {

nlohmann::json counts_json(const DetectionCounts& c) {
  auto num = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  return {{"f1", num(c.strict.f1)},
          {"precision", num(c.strict.precision)},
          {"recall", num(c.strict.recall)},
          {"true_steps", c.strict.true_steps},
          {"detected", c.strict.detected},
          {"matched", c.strict.matched},
          {"latency_median_ms", num(c.strict.median_ms)},
          {"latency_p90_ms", num(c.strict.p90_ms)},
          {"noisy_f1", num(c.noisy.f1)},
          {"noisy_latency_median_ms", num(c.noisy.median_ms)},
          {"still_minutes", c.still_minutes},
          {"false_steps", c.false_steps},
          {"false_steps_noisy", c.false_steps_noisy}};
}

nlohmann::json params_json(const DetectorParams& p) {
  return {{"detect_cutoff_hz", p.detect_cutoff}, {"lift_fraction", p.lift_fraction}, {"min_lift_m", p.min_lift},
          {"min_rise_mps", p.min_rise},          {"noise_factor", p.noise_factor},   {"rise_noise_factor", p.rise_noise_factor},
          {"rise_fraction", p.rise_fraction},     {"rest_time_s", p.rest_time},      {"rest_noise_factor", p.rest_noise_factor},
          {"settle_time_s", p.settle_time},       {"min_swing_time_s", p.min_swing_time}};
}

}  // namespace

std::string tuning_json(const DetectorTuning& t) {
  nlohmann::json j;
  j["grid_points"] = t.grid.size();
  j["selection"] = {{"objective", "clean + noisy strict F1 (+-200 ms), pooled over the training trials"},
                    {"max_false_steps_per_minute", t.max_false_per_minute},
                    {"max_latency_median_ms", t.max_latency_ms}};
  j["cross_validated"] = counts_json(t.cross_validated);
  j["folds"] = nlohmann::json::array();
  for (const auto& f : t.folds)
    j["folds"].push_back({{"held_out_subject", f.subject}, {"trials", f.trials},
                          {"chosen", params_json(t.grid[static_cast<std::size_t>(f.chosen)])},
                          {"held_out", counts_json(f.held_out)}});
  if (t.chosen_all >= 0) {
    j["chosen_on_all_subjects"] = params_json(t.grid[static_cast<std::size_t>(t.chosen_all)]);
    j["chosen_on_all_subjects_in_sample"] = counts_json(t.all[static_cast<std::size_t>(t.chosen_all)]);
  }
  return j.dump(2) + "\n";
}

std::string tuning_markdown(const DetectorTuning& t) {
  std::ostringstream md;
  const auto& c = t.cross_validated;
  md << "\n## Adaptive detector, parameters cross-validated by subject\n\n"
     << t.grid.size() << " parameter sets; for each subject the set with the best clean + noisy strict F1 on the other "
        "subjects' trials (at most "
     << t.max_false_per_minute << " false step/min on their still segments, median latency <= " << t.max_latency_ms
     << " ms) is scored on that subject's trials only.\n\n"
     << "| held-out subject | trials | chosen | F1 | noisy F1 | latency median ms | false steps (clean / noisy) |\n"
        "|---|---|---|---|---|---|---|\n";
  for (const auto& f : t.folds)
    md << "| " << f.subject << " | " << f.trials << " | " << t.grid[static_cast<std::size_t>(f.chosen)].describe() << " | "
       << format_or_na(f.held_out.strict.f1, "%.3f") << " | " << format_or_na(f.held_out.noisy.f1, "%.3f") << " | "
       << format_or_na(f.held_out.strict.median_ms, "%.0f") << " | " << f.held_out.false_steps << " / "
       << f.held_out.false_steps_noisy << " |\n";
  md << "| **all, held out** | | | **" << format_or_na(c.strict.f1, "%.3f") << "** | **" << format_or_na(c.noisy.f1, "%.3f") << "** | **"
     << format_or_na(c.strict.median_ms, "%.0f") << "** | " << c.false_steps << " / " << c.false_steps_noisy << " ("
     << format_or_na(c.false_per_minute(), "%.2f") << " / " << format_or_na(c.false_per_minute_noisy(), "%.2f") << " per min) |\n";
  if (t.chosen_all >= 0)
    md << "\nChosen on all subjects (the adaptive detector's shipped parameters): " << t.grid[static_cast<std::size_t>(t.chosen_all)].describe()
       << ".\n";
  return md.str();
}

}  // namespace legwork::eval

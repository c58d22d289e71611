#include <legwork/eval/report.hpp>
#include <legwork/core/stats.hpp>

#include <legwork/core/interpolate.hpp>
#include <legwork/render/plot.hpp>
#include <legwork/render/render.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>

namespace legwork::eval {
namespace {

using json = nlohmann::json;

// JSON has no NaN: undefined figures become null.
json num(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }
double get(const json& j, const std::string& key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : kNaN;
}

// Mean and SD across folds of every metric, for the folds selected.
json summarize_folds(const std::vector<const MethodFold*>& folds) {
  json out;
  long frames = 0;
  double seconds = 0;
  for (const auto& k : metric_keys()) {
    std::vector<double> v;
    for (const MethodFold* f : folds) v.push_back(metric_value(f->metrics, k.key));
    const MeanSd s = mean_sd(v);
    out[k.key] = num(s.mean);
    out[std::string(k.key) + "_sd"] = num(s.sd);
  }
  for (const MethodFold* f : folds) {
    frames += f->frames;
    seconds += f->seconds;
  }
  long right = 0;
  int switches = 0;
  for (const MethodFold* f : folds) {
    right += f->class_frames_right;
    switches += f->class_switches;
  }
  if (right > 0 || switches > 0) {  // the no-class setting: class recognition, frame-weighted
    out["class_accuracy"] = num(frames > 0 ? static_cast<double>(right) / static_cast<double>(frames) : kNaN);
    out["class_switches_per_minute"] = num(frames > 0 ? switches / (frames / 90.0 / 60.0) : kNaN);
  }
  out["folds"] = folds.size();
  out["frames"] = frames;
  out["frames_per_second"] = num(seconds > 0 ? static_cast<double>(frames) / seconds : kNaN);
  return out;
}

json summarize_method(const ProtocolResult& p, const std::string& method) {
  std::vector<const MethodFold*> all;
  std::map<std::string, std::vector<const MethodFold*>> by_class;
  json failures = json::array();
  for (const auto& f : p.folds) {
    const auto it = f.methods.find(method);
    if (it == f.methods.end()) continue;
    if (!it->second.ok) {
      failures.push_back({{"class", f.fold.cls}, {"held_out", f.fold.held_out}, {"error", it->second.error}});
      continue;
    }
    all.push_back(&it->second);
    by_class[f.fold.cls].push_back(&it->second);
  }
  json out = summarize_folds(all);
  json classes = json::object();
  for (const auto& [cls, folds] : by_class) classes[cls] = summarize_folds(folds);
  out["classes"] = classes;
  // Macro average: every class counts once, however many folds it has (the
  // fold mean above is dominated by the classes with most subjects/trials).
  json macro = json::object();
  for (const auto& k : metric_keys()) {
    std::vector<double> v;
    for (const auto& [cls, c] : classes.items()) v.push_back(get(c, k.key));
    macro[k.key] = num(mean_sd(v).mean);
  }
  out["class_mean"] = macro;
  if (!failures.empty()) out["failed_folds"] = failures;
  return out;
}

// The document's published figures (CoolMoves, section 4.1.2).
json paper_figures() {
  json p;
  p["cross_subject"]["accent"] = {{"full_body_cm", 11.4}, {"full_body_cm_sd", 2.3}, {"left_hand_cm", 1.6},
                                  {"left_hand_cm_sd", 0.22}, {"right_hand_cm", 1.9}, {"right_hand_cm_sd", 0.27},
                                  {"left_hand_correlation", 0.92}, {"right_hand_correlation", 0.94},
                                  {"hand_correlation", 0.93}, {"frames_per_second", 152.0}};
  p["cross_subject"]["ik"] = {{"full_body_cm", 12.1}, {"full_body_cm_sd", 3.4}, {"left_hand_cm", 0.0},
                              {"right_hand_cm", 0.0}, {"hand_correlation", 1.0}};
  p["cross_trial"]["accent"] = {{"full_body_cm", 9.6}, {"full_body_cm_sd", 2.1}, {"left_hand_cm", 1.4},
                                {"left_hand_cm_sd", 0.18}, {"right_hand_cm", 1.7}, {"right_hand_cm_sd", 0.21}};
  p["ablation"] = {{"nn", 16.5}, {"nn_align", 13.2}, {"paper", 11.4}};
  p["lower_body_gain_over_ik_cm"] = 3.5;
  p["note"] = "CoolMoves (section 4.1.2, Figure 4): CMU boxing, basketball, climbing ladder, running, swimming; "
              "its own body-part figures other than hands and full body are only plotted, not printed";
  return p;
}

json target(const std::string& name, double value, const std::string& op, double goal, const std::string& note = "",
            const std::string& source = "document") {
  json t = {{"target", name}, {"value", num(value)}, {"goal", goal}, {"op", op}, {"source", source}};
  const bool defined = std::isfinite(value);
  t["met"] = defined ? json(op == "<=" ? value <= goal : value >= goal) : json(nullptr);
  if (!note.empty()) t["note"] = note;
  return t;
}
// A goal of issue 12 (see targets_of).
json goal(const std::string& name, double value, const std::string& op, double g, const std::string& note = "") {
  return target(name, value, op, g, note, "issue 12");
}
// A goal this run does not measure: not met (nothing shows it is).
json unmeasured(const std::string& name, double g, const std::string& op, const std::string& why) {
  json t = goal(name, kNaN, op, g, "not measured by this run: " + why);
  t["met"] = false;
  return t;
}

// Per class, the engine against the IK baseline on full and lower body (class
// means over folds): { "<class>": { "full_body": {"accent": x, "ik": y,
// "winner": "accent"|"ik"}, "lower_body": {...} } }, and the counts.
// `ik` names the baseline: "ik" (the database skeleton at the user's height,
// what the engine gets) or "ik_own" (the subject's own skeleton); `engine` the
// engine's setting: "accent" (the class given) or "no_class" (recognised), also
// the key of its error in each pair.
json class_winners(const json& pj, const char* ik = "ik", const char* engine = "accent") {
  json out = json::object();
  if (!pj.contains(engine) || !pj.contains(ik)) return out;
  int wins = 0, contests = 0;
  for (const auto& [cls, a] : pj[engine]["classes"].items()) {
    if (!pj[ik]["classes"].contains(cls)) continue;
    const json& i = pj[ik]["classes"][cls];
    for (const char* part : {"full_body", "lower_body"}) {
      const std::string key = std::string(part) + "_cm";
      const double va = get(a, key), vi = get(i, key);
      json w = {{engine, num(va)}, {"ik", num(vi)}, {"margin_cm", num(vi - va)}};
      w["winner"] = std::isfinite(va) && std::isfinite(vi) ? json(va < vi ? engine : "ik") : json(nullptr);
      if (std::isfinite(va) && std::isfinite(vi)) {
        ++contests;
        if (va < vi) ++wins;
      }
      out["classes"][cls][part] = w;
    }
  }
  out["engine_wins"] = wins;
  out["contests"] = contests;
  return out;
}

// The document's figures, then the goals of issue 12 (all from this run).
json targets_of(const json& r) {
  json t = json::array();
  auto method = [&](const char* p, const char* m) -> json {
    return r.contains(p) && r[p].contains(m) ? r[p][m] : json::object();
  };
  const json cs = method("cross_subject", "accent"), ct = method("cross_trial", "accent");
  const json cs_ik = method("cross_subject", "ik"), ct_ik = method("cross_trial", "ik");
  if (!cs.empty()) t.push_back(target("cross-subject full body <= 11.4 cm (document)", get(cs, "full_body_cm"), "<=", 11.4));
  if (!ct.empty()) t.push_back(target("cross-trial full body <= 9.6 cm (document)", get(ct, "full_body_cm"), "<=", 9.6));
  for (const auto& [name, m] : {std::pair{"cross-subject", cs}, std::pair{"cross-trial", ct}}) {
    if (m.empty()) continue;
    t.push_back(target(std::string(name) + " left hand <= 1.6 cm", get(m, "left_hand_cm"), "<=", 1.6));
    t.push_back(target(std::string(name) + " right hand <= 1.6 cm", get(m, "right_hand_cm"), "<=", 1.6));
    t.push_back(target(std::string(name) + " hand correlation >= 0.95", get(m, "hand_correlation"), ">=", 0.95));
  }
  if (!cs.empty() && !cs_ik.empty())
    t.push_back(target("cross-subject lower body >= 3.5 cm better than IK",
                       get(cs_ik, "lower_body_cm") - get(cs, "lower_body_cm"), ">=", 3.5,
                       "value = IK lower body - engine lower body (cm)"));
  if (!ct.empty() && !ct_ik.empty())
    t.push_back(target("cross-trial lower body >= 3.5 cm better than IK",
                       get(ct_ik, "lower_body_cm") - get(ct, "lower_body_cm"), ">=", 3.5,
                       "value = IK lower body - engine lower body (cm)"));
  // Issue 12.
  if (!cs.empty()) {
    t.push_back(goal("cross-subject full body <= 10.0 cm (fold mean)", get(cs, "full_body_cm"), "<=", 10.0));
    t.push_back(goal("cross-subject full body <= 11.0 cm (class mean)", get(cs["class_mean"], "full_body_cm"), "<=", 11.0));
  }
  if (!ct.empty()) t.push_back(goal("cross-trial full body <= 7.0 cm", get(ct, "full_body_cm"), "<=", 7.0));
  for (const char* p : {"cross_subject", "cross_trial"}) {
    if (!r.contains(p) || !r[p].contains("winners") || !r[p]["winners"].contains("contests")) continue;
    const json& w = r[p]["winners"];
    t.push_back(goal(std::string(p) + ": engine below IK in every class, full and lower body",
                     w["engine_wins"].get<double>(), ">=", w["contests"].get<double>(),
                     "value = (class, part) pairs the engine wins, goal = all pairs"));
  }
  if (!cs.empty() && !cs_ik.empty())
    t.push_back(goal("cross-subject lower body >= 4 cm better than IK", get(cs_ik, "lower_body_cm") - get(cs, "lower_body_cm"),
                     ">=", 4.0, "value = IK lower body - engine lower body (cm)"));
  for (const auto& [p, m] : {std::pair{"cross-subject", cs}, std::pair{"cross-trial", ct}}) {
    if (m.empty()) continue;
    t.push_back(goal(std::string(p) + " foot skating <= 1.5x the capture's",
                     get(m, "foot_skating_cm") / get(m, "foot_skating_truth_cm"), "<=", 1.5,
                     "value = engine foot skating / ground truth's (fold means)"));
    t.push_back(goal(std::string(p) + " jitter <= 1.2x the capture's", get(m, "jitter") / get(m, "jitter_truth"), "<=", 1.2,
                     "value = engine jitter / ground truth's (fold means)"));
    t.push_back(goal(std::string(p) + " hands <= 1.0 cm from the controllers",
                     std::max(get(m, "left_hand_cm"), get(m, "right_hand_cm")), "<=", 1.0, "value = the worse hand"));
    t.push_back(goal(std::string(p) + " hand correlation >= 0.98", get(m, "hand_correlation"), ">=", 0.98));
  }
  bool no_class = false;
  for (const char* p : {"cross_subject", "cross_trial"}) {
    const json nc = method(p, "no_class"), pc = method(p, "accent");
    if (nc.empty() || pc.empty()) continue;
    no_class = true;
    t.push_back(goal(std::string(p) + ": no-class setting within 1 cm of the per-class one",
                     get(nc, "full_body_cm") - get(pc, "full_body_cm"), "<=", 1.0,
                     "value = no-class full body - per-class full body (cm, fold means)"));
    if (r[p].contains("winners_no_class") && r[p]["winners_no_class"].contains("contests")) {
      const json& w = r[p]["winners_no_class"];
      t.push_back(goal(std::string(p) + ": no-class setting below IK in every class, full and lower body",
                       w["engine_wins"].get<double>(), ">=", w["contests"].get<double>(),
                       "value = (class, part) pairs the no-class setting wins, goal = all pairs; per class below "
                       "(\"No class given\")"));
    }
  }
  if (!no_class)
    t.push_back(unmeasured("no-class setting within 1 cm of the per-class one", 1.0, "<=", "not run (--skip-no-class)"));
  const json speed = r["meta"].contains("speed") ? r["meta"]["speed"] : json::object();
  const double fps = get(speed, "accent_frames_per_second"), p99 = get(speed, "accent_p99_us");
  if (std::isfinite(fps)) {
    t.push_back(target("engine >= 130x the document's 152 Hz", fps / 152.0, ">=", 130.0));
    t.push_back(goal("engine >= 20,000 frames/s (per-frame update, one core)", fps, ">=", 20000.0,
                     "speed pass of this run (meta.speed)"));
    t.push_back(goal("engine p99 <= 150 us per frame", p99, "<=", 150.0, "speed pass of this run (meta.speed)"));
  }
  if (std::isfinite(get(speed, "fast_recall"))) {
    t.push_back(goal("fast-search recall >= 0.95", get(speed, "fast_recall"), ">=", 0.95,
                     "speed pass: the engine's k, eps, budget and seeds (previous frame's results) vs brute force, per-class "
                     "database; without seeds: meta.speed.fast_recall_unseeded"));
    t.push_back(goal("database load with its search index <= 5 ms", get(speed, "load_ms"), "<=", 5.0,
                     "speed pass: the per-class database saved and loaded (checksum verified), best of 5"));
  }
  if (std::isfinite(get(speed, "no_class_frames_per_second"))) {
    t.push_back(goal("no-class: engine >= 20,000 frames/s (one core)", get(speed, "no_class_frames_per_second"), ">=",
                     20000.0, "speed pass, database of every class"));
    t.push_back(goal("no-class: engine p99 <= 150 us per frame", get(speed, "no_class_p99_us"), "<=", 150.0,
                     "speed pass, database of every class"));
    t.push_back(goal("no-class: fast-search recall >= 0.95", get(speed, "no_class_fast_recall"), ">=", 0.95,
                     "speed pass, within the trial's class of the database of every class"));
    t.push_back(goal("no-class: database load with its search index <= 5 ms", get(speed, "no_class_load_ms"), "<=", 5.0,
                     "speed pass, database of every class (checksum verified), best of 5"));
  }
  return t;
}

std::string fmt(double v, int decimals = 1) {
  if (!std::isfinite(v)) return "n/a";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}
std::string fmt_sd(const json& m, const std::string& key, int decimals = 1) {
  const double v = get(m, key), sd = get(m, key + "_sd");
  if (!std::isfinite(v)) return "n/a";
  return fmt(v, decimals) + " (" + fmt(sd, decimals) + ")";
}
std::string paper_cell(const json& paper, const std::string& key, int decimals = 1) {
  if (!paper.contains(key)) return "–";
  const double v = paper[key].get<double>();
  std::string s = fmt(v, decimals);
  if (paper.contains(key + "_sd")) {
    char sd[32];
    std::snprintf(sd, sizeof sd, "%.2g", paper[key + "_sd"].get<double>());  // as printed: 2.3, 0.22
    s += std::string(" (") + sd + ")";
  }
  return s;
}

const std::vector<std::string> kProtocols{"cross_subject", "cross_trial", "cross_dataset"};

// Figures for charts: value of a metric for protocol/method (NaN if absent).
double value_of(const json& r, const std::string& protocol, const std::string& method, const std::string& key) {
  if (!r.contains(protocol) || !r[protocol].contains(method)) return kNaN;
  return get(r[protocol][method], key);
}

// Calls row(protocol, method, results, document's figures) for each protocol
// and main method (accent engine, IK baseline) the report holds, in table order.
// "accent engine", "IK baseline" (database skeleton at the user's height), "IK, own skeleton".
std::string method_label(const std::string& m) {
  return m == "ik" ? "IK baseline" : m == "ik_own" ? "IK baseline, subject's own skeleton" : "accent engine";
}

template <class Row>
void for_each_method(const json& r, Row&& row) {
  const json& paper = r["paper"];
  for (const auto& p : kProtocols) {
    if (!r.contains(p)) continue;
    for (const char* m : {"accent", "ik", "ik_own"}) {
      if (!r[p].contains(m)) continue;
      const json pp = paper.contains(p) && paper[p].contains(m) ? paper[p][m] : json::object();
      row(p, std::string(m), r[p][m], pp);
    }
  }
}

}  // namespace

const std::vector<MetricKey>& metric_keys() {
  static const std::vector<MetricKey> keys{
      {"full_body_cm", "full body", "cm"},
      {"upper_body_cm", "upper body", "cm"},
      {"lower_body_cm", "lower body", "cm"},
      {"left_hand_cm", "left hand", "cm"},
      {"right_hand_cm", "right hand", "cm"},
      {"mpjpe_cm", "MPJPE", "cm"},
      {"mpjve_cm_s", "MPJVE", "cm/s"},
      {"jitter", "jitter", "10^2 m/s^3"},
      {"jitter_truth", "jitter of the ground truth", "10^2 m/s^3"},
      {"hand_correlation", "hand correlation", ""},
      {"left_hand_correlation", "left hand correlation", ""},
      {"right_hand_correlation", "right hand correlation", ""},
      {"foot_skating_cm", "foot skating", "cm/frame"},
      {"foot_skating_truth_cm", "foot skating of the ground truth", "cm/frame"},
  };
  return keys;
}

double metric_value(const TrialMetrics& m, const std::string& key) {
  auto part = [&](Part p) { return m.part_cm[static_cast<std::size_t>(p)]; };
  if (key == "full_body_cm") return part(Part::FullBody);
  if (key == "upper_body_cm") return part(Part::UpperBody);
  if (key == "lower_body_cm") return part(Part::LowerBody);
  if (key == "left_hand_cm") return part(Part::LeftHand);
  if (key == "right_hand_cm") return part(Part::RightHand);
  if (key == "mpjpe_cm") return m.mpjpe_cm;
  if (key == "mpjve_cm_s") return m.mpjve_cm_s;
  if (key == "jitter") return m.jitter;
  if (key == "jitter_truth") return m.jitter_truth;
  if (key == "left_hand_correlation") return m.hand_correlation[0];
  if (key == "right_hand_correlation") return m.hand_correlation[1];
  if (key == "hand_correlation") {
    const double l = m.hand_correlation[0], r = m.hand_correlation[1];
    if (std::isfinite(l) && std::isfinite(r)) return 0.5 * (l + r);
    return std::isfinite(l) ? l : r;
  }
  if (key == "foot_skating_cm") return m.foot_skating_cm;
  if (key == "foot_skating_truth_cm") return m.foot_skating_truth_cm;
  throw Error("unknown metric key '" + key + "'");
}

// One protocol's part of report.json: folds, method summaries, ablation, winners.
static json protocol_json(const EvalResult& r, const ProtocolResult& p) {
  json pj;
  pj["folds"] = p.folds.size();
  json skipped = json::object();
  for (const auto& [cls, why] : p.plan.skipped) skipped[cls] = why;
  pj["skipped_classes"] = skipped;
  json folds = json::array();
  for (const auto& f : p.folds) {
    json fj = {{"class", f.fold.cls}, {"held_out", f.fold.held_out}, {"test", f.test_ids},
               {"database_trials", f.fold.database.size()}};
    for (const auto& [m, mf] : f.methods) {
      if (!mf.ok) {
        fj[m] = {{"error", mf.error}};
        continue;
      }
      json mj = {{"frames", mf.frames}, {"database_windows", mf.database_windows}};
      for (const auto& k : metric_keys()) mj[k.key] = num(metric_value(mf.metrics, k.key));
      fj[m] = mj;
    }
    folds.push_back(fj);
  }
  for (const auto& m : p.methods) {
    const bool main_method = m == "accent" || m == "ik" || m == "ik_own" || m == "no_class";
    json s = summarize_method(p, m);
    if (main_method) pj[m] = s;
    const bool baseline = m == "ik" || m == "ik_own" || m == "no_class";
    if (!baseline && r.variants.size() > 1 && p.protocol == Protocol::CrossSubject) pj["ablation"][m] = s;
  }
  pj["winners"] = class_winners(pj);
  pj["winners_own_skeleton"] = class_winners(pj, "ik_own");
  if (pj.contains("no_class")) pj["winners_no_class"] = class_winners(pj, "ik", "no_class");
  pj["fold_results"] = folds;
  return pj;
}

json report_json(const EvalResult& r) {
  json out;
  json meta;
  meta["data"] = r.data.root;
  meta["trials"] = r.data.trials;
  meta["trials_per_class"] = r.data.trials_per_class;
  meta["subjects_per_class"] = r.data.subjects_per_class;
  meta["dropped_by_correlation_filter"] = r.data.dropped;
  meta["seconds"] = r.seconds;
  meta["threads"] = r.threads;
  json variants = json::array();
  for (const auto& v : r.variants) {
    variants.push_back({{"key", v.key},
                        {"label", v.label},
                        {"hop", v.build.hop},
                        {"speed_variants", v.build.speed_variants},
                        {"speed_range", v.build.speed_range},
                        {"mirror", v.build.mirror},
                        {"correlation_threshold", v.build.correlation_threshold},
                        {"k_left", v.config.k_left},
                        {"k_right", v.config.k_right},
                        {"threshold", v.config.threshold},
                        {"align", v.config.align},
                        {"smooth", v.config.smooth},
                        {"smooth_halflife", v.config.smooth_halflife},
                        {"smooth_feedforward", v.config.smooth_feedforward},
                        {"lying_root_smoothing", v.config.lying_root_smoothing},
                        {"lying_crown", v.config.lying_crown},
                        {"other_class_cost", v.config.other_class_cost},
                        {"foot_lock", v.config.foot_lock},
                        {"foot_lock_follow_seconds", v.config.foot_lock_follow_seconds},
                        {"foot_lift_height", v.config.foot_lift_height},
                        {"foot_lock_slack", v.config.foot_lock_slack},
                        {"foot_lock_hold_seconds", v.config.foot_lock_hold_seconds},
                        {"foot_swing_speed", v.config.foot_swing_speed},
                        {"floor", v.config.floor},
                        {"floor_height", v.config.floor_height},
                        {"travel_weight", v.config.travel_weight},
                        {"max_head_height_diff", v.config.max_head_height_diff},
                        {"ik_blend_min", v.config.ik_blend_min},
                        {"ik_blend_max", v.config.ik_blend_max},
                        {"search", v.config.search == accent::SearchMode::Fast    ? "fast"
                                   : v.config.search == accent::SearchMode::Exact ? "exact"
                                                                                  : "brute_force"}});
  }
  meta["variants"] = variants;
  meta["speed"] = {{"trial", r.speed.trial},
                   {"fold", r.speed.fold},
                   {"frames", r.speed.frames},
                   {"database_windows", r.speed.database_windows},
                   {"accent_frames_per_second", num(r.speed.accent_frames_per_second)},
                   {"ik_frames_per_second", num(r.speed.ik_frames_per_second)},
                   {"accent_p99_us", num(r.speed.accent_p99_us)},
                   {"accent_cpu_frames_per_second", num(r.speed.accent_cpu_frames_per_second)},
                   {"fast_recall", num(r.speed.fast_recall)},
                   {"fast_recall_unseeded", num(r.speed.fast_recall_unseeded)},
                   {"load_ms", num(r.speed.load_ms)},
                   {"load_ms_unverified", num(r.speed.load_ms_unverified)},
                   {"database_bytes", r.speed.database_bytes},
                   {"no_class_windows", r.speed.no_class_windows},
                   {"no_class_frames_per_second", num(r.speed.no_class_windows ? r.speed.no_class_frames_per_second : kNaN)},
                   {"no_class_cpu_frames_per_second", num(r.speed.no_class_windows ? r.speed.no_class_cpu_frames_per_second : kNaN)},
                   {"no_class_p99_us", num(r.speed.no_class_windows ? r.speed.no_class_p99_us : kNaN)},
                   {"no_class_fast_recall", num(r.speed.no_class_windows ? r.speed.no_class_fast_recall : kNaN)},
                   {"no_class_fast_recall_unseeded", num(r.speed.no_class_windows ? r.speed.no_class_fast_recall_unseeded : kNaN)},
                   {"no_class_load_ms", num(r.speed.no_class_windows ? r.speed.no_class_load_ms : kNaN)},
                   {"no_class_load_ms_unverified", num(r.speed.no_class_windows ? r.speed.no_class_load_ms_unverified : kNaN)},
                   {"no_class_database_bytes", r.speed.no_class_database_bytes},
                   {"note", "single-threaded pass after the folds, best of 3, per-frame solver time only; the "
                            "per-protocol frames_per_second figures were measured while the folds ran in parallel"}};
  json units = json::object();
  for (const auto& k : metric_keys()) units[k.key] = k.unit;
  meta["units"] = units;
  meta["definitions"] =
      "errors: mean Euclidean distance over role joints and frames per fold (upper body = head, neck, spine, "
      "clavicles, arms; lower body = pelvis, legs, feet); mean and SD across folds. MPJVE: central-difference "
      "velocities. jitter: mean jerk magnitude of the output (10^2 m/s^3, as AvatarPoser/AGRoL). hand correlation: "
      "Pearson r of input vs output hand positions relative to the input head, per axis, averaged over x, y, z. "
      "foot skating: mean horizontal slide per frame (90 Hz) of an ankle or toe staying within 3 cm of its floor "
      "level. frames_per_second: per-frame solver time only. IK baseline (method ik): the VRIK-style full-body IK "
      "on the database's reference skeleton scaled to the user's standing height, the information the engine gets; "
      "ik_own: the same IK on the held-out subject's own skeleton (true bone lengths; the baseline of reports before "
      "this change). Wins and the 'better than IK' goals are against ik.";
  out["meta"] = meta;
  out["paper"] = paper_figures();

  for (const auto& p : r.protocols) out[protocol_key(p.protocol)] = protocol_json(r, p);
  out["targets"] = targets_of(out);
  return out;
}

namespace {

// Per body part (the document's Figure 4 A), over folds and over classes.
void md_body_parts(std::ostringstream& md, const json& r) {
  // Headline: per protocol and method, body parts.
  md << "## Per body part (document's Figure 4 A)\n\n";
  md << "| protocol | method | left hand | right hand | upper body | lower body | full body | doc. full body | "
        "doc. hands (L/R) |\n|---|---|---|---|---|---|---|---|---|\n";
  for_each_method(r, [&](const std::string& p, const std::string& m, const json& x, const json& pp) {
    md << "| " << p << " | " << method_label(m) << " | " << fmt_sd(x, "left_hand_cm")
       << " | " << fmt_sd(x, "right_hand_cm") << " | " << fmt_sd(x, "upper_body_cm") << " | "
       << fmt_sd(x, "lower_body_cm") << " | **" << fmt_sd(x, "full_body_cm") << "** | " << paper_cell(pp, "full_body_cm")
       << " | " << paper_cell(pp, "left_hand_cm") << " / " << paper_cell(pp, "right_hand_cm") << " |\n";
  });
  md << "\nAveraged over classes instead (each class once, whatever its number of folds):\n\n"
        "| protocol | method | left hand | right hand | upper body | lower body | full body |\n|---|---|---|---|---|---|---|\n";
  for_each_method(r, [&](const std::string& p, const std::string& m, const json& results, const json&) {
    if (!results.contains("class_mean")) return;
    const json& x = results["class_mean"];
    md << "| " << p << " | " << m << " | " << fmt(get(x, "left_hand_cm")) << " | " << fmt(get(x, "right_hand_cm"))
       << " | " << fmt(get(x, "upper_body_cm")) << " | " << fmt(get(x, "lower_body_cm")) << " | "
       << fmt(get(x, "full_body_cm")) << " |\n";
  });
}

// Motion quality and speed per protocol and method.
void md_quality(std::ostringstream& md, const json& r) {
  md << "\n## Motion quality and speed\n\n";
  md << "| protocol | method | MPJVE (cm/s) | jitter (10² m/s³) | jitter of truth | hand corr. (L/R) | doc. hand corr. "
        "| foot skating (cm/frame) | truth skating | frames/s | doc. frames/s |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
  for_each_method(r, [&](const std::string& p, const std::string& m, const json& x, const json& pp) {
    md << "| " << p << " | " << m << " | " << fmt_sd(x, "mpjve_cm_s") << " | " << fmt(get(x, "jitter"), 2) << " | "
       << fmt(get(x, "jitter_truth"), 2) << " | " << fmt(get(x, "left_hand_correlation"), 3) << " / "
       << fmt(get(x, "right_hand_correlation"), 3) << " | "
       << (pp.contains("left_hand_correlation")
               ? fmt(pp["left_hand_correlation"].get<double>(), 2) + " / " + fmt(pp["right_hand_correlation"].get<double>(), 2)
               : (pp.contains("hand_correlation") ? fmt(pp["hand_correlation"].get<double>(), 2) : "–"))
       << " | " << fmt(get(x, "foot_skating_cm"), 2) << " | " << fmt(get(x, "foot_skating_truth_cm"), 2) << " | "
       << fmt(get(x, "frames_per_second"), 0) << " | " << paper_cell(pp, "frames_per_second", 0) << " |\n";
  });
}

// "accent" / "IK" / "n/a" for a class's winner on one part.
std::string winner_cell(const json& pj, const std::string& cls, const char* part) {
  if (!pj.contains("winners") || !pj["winners"].contains("classes") || !pj["winners"]["classes"].contains(cls)) return "n/a";
  const json& w = pj["winners"]["classes"][cls][part]["winner"];
  return w.is_null() ? "n/a" : (w.get<std::string>() == "accent" ? "**accent**" : "IK");
}

// Per protocol: per class (errors, winner, skating and jitter beside the
// truth's), and the classes left out.
void md_per_class(std::ostringstream& md, const json& r) {
  for (const auto& p : kProtocols) {
    if (!r.contains(p)) continue;
    const json& pj = r[p];
    md << "\n## " << p << ": per class (full body / lower body, cm; winner = lower error)\n\n";
    md << "| class | folds | accent full | IK full | winner full | accent lower | IK lower | winner lower | "
          "skating accent / IK / truth (cm/frame) | jitter accent / IK / truth | accent hands L/R | hand corr. | "
          "IK on the subject's own skeleton: full / lower |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    std::set<std::string> classes;
    for (const char* m : {"accent", "ik"})
      if (pj.contains(m))
        for (const auto& [c, v] : pj[m]["classes"].items()) classes.insert(c);
    for (const auto& c : classes) {
      auto cls = [&](const char* m) -> json {
        return pj.contains(m) && pj[m]["classes"].contains(c) ? pj[m]["classes"][c] : json::object();
      };
      const json a = cls("accent"), i = cls("ik"), own = cls("ik_own");
      md << "| " << c << " | " << (a.contains("folds") ? a["folds"].dump() : i.value("folds", json(0)).dump()) << " | "
         << fmt_sd(a, "full_body_cm") << " | " << fmt_sd(i, "full_body_cm") << " | " << winner_cell(pj, c, "full_body")
         << " | " << fmt_sd(a, "lower_body_cm") << " | " << fmt_sd(i, "lower_body_cm") << " | "
         << winner_cell(pj, c, "lower_body") << " | " << fmt(get(a, "foot_skating_cm"), 2) << " / "
         << fmt(get(i, "foot_skating_cm"), 2) << " / " << fmt(get(a, "foot_skating_truth_cm"), 2) << " | "
         << fmt(get(a, "jitter"), 1) << " / " << fmt(get(i, "jitter"), 1) << " / " << fmt(get(a, "jitter_truth"), 1)
         << " | " << fmt(get(a, "left_hand_cm"), 2) << " / " << fmt(get(a, "right_hand_cm"), 2) << " | "
         << fmt(get(a, "hand_correlation"), 3) << " | " << fmt(get(own, "full_body_cm")) << " / "
         << fmt(get(own, "lower_body_cm")) << " |\n";
    }
    if (pj.contains("winners") && pj["winners"].contains("contests"))
      md << "\nThe engine is below the IK baseline in " << pj["winners"]["engine_wins"] << " of "
         << pj["winners"]["contests"] << " (class, part) pairs.\n";
    if (pj.contains("winners_own_skeleton") && pj["winners_own_skeleton"].contains("contests"))
      md << "Against the IK baseline on the subject's own skeleton (true bone lengths, which the engine is not "
            "given): "
         << pj["winners_own_skeleton"]["engine_wins"] << " of " << pj["winners_own_skeleton"]["contests"] << ".\n";
    md << "\nThe document gives its per-class figures (Figure 4 B) only as a plot, without numbers.\n";
    if (!pj["skipped_classes"].empty()) {
      md << "\nNot evaluated under " << p << ":\n";
      for (const auto& [c, why] : pj["skipped_classes"].items()) md << "- " << c << ": " << why.get<std::string>() << "\n";
    }
  }
}

// Speed pass details: CPU time, recall, load, and the no-class setting.
void md_speed_details(std::ostringstream& md, const json& sp) {
  md << "\n| setting | windows | frames/s (wall) | frames/s (thread CPU) | p99 (us) | fast recall (seeded / no seeds) | "
        "load, checksum (ms) | load, no checksum (ms) | file (MB) |\n|---|---|---|---|---|---|---|---|---|\n";
  md << "| per class | " << sp["database_windows"] << " | " << fmt(get(sp, "accent_frames_per_second"), 0) << " | "
     << fmt(get(sp, "accent_cpu_frames_per_second"), 0) << " | " << fmt(get(sp, "accent_p99_us"), 0) << " | "
     << fmt(get(sp, "fast_recall"), 3) << " / " << fmt(get(sp, "fast_recall_unseeded"), 3) << " | " << fmt(get(sp, "load_ms"), 2) << " | " << fmt(get(sp, "load_ms_unverified"), 2)
     << " | " << fmt(get(sp, "database_bytes") / 1e6, 1) << " |\n";
  if (std::isfinite(get(sp, "no_class_frames_per_second")))
    md << "| no class given | " << sp["no_class_windows"] << " | " << fmt(get(sp, "no_class_frames_per_second"), 0) << " | "
       << fmt(get(sp, "no_class_cpu_frames_per_second"), 0) << " | " << fmt(get(sp, "no_class_p99_us"), 0) << " | "
       << fmt(get(sp, "no_class_fast_recall"), 3) << " / " << fmt(get(sp, "no_class_fast_recall_unseeded"), 3) << " | "
       << fmt(get(sp, "no_class_load_ms"), 2) << " | "
       << fmt(get(sp, "no_class_load_ms_unverified"), 2) << " | " << fmt(get(sp, "no_class_database_bytes") / 1e6, 1) << " |\n";
}

// The no-class setting beside the per-class one.
void md_no_class(std::ostringstream& md, const json& r) {
  bool any = false;
  for (const char* p : {"cross_subject", "cross_trial"}) any = any || (r.contains(p) && r[p].contains("no_class"));
  if (!any) return;
  md << "\n## No class given (one database of every class, the class recognised from the input)\n\n"
        "The held-out subject (cross-subject) or trial (cross-trial) is left out of every class of the fold's database.\n\n"
        "| protocol | per class: full / lower (cm) | no class: full / lower (cm) | difference (cm) | IK: full / lower (cm) | "
        "winner full / lower | class accuracy | class switches per minute |\n|---|---|---|---|---|---|---|---|\n";
  for (const char* p : {"cross_subject", "cross_trial"}) {
    if (!r.contains(p) || !r[p].contains("no_class") || !r[p].contains("accent")) continue;
    const json &a = r[p]["accent"], &n = r[p]["no_class"];
    const json ik = r[p].contains("ik") ? r[p]["ik"] : json::object();
    const json w = r[p].contains("winners_no_class") ? r[p]["winners_no_class"] : json::object();
    auto winner = [&](const std::string& cls, const char* part) -> std::string {
      if (!w.contains("classes") || !w["classes"].contains(cls) || w["classes"][cls][part]["winner"].is_null()) return "n/a";
      return w["classes"][cls][part]["winner"].get<std::string>() == "no_class" ? "**no class**" : "IK";
    };
    md << "| " << p << " | " << fmt(get(a, "full_body_cm"), 2) << " / " << fmt(get(a, "lower_body_cm"), 2) << " | "
       << fmt(get(n, "full_body_cm"), 2) << " / " << fmt(get(n, "lower_body_cm"), 2) << " | "
       << fmt(get(n, "full_body_cm") - get(a, "full_body_cm"), 2) << " | " << fmt(get(ik, "full_body_cm"), 2) << " / "
       << fmt(get(ik, "lower_body_cm"), 2) << " | – | " << fmt(get(n, "class_accuracy"), 3) << " | "
       << fmt(get(n, "class_switches_per_minute"), 2) << " |\n";
    for (const auto& [cls, x] : n["classes"].items()) {
      const json ic = ik.contains("classes") && ik["classes"].contains(cls) ? ik["classes"][cls] : json::object();
      md << "| " << p << " " << cls << " | " << fmt(get(a["classes"][cls], "full_body_cm"), 2) << " / "
         << fmt(get(a["classes"][cls], "lower_body_cm"), 2) << " | " << fmt(get(x, "full_body_cm"), 2) << " / "
         << fmt(get(x, "lower_body_cm"), 2) << " | " << fmt(get(x, "full_body_cm") - get(a["classes"][cls], "full_body_cm"), 2)
         << " | " << fmt(get(ic, "full_body_cm"), 2) << " / " << fmt(get(ic, "lower_body_cm"), 2) << " | "
         << winner(cls, "full_body") << " / " << winner(cls, "lower_body") << " | " << fmt(get(x, "class_accuracy"), 3)
         << " | " << fmt(get(x, "class_switches_per_minute"), 2) << " |\n";
    }
  }
  for (const char* p : {"cross_subject", "cross_trial"})
    if (r.contains(p) && r[p].contains("winners_no_class") && r[p]["winners_no_class"].contains("contests"))
      md << "\n" << p << ": with no class given the engine is below the IK baseline in "
         << r[p]["winners_no_class"]["engine_wins"] << " of " << r[p]["winners_no_class"]["contests"]
         << " (class, part) pairs (the class given: " << r[p]["winners"].value("engine_wins", json(0)) << " of "
         << r[p]["winners"].value("contests", json(0)) << ").\n";
}

// The cross-subject ablation beside the document's figures.
void md_ablation(std::ostringstream& md, const json& r) {
  const json& paper = r["paper"];
  const json& meta = r["meta"];
  // Ablation.
  if (r.contains("cross_subject") && r["cross_subject"].contains("ablation")) {
    md << "\n## Ablation (cross-subject, full body cm)\n\n| variant | full body | lower body | hands L/R | MPJVE | "
          "jitter | hand corr. | doc. |\n|---|---|---|---|---|---|---|---|\n";
    const json& ab = r["cross_subject"]["ablation"];
    std::vector<std::string> order{"nn", "nn_align", "paper", "spring", "spring_k", "accent"};
    for (const auto& [k, v] : ab.items())
      if (std::find(order.begin(), order.end(), k) == order.end()) order.push_back(k);
    std::map<std::string, std::string> labels;
    for (const auto& v : meta["variants"]) labels[v["key"].get<std::string>()] = v["label"].get<std::string>();
    for (const auto& k : order) {
      if (!ab.contains(k)) continue;
      const json& x = ab[k];
      md << "| " << k << " (" << labels[k] << ") | " << fmt_sd(x, "full_body_cm") << " | " << fmt(get(x, "lower_body_cm"))
         << " | " << fmt(get(x, "left_hand_cm"), 2) << " / " << fmt(get(x, "right_hand_cm"), 2) << " | "
         << fmt(get(x, "mpjve_cm_s")) << " | " << fmt(get(x, "jitter"), 2) << " | " << fmt(get(x, "hand_correlation"), 3)
         << " | " << (paper["ablation"].contains(k) ? fmt(paper["ablation"][k].get<double>()) : "–") << " |\n";
    }
  }
}

// The speed pass, the targets, the IK baseline against the document's, dropped trials.
void md_speed_and_targets(std::ostringstream& md, const json& r) {
  const json& meta = r["meta"];
  if (meta.contains("speed") && meta["speed"]["frames"].get<int>() > 0) {
    const json& sp = meta["speed"];
    md << "\n## Speed (measured in this run)\n\nSingle-threaded pass after the folds on held-out trial "
       << sp["trial"].get<std::string>() << " (" << sp["fold"].get<std::string>() << ", " << sp["frames"]
       << " frames at 90 Hz, database of " << sp["database_windows"] << " windows), best of 3, solver time only: "
       << "engine **" << fmt(get(sp, "accent_frames_per_second"), 0) << " frames/s** ("
       << fmt(get(sp, "accent_frames_per_second") / 152.0, 0) << "x the document's 152 Hz), IK baseline "
       << fmt(get(sp, "ik_frames_per_second"), 0) << " frames/s. The machine is shared, so expect noise.\n";
    md_speed_details(md, sp);
  }
  md << "\n## Targets (computed from this run)\n\n| source | target | value | met | note |\n|---|---|---|---|---|\n";
  for (const auto& t : r["targets"]) {
    const std::string met = t["met"].is_null() ? "n/a" : (t["met"].get<bool>() ? "**met**" : "not met");
    const double v = t["value"].is_null() ? kNaN : t["value"].get<double>();
    md << "| " << t.value("source", "") << " | " << t["target"].get<std::string>() << " | " << fmt(v, v > 100 ? 0 : 2)
       << " | " << met << " | " << t.value("note", "") << " |\n";
  }
  if (r.contains("cross_subject") && r["cross_subject"].contains("ik")) {
    const double ik = get(r["cross_subject"]["ik"], "full_body_cm");
    const double ik_macro = get(r["cross_subject"]["ik"]["class_mean"], "full_body_cm");
    md << "\nIK baseline against the document's (Final IK VRIK, 12.1 cm cross-subject): ours " << fmt(ik)
       << " cm over folds (" << fmt(ik - 12.1) << " cm), " << fmt(ik_macro) << " cm averaged over classes.\n";
  }
  if (!meta["dropped_by_correlation_filter"].empty()) {
    md << "\nTrials the engine's hand-foot correlation filter keeps out of every database (they are still tested):\n";
    for (const auto& [t, why] : meta["dropped_by_correlation_filter"].items())
      md << "- " << t << ": " << why.get<std::string>() << "\n";
  }
}

}  // namespace

std::string report_markdown(const json& r) {
  std::ostringstream md;
  const json& meta = r["meta"];
  md << "# Accentuation evaluation (CoolMoves section 4.1 protocol)\n\n";
  md << "Data: `" << meta["data"].get<std::string>() << "`, " << meta["trials"] << " trials; run took "
     << fmt(meta["seconds"].get<double>(), 0) << " s on " << meta["threads"] << " threads.\n\n";
  md << "Every figure below comes from this run's report.json; the document's published figures are printed "
        "beside ours (\"doc.\"). Errors in cm, mean (SD across folds).\n\n";

  md_body_parts(md, r);
  md_quality(md, r);
  md_per_class(md, r);
  md_no_class(md, r);
  md_ablation(md, r);
  md_speed_and_targets(md, r);
  md << "\nDefinitions: " << meta["definitions"].get<std::string>() << "\n";
  return md.str();
}

namespace {

// An empty bar chart in cm, values with one decimal, 1000 pixels wide.
render::BarChart cm_chart(const std::string& title) {
  render::BarChart c;
  c.title = title;
  c.y_label = "cm";
  c.width = 1000;
  c.value_decimals = 1;
  return c;
}

// Series colours of the evaluation charts: a hue per method (accent teal, IK
// purple; never the body's left blue / right orange), darker for
// cross-subject than cross-trial, greyed for the document's figures.
render::Rgb method_color(const std::string& method, const std::string& protocol, bool document) {
  const bool ik = method == "ik";
  const bool subject = protocol == "cross_subject";
  render::Rgb c = ik ? (subject ? render::Rgb{0.42, 0.24, 0.60} : render::Rgb{0.68, 0.56, 0.82})
                     : (subject ? render::Rgb{0.00, 0.47, 0.50} : render::Rgb{0.40, 0.74, 0.76});
  if (protocol == "cross_dataset") c = ik ? render::Rgb{0.82, 0.76, 0.90} : render::Rgb{0.68, 0.88, 0.88};
  if (document)
    for (double& x : c) x = 0.45 * x + 0.55 * 0.62;  // towards grey
  return c;
}

// "accent engine, cross-subject" for a method and protocol key.
std::string series_name(const std::string& method, const std::string& protocol) {
  std::string p = protocol;
  std::replace(p.begin(), p.end(), '_', '-');
  return std::string(method == "ik" ? "IK baseline" : "accent engine") + ", " + p;
}

// An engine or IK bar series of one protocol, named and coloured as everywhere in the report.
render::BarSeries method_series(const std::string& method, const std::string& protocol) {
  render::BarSeries s;
  s.name = series_name(method, protocol);
  s.color = method_color(method, protocol, false);
  return s;
}

// Figure 4 A: per body part, this run's methods beside the document's figures.
render::BarChart body_parts_chart(const json& r) {
  render::BarChart c = cm_chart("Mean joint error per body part (cm)");
  const std::vector<std::pair<std::string, std::string>> parts{{"left_hand_cm", "left hand"},
                                                               {"right_hand_cm", "right hand"},
                                                               {"upper_body_cm", "upper body"},
                                                               {"lower_body_cm", "lower body"},
                                                               {"full_body_cm", "full body"}};
  for (const auto& [k, label] : parts) c.groups.push_back(label);
  for (const auto& p : kProtocols)
    for (const char* m : {"accent", "ik"}) {
      if (!r.contains(p) || !r[p].contains(m)) continue;
      render::BarSeries s = method_series(m, p);
      for (const auto& [k, label] : parts) s.values.push_back(value_of(r, p, m, k));
      c.series.push_back(s);
    }
  for (const auto& [p, m, name] : {std::tuple{"cross_subject", "accent", "document: accent, cross-subject"},
                                   std::tuple{"cross_trial", "accent", "document: accent, cross-trial"},
                                   std::tuple{"cross_subject", "ik", "document: IK baseline"}}) {
    render::BarSeries s;
    s.name = name;
    s.color = method_color(m, p, true);
    const json& pp = r["paper"][p][m];
    for (const auto& [k, label] : parts) s.values.push_back(pp.contains(k) ? pp[k].get<double>() : kNaN);
    c.series.push_back(s);
  }
  return c;
}

// Full-body error per class.
render::BarChart classes_chart(const json& r) {
  render::BarChart c = cm_chart("Full-body error per class (cm)");
  std::set<std::string> classes;
  for (const auto& p : kProtocols)
    for (const char* m : {"accent", "ik"})
      if (r.contains(p) && r[p].contains(m))
        for (const auto& [cls, v] : r[p][m]["classes"].items()) classes.insert(cls);
  c.groups.assign(classes.begin(), classes.end());
  for (const auto& p : kProtocols)
    for (const char* m : {"accent", "ik"}) {
      if (!r.contains(p) || !r[p].contains(m)) continue;
      render::BarSeries s = method_series(m, p);
      for (const auto& cls : c.groups) {
        const json& cj = r[p][m]["classes"];
        s.values.push_back(cj.contains(cls) ? get(cj[cls], "full_body_cm") : kNaN);
      }
      c.series.push_back(s);
    }
  return c;
}

// Cross-subject ablation, this run beside the document.
render::BarChart ablation_chart(const json& r) {
  render::BarChart c = cm_chart("Ablation, cross-subject full-body error (cm)");
  const json& ab = r["cross_subject"]["ablation"];
  std::vector<std::string> order{"nn", "nn_align", "paper", "spring", "spring_k", "accent"};
  for (const auto& [k, v] : ab.items())
    if (std::find(order.begin(), order.end(), k) == order.end()) order.push_back(k);
  render::BarSeries ours{"this run", {}, method_color("accent", "cross_subject", false)},
      doc{"document", {}, method_color("accent", "cross_subject", true)};
  // Short names under the bars, explained in the notes below the chart.
  const std::map<std::string, std::string> shorts{{"nn", "NN only"},        {"nn_align", "+ alignment"}, {"paper", "+ EWMA"},
                                                  {"spring", "+ spring"},    {"spring_k", "+ spring, k"}, {"accent", "engine"}};
  std::map<std::string, std::string> labels;
  if (r.contains("meta") && r["meta"].contains("variants"))
    for (const auto& v : r["meta"]["variants"]) labels[v.value("key", "")] = v.value("label", "");
  labels.emplace("accent", "the full engine: + spring smoothing, engine k and hand IK");
  for (const auto& k : order) {
    if (!ab.contains(k)) continue;
    const std::string name = shorts.count(k) ? shorts.at(k) : k;
    c.groups.push_back(name);
    if (!labels[k].empty()) c.notes.push_back(name + " (" + k + "): " + labels[k]);
    ours.values.push_back(get(ab[k], "full_body_cm"));
    doc.values.push_back(r["paper"]["ablation"].contains(k) ? r["paper"]["ablation"][k].get<double>() : kNaN);
  }
  c.series = {ours, doc};
  c.width = std::max(800, 105 * static_cast<int>(c.groups.size()));
  return c;
}

}  // namespace

std::vector<std::string> write_report(const EvalResult& res, const std::string& dir) {
  namespace fs = std::filesystem;
  fs::create_directories(dir);
  std::vector<std::string> written;
  const json r = report_json(res);
  auto write_text = [&](const std::string& name, const std::string& text) {
    const std::string path = (fs::path(dir) / name).string();
    std::ofstream f(path);
    if (!(f << text)) throw Error(path + ": cannot write");
    written.push_back(path);
  };
  write_text("report.json", r.dump(2) + "\n");
  write_text("report.md", report_markdown(r));
  auto both = [&](const render::BarChart& c, const std::string& stem) {
    for (const char* ext : {".png", ".svg"}) {
      const std::string path = (fs::path(dir) / (stem + ext)).string();
      render::plot_bars(c, path);
      written.push_back(path);
    }
  };
  both(body_parts_chart(r), "body_parts");
  if (const auto c = classes_chart(r); !c.groups.empty()) both(c, "classes");
  if (r.contains("cross_subject") && r["cross_subject"].contains("ablation")) both(ablation_chart(r), "ablation");
  return written;
}

std::string write_comparison_video(const EvalResult& r, const std::string& dir, double seconds) {
  namespace fs = std::filesystem;
  const SpeedResult& s = r.speed;
  if (s.truth.frame_count() < 2) throw Error("no held-out trial to show (the run scored no engine fold)");
  fs::create_directories(dir);
  const int last = std::min(s.truth.frame_count(), static_cast<int>(seconds * s.truth.fps) + 1) - 1;
  const Motion truth = trim(s.truth, 0, last), engine = trim(s.accent, 0, last), ik = trim(s.ik, 0, last);
  render::VideoOptions opt;
  opt.camera.view = render::View::ThreeQuarter;
  opt.follow = true;  // bodies fill their panels
  opt.camera.width = 1080;
  opt.camera.height = 480;
  opt.title = "held-out " + s.trial + " (" + s.fold + ")";
  const std::string path = (fs::path(dir) / "compare.mp4").string();
  render::render_video_side_by_side({&truth, &engine, &ik}, {"ground truth", "accent engine", "IK baseline"}, opt, path);
  return path;
}

std::string report_summary(const nlohmann::json& r) {
  auto val = [](const nlohmann::json& m, const char* k) {
    return m.contains(k) && m[k].is_number() ? m[k].get<double>() : NAN;
  };
  std::string out;
  char buf[1024];
  for (const char* p : {"cross_subject", "cross_trial", "cross_dataset"}) {
    if (!r.contains(p)) continue;
    std::snprintf(buf, sizeof buf, "%s (%d folds):\n", p, r[p]["folds"].get<int>());
    out += buf;
    for (const char* m : {"accent", "ik", "ik_own", "no_class"}) {
      if (!r[p].contains(m)) continue;
      const auto& x = r[p][m];
      std::snprintf(buf, sizeof buf,
                    "  %-8s full %5.2f cm (SD %.2f)  upper %5.2f  lower %5.2f  hands %.2f / %.2f cm  "
                    "MPJVE %.1f cm/s  jitter %.2f (truth %.2f)  skating %.2f (truth %.2f) cm/frame  hand r %.3f  "
                    "%.0f frames/s\n",
                    m, val(x, "full_body_cm"), val(x, "full_body_cm_sd"), val(x, "upper_body_cm"), val(x, "lower_body_cm"),
                    val(x, "left_hand_cm"), val(x, "right_hand_cm"), val(x, "mpjve_cm_s"), val(x, "jitter"),
                    val(x, "jitter_truth"), val(x, "foot_skating_cm"), val(x, "foot_skating_truth_cm"),
                    val(x, "hand_correlation"), val(x, "frames_per_second"));
      out += buf;
    }
    if (r[p].contains("no_class")) {
      std::snprintf(buf, sizeof buf, "  no_class: class recognised right on %.1f %% of frames, %.2f class switches per minute\n",
                    100 * val(r[p]["no_class"], "class_accuracy"), val(r[p]["no_class"], "class_switches_per_minute"));
      out += buf;
    }
    if (r[p].contains("winners") && r[p]["winners"].contains("classes"))
      for (const auto& [cls, w] : r[p]["winners"]["classes"].items()) {
        const auto& a = r[p]["accent"]["classes"][cls];
        auto who = [&](const char* part) { return w[part]["winner"].is_null() ? std::string("n/a") : w[part]["winner"].get<std::string>(); };
        std::snprintf(buf, sizeof buf,
                      "  class %-15s full %5.2f vs IK %5.2f (%s)  lower %5.2f vs IK %5.2f (%s)  skating %.2f (truth %.2f) "
                      "jitter %.1f (truth %.1f)\n",
                      cls.c_str(), val(w["full_body"], "accent"), val(w["full_body"], "ik"), who("full_body").c_str(),
                      val(w["lower_body"], "accent"), val(w["lower_body"], "ik"), who("lower_body").c_str(),
                      val(a, "foot_skating_cm"), val(a, "foot_skating_truth_cm"), val(a, "jitter"), val(a, "jitter_truth"));
        out += buf;
      }
    if (r[p].contains("ablation"))
      for (const auto& [k, x] : r[p]["ablation"].items()) {
        std::snprintf(buf, sizeof buf, "  ablation %-16s full %5.2f cm  lower %5.2f cm\n", k.c_str(), val(x, "full_body_cm"),
                      val(x, "lower_body_cm"));
        out += buf;
      }
  }
  if (r.contains("meta") && r["meta"].contains("speed")) {
    const auto& sp = r["meta"]["speed"];
    std::snprintf(buf, sizeof buf,
                  "speed pass %s: per class %.0f frames/s (%.0f CPU), p99 %.0f us, recall %.3f (%.3f without seeds), load %.2f ms "
                  "(%.2f without checksum); no class %.0f frames/s (%.0f CPU), p99 %.0f us, recall %.3f (%.3f), load %.2f ms (%.2f)\n",
                  sp.value("trial", "").c_str(), val(sp, "accent_frames_per_second"), val(sp, "accent_cpu_frames_per_second"),
                  val(sp, "accent_p99_us"), val(sp, "fast_recall"), val(sp, "fast_recall_unseeded"), val(sp, "load_ms"),
                  val(sp, "load_ms_unverified"), val(sp, "no_class_frames_per_second"), val(sp, "no_class_cpu_frames_per_second"),
                  val(sp, "no_class_p99_us"), val(sp, "no_class_fast_recall"), val(sp, "no_class_fast_recall_unseeded"),
                  val(sp, "no_class_load_ms"), val(sp, "no_class_load_ms_unverified"));
    out += buf;
  }
  for (const auto& t : r["targets"]) {
    std::snprintf(buf, sizeof buf, "target %-9s %-66s ", t.value("source", "").c_str(), t["target"].get<std::string>().c_str());
    out += std::string(buf) + (t["met"].is_null() ? "n/a" : (t["met"].get<bool>() ? "met" : "NOT met")) + "\n";
  }
  return out;
}

}  // namespace legwork::eval

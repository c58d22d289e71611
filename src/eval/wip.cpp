// Walking-in-place evaluation: detected vs true swings, depth agreement,
// the key-frame baseline, and the `legwork wip eval` report.
#include <legwork/eval/wip.hpp>
#include <legwork/eval/wip_tune.hpp>

#include <legwork/io/progress.hpp>
#include <legwork/core/stats.hpp>

#include <legwork/core/fk.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/core/series.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/io/text.hpp>
#include <legwork/render/plot.hpp>
#include <legwork/render/render.hpp>
#include <legwork/wip/baseline.hpp>
#include <legwork/wip/offline/run.hpp>
#include <legwork/wip/offline/walk_cycle.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <sstream>

namespace legwork::eval {

std::vector<SwingEvent> detected_swings(std::span<const wip::Info> frames) {
  std::vector<SwingEvent> out;
  double off[2] = {-1, -1}, apex[2] = {0, 0};
  for (const auto& fr : frames)
    for (int f = 0; f < 2; ++f) {
      if (fr.events[f] & wip::kEventFootOff) off[f] = fr.time, apex[f] = 0;
      if (off[f] >= 0) apex[f] = std::max(apex[f], fr.h[f]);
      if ((fr.events[f] & wip::kEventFootStrike) && off[f] >= 0) {
        out.push_back({f, off[f], fr.time, apex[f]});
        off[f] = -1;
      }
    }
  // A swing still open when the frames end was detected too (its foot-off fired): cut at the last frame.
  for (int f = 0; f < 2; ++f)
    if (off[f] >= 0) out.push_back({f, off[f], frames.back().time, apex[f], true});
  std::sort(out.begin(), out.end(), [](const SwingEvent& a, const SwingEvent& b) { return a.off < b.off; });
  return out;
}

StepScore score_steps(std::span<const SwingEvent> detected, std::span<const SwingEvent> truth, double t_begin,
                      double t_end) {
  StepScore s;
  auto inside = [&](const SwingEvent& e) { return e.off >= t_begin && e.strike <= t_end; };
  std::vector<char> used(detected.size(), 0);
  double off_sum = 0, strike_sum = 0;
  for (const auto& t : truth) {
    if (!inside(t)) continue;
    ++s.true_steps;
    int best = -1;
    double best_overlap = 0;
    for (std::size_t i = 0; i < detected.size(); ++i) {
      const auto& d = detected[i];
      if (used[i] || d.foot != t.foot) continue;
      const double overlap = std::min(d.strike, t.strike) - std::max(d.off, t.off);
      if (overlap > best_overlap) best_overlap = overlap, best = static_cast<int>(i);
    }
    if (best < 0) continue;
    used[static_cast<std::size_t>(best)] = 1;
    ++s.matched;
    const auto& d = detected[static_cast<std::size_t>(best)];
    s.off_latencies_ms.push_back(1000 * (d.off - t.off));
    off_sum += 1000 * (d.off - t.off);
    strike_sum += 1000 * (d.strike - t.strike);
  }
  // Detections overlapping a true swing that was left out (clip ends) are not
  // false positives.
  for (std::size_t i = 0; i < detected.size(); ++i) {
    if (used[i]) continue;
    const auto& d = detected[i];
    bool excluded = !inside(d);
    for (const auto& t : truth)
      if (!inside(t) && t.foot == d.foot && std::min(d.strike, t.strike) > std::max(d.off, t.off)) excluded = true;
    if (!excluded) ++s.detected;
  }
  s.detected += s.matched;
  s.precision = s.detected ? double(s.matched) / s.detected : 0;
  s.recall = s.true_steps ? double(s.matched) / s.true_steps : 0;
  s.f1 = s.precision + s.recall > 0 ? 2 * s.precision * s.recall / (s.precision + s.recall) : 0;
  if (s.matched) {
    s.off_latency_ms = off_sum / s.matched;
    s.strike_latency_ms = strike_sum / s.matched;
  }
  return s;
}

StepScore combine(std::span<const StepScore> scores) {
  StepScore c;
  double off = 0, strike = 0;
  for (const auto& s : scores) {
    c.true_steps += s.true_steps;
    c.detected += s.detected;
    c.matched += s.matched;
    off += s.off_latency_ms * s.matched;
    strike += s.strike_latency_ms * s.matched;
    c.off_latencies_ms.insert(c.off_latencies_ms.end(), s.off_latencies_ms.begin(), s.off_latencies_ms.end());
  }
  c.precision = c.detected ? double(c.matched) / c.detected : 0;
  c.recall = c.true_steps ? double(c.matched) / c.true_steps : 0;
  c.f1 = c.precision + c.recall > 0 ? 2 * c.precision * c.recall / (c.precision + c.recall) : 0;
  if (c.matched) c.off_latency_ms = off / c.matched, c.strike_latency_ms = strike / c.matched;
  return c;
}

namespace {
// A percentile of the latencies; NaN (n/a) when there are none.
double latency_percentile(const std::vector<double>& v, double p) { return v.empty() ? NAN : percentile(v, p); }
}  // namespace

void StrictScore::finish() {
  precision = detected ? double(matched) / detected : NAN;
  recall = true_steps ? double(matched) / true_steps : NAN;
  f1 = true_steps + detected ? 2.0 * matched / (true_steps + detected) : NAN;
  median_ms = latency_percentile(latencies_ms, 0.5);
  p90_ms = latency_percentile(latencies_ms, 0.9);
  mean_ms = NAN;
  if (!latencies_ms.empty()) {
    double sum = 0;
    for (double l : latencies_ms) sum += l;
    mean_ms = sum / static_cast<double>(latencies_ms.size());
  }
}

namespace {

// One-to-one pairs (detection, truth) within +-tolerance, closest first.
std::vector<std::pair<std::size_t, std::size_t>> match_pairs(std::span<const SwingEvent> detected,
                                                             std::span<const SwingEvent> truth, double tolerance) {
  struct Pair {
    double gap;
    std::size_t d, t;
  };
  std::vector<Pair> pairs;
  for (std::size_t t = 0; t < truth.size(); ++t)
    for (std::size_t d = 0; d < detected.size(); ++d)
      if (detected[d].foot == truth[t].foot && std::abs(detected[d].off - truth[t].off) <= tolerance + 1e-9)
        pairs.push_back({std::abs(detected[d].off - truth[t].off), d, t});
  std::stable_sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) { return a.gap < b.gap; });
  std::vector<char> used_d(detected.size(), 0), used_t(truth.size(), 0);
  std::vector<std::pair<std::size_t, std::size_t>> out;
  for (const auto& p : pairs) {
    if (used_d[p.d] || used_t[p.t]) continue;
    used_d[p.d] = used_t[p.t] = 1;
    out.emplace_back(p.d, p.t);
  }
  return out;
}

}  // namespace

std::vector<SwingEvent> unmatched_detections(std::span<const SwingEvent> detected, std::span<const SwingEvent> truth,
                                             double tolerance) {
  std::vector<char> used(detected.size(), 0);
  for (const auto& [d, t] : match_pairs(detected, truth, tolerance)) used[d] = 1;
  std::vector<SwingEvent> out;
  for (std::size_t d = 0; d < detected.size(); ++d)
    if (!used[d]) out.push_back(detected[d]);
  return out;
}

StrictScore match_foot_offs(std::span<const SwingEvent> detected, std::span<const SwingEvent> truth, double tolerance,
                            double t_begin, double t_end) {
  StrictScore s;
  s.tolerance_ms = 1000 * tolerance;
  std::vector<char> used_d(detected.size(), 0);
  auto inside = [&](double t) { return t >= t_begin && t <= t_end; };
  for (const auto& [d, t] : match_pairs(detected, truth, tolerance)) {
    used_d[d] = 1;
    if (!inside(truth[t].off)) continue;  // partner of a true step outside the window: not scored
    ++s.matched;
    s.latencies_ms.push_back(1000 * (detected[d].off - truth[t].off));
  }
  for (const auto& t : truth) s.true_steps += inside(t.off) ? 1 : 0;
  s.detected = s.matched;
  for (std::size_t d = 0; d < detected.size(); ++d) s.detected += !used_d[d] && inside(detected[d].off) ? 1 : 0;
  s.finish();
  return s;
}

StrictScore combine(std::span<const StrictScore> scores) {
  StrictScore c;
  for (const auto& s : scores) {
    c.tolerance_ms = s.tolerance_ms;
    c.true_steps += s.true_steps;
    c.detected += s.detected;
    c.matched += s.matched;
    c.latencies_ms.insert(c.latencies_ms.end(), s.latencies_ms.begin(), s.latencies_ms.end());
  }
  c.finish();
  return c;
}

std::vector<StillSegment> still_segments(const Motion& m, const std::string& name, const ContactOptions& truth,
                                         std::span<const SwingEvent> detected, double min_duration, double t_begin,
                                         double t_end) {
  const auto contact = foot_contacts(m, truth);
  std::vector<StillSegment> out;
  const int n = m.frame_count();
  for (int f = 0; f < n;) {
    const auto fu = static_cast<std::size_t>(f);
    if (!contact[0][fu] || !contact[1][fu]) { ++f; continue; }
    int e = f;
    while (e < n && contact[0][static_cast<std::size_t>(e)] && contact[1][static_cast<std::size_t>(e)]) ++e;
    StillSegment seg{name, std::max(t_begin, f / m.fps), std::min(t_end, (e - 1) / m.fps), 0};
    f = e;
    if (seg.end - seg.begin < min_duration) continue;
    for (const auto& d : detected) seg.false_steps += d.off >= seg.begin && d.off <= seg.end ? 1 : 0;
    out.push_back(seg);
  }
  return out;
}

namespace {

// The pelvis's travel per sample (DepthTrack::travel_*): direction and speed over +-kTravelWindow s, the
// direction's turn rate between the windows ending and starting at the sample, and its cosine with `forward`.
void fill_travel(DepthTrack& d, const std::vector<Vec3>& forward, double rate) {
  const int n = static_cast<int>(d.pelvis.size());
  const int w = std::max(1, static_cast<int>(std::lround(kTravelWindow * rate)));
  std::vector<double> direction(static_cast<std::size_t>(n), 0.0);
  d.travel_speed.assign(static_cast<std::size_t>(n), 0.0);
  d.travel_turn_deg_s.assign(static_cast<std::size_t>(n), 0.0);
  d.travel_along.assign(static_cast<std::size_t>(n), 1.0);
  for (int i = 0; i < n; ++i) {
    const int a = std::max(0, i - w), b = std::min(n - 1, i + w);
    Vec3 step = d.pelvis[static_cast<std::size_t>(b)] - d.pelvis[static_cast<std::size_t>(a)];
    step.y() = 0;
    const auto iu = static_cast<std::size_t>(i);
    d.travel_speed[iu] = b > a ? step.norm() * rate / (b - a) : 0.0;
    direction[iu] = std::atan2(step.x(), step.z());
    if (step.norm() > 1e-9 && std::isfinite(forward[iu].x())) d.travel_along[iu] = step.normalized().dot(forward[iu]);
  }
  for (int i = 0; i < n; ++i) {
    const int a = std::max(0, i - w), b = std::min(n - 1, i + w);
    if (b <= a) continue;
    const double turn = std::remainder(direction[static_cast<std::size_t>(b)] - direction[static_cast<std::size_t>(a)], 2 * kPi);
    d.travel_turn_deg_s[static_cast<std::size_t>(i)] = std::abs(turn) * 180 / kPi * rate / (b - a);
  }
}

}  // namespace

const char* depth_segment_name(DepthSegment s) {
  switch (s) {
    case DepthSegment::Straight: return "walking straight";
    case DepthSegment::Turning: return "walking, travel direction turning";
    case DepthSegment::Slow: return "walking, pelvis slow (turns on the spot, start/stop shuffles)";
    case DepthSegment::Backward: return "walking backward or sideways";
    case DepthSegment::NotWalking: return "not walking (before the first step, after the stop rule)";
  }
  return "?";
}

DepthSegment depth_segment(const DepthTrack& d, std::size_t i, bool walking) {
  if (i >= d.travel_speed.size()) return walking ? DepthSegment::Straight : DepthSegment::NotWalking;
  const bool moving = d.travel_speed[i] >= kSlowTravel;
  if (walking && moving && d.travel_along[i] < kBackwardCosine) return DepthSegment::Backward;
  if (!walking) return DepthSegment::NotWalking;
  if (!moving) return DepthSegment::Slow;
  return d.travel_turn_deg_s[i] > kTurnRate ? DepthSegment::Turning : DepthSegment::Straight;
}

DepthTrack true_depths(const Motion& m, double rate) {
  const auto& r = m.skeleton.roles;
  for (Role need : {Role::Pelvis, Role::LeftHip, Role::RightHip, Role::LeftAnkle, Role::RightAnkle})
    if (!r.has(need)) throw Error("true foot depths need the role " + std::string(role_name(need)));
  DepthTrack d;
  const int n = static_cast<int>(std::floor(m.duration() * rate + 1e-9)) + 1;
  Pose pose(m.skeleton);
  std::vector<Vec3> pos(static_cast<std::size_t>(m.joint_count()));
  std::vector<Vec3> pelvis(static_cast<std::size_t>(n)), ankle[2], hipline(static_cast<std::size_t>(n));
  ankle[0].resize(static_cast<std::size_t>(n));
  ankle[1].resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    sample_motion(m, i / rate, pose.ref());
    forward_positions(m.skeleton, pose, pos);
    const auto iu = static_cast<std::size_t>(i);
    pelvis[iu] = pos[static_cast<std::size_t>(r[Role::Pelvis])];
    d.pelvis.push_back(pelvis[iu]);
    ankle[0][iu] = pos[static_cast<std::size_t>(r[Role::LeftAnkle])];
    ankle[1][iu] = pos[static_cast<std::size_t>(r[Role::RightAnkle])];
    Vec3 h = pos[static_cast<std::size_t>(r[Role::LeftHip])] - pos[static_cast<std::size_t>(r[Role::RightHip])];
    h.y() = 0;
    hipline[iu] = h.normalized();
  }
  // Heading: the hip line averaged over +-0.5 s (the pelvis yaws with each step).
  const int w = std::max(1, static_cast<int>(std::lround(0.5 * rate)));
  d.z[0].resize(static_cast<std::size_t>(n));
  d.z[1].resize(static_cast<std::size_t>(n));
  d.time.resize(static_cast<std::size_t>(n));
  double yaw = NAN, lo = 0, hi = 0;
  bool first = true;
  std::vector<Vec3> forwards(static_cast<std::size_t>(n), Vec3::Zero());
  for (int i = 0; i < n; ++i) {
    Vec3 left = Vec3::Zero();
    for (int k = std::max(0, i - w); k <= std::min(n - 1, i + w); ++k) left += hipline[static_cast<std::size_t>(k)];
    left.y() = 0;
    const Vec3 forward = left.normalized().cross(Vec3::UnitY());  // +x (left) x +y (up) = +z (forward)
    const auto iu = static_cast<std::size_t>(i);
    forwards[iu] = forward;
    d.time[iu] = i / rate;
    for (int f = 0; f < 2; ++f) d.z[f][iu] = (ankle[f][iu] - pelvis[iu]).dot(forward);
    const double a = std::atan2(forward.x(), forward.z());
    if (!std::isfinite(a)) continue;
    yaw = std::isfinite(yaw) ? yaw + std::remainder(a - yaw, 2 * kPi) : a;  // unwrapped
    lo = first ? yaw : std::min(lo, yaw);
    hi = first ? yaw : std::max(hi, yaw);
    first = false;
  }
  d.heading_range_deg = (hi - lo) * 180 / kPi;
  fill_travel(d, forwards, rate);
  return d;
}

void Agreement::add(double x, double y) {
  if (!std::isfinite(x) || !std::isfinite(y)) return;
  ++samples;
  sx += x, sy += y, sxx += x * x, syy += y * y, sxy += x * y;
  se2 += (x - y) * (x - y);
}

void Agreement::merge(const Agreement& o) {
  samples += o.samples;
  sx += o.sx, sy += o.sy, sxx += o.sxx, syy += o.syy, sxy += o.sxy, se2 += o.se2;
}

void Agreement::finish() {
  if (samples < 2) return;
  const double n = samples;
  const double cov = sxy / n - (sx / n) * (sy / n);
  const double vx = sxx / n - (sx / n) * (sx / n), vy = syy / n - (sy / n) * (sy / n);
  correlation = vx > 1e-12 && vy > 1e-12 ? cov / std::sqrt(vx * vy) : 0;
  rms = std::sqrt(se2 / n);
}

WipTrialEval evaluate_wip_trial(const Motion& trial, const std::string& name, const Motion& cycle,
                                const WipEvalOptions& opt, int trial_index) {
  WipTrialEval e;
  e.name = name;
  e.subject = subject_of(name);
  e.duration = trial.duration();
  const double rate = opt.settings.signal.rate;
  wip::Settings settings = opt.settings;
  settings.mapping.depth = wip::DepthMapping::Document;  // the learned one is scored by subject (evaluate_learned_depth)
  const wip::Model model = wip::make_model(trial.skeleton, settings);
  e.leg_length = model.leg_length();
  e.truth = foot_swings(trial, opt.truth);
  wip::RunOptions ro;
  ro.calibrate = false;  // real walking has no still period: rolling floor
  ro.keep_poses = false;
  auto samples = tracker_frames_from_motion(trial, rate);
  e.frames = wip::run_wip(model, samples, ro).frames;
  e.detected = detected_swings(e.frames);
  const double t_end = e.duration - 0.1;
  e.steps = score_steps(e.detected, e.truth, opt.settle, t_end);
  e.strict = match_foot_offs(e.detected, e.truth, 0.2, opt.settle, t_end);
  e.strict_100 = match_foot_offs(e.detected, e.truth, 0.1, opt.settle, t_end);
  e.still = still_segments(trial, name, opt.truth, unmatched_detections(e.detected, e.truth, 0.2), opt.min_still,
                           opt.settle, t_end);

  wip::add_tracker_noise(samples, opt.noise, opt.drop_rate, opt.seed * 1000003ULL + static_cast<std::uint64_t>(trial_index));
  const auto noisy = wip::run_wip(model, samples, ro).frames;
  e.detected_noisy = detected_swings(noisy);
  e.steps_noisy = score_steps(e.detected_noisy, e.truth, opt.settle, t_end);
  e.strict_noisy = match_foot_offs(e.detected_noisy, e.truth, 0.2, opt.settle, t_end);
  const auto false_noisy = unmatched_detections(e.detected_noisy, e.truth, 0.2);
  for (auto& g : e.still)
    for (const auto& d : false_noisy) g.false_steps_noisy += d.off >= g.begin && d.off <= g.end ? 1 : 0;

  e.true_depth = true_depths(trial, rate);
  e.turning = e.true_depth.heading_range_deg > kTurningDegrees;
  e.speed = {name, e.subject, std::max(0.0, t_end - opt.settle),
             travelled_distance(e.true_depth.pelvis, rate, opt.settle, t_end), wip_travelled(e.frames, opt.settle, t_end)};
  e.learn = wip::learning_samples(e.frames, e.true_depth.z[0], e.true_depth.z[1], model.leg_length(), opt.settle);
  const auto base_model = wip::make_keyframe_baseline(cycle, model.leg_length());
  auto base = wip::make_baseline_state(base_model);
  const std::size_t n = std::min(e.frames.size(), e.true_depth.time.size());
  e.baseline_z[0].resize(n);
  e.baseline_z[1].resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    wip::update_baseline(base_model, e.frames[i].walking, 1.0 / rate, base);
    for (int f = 0; f < 2; ++f) {
      e.baseline_z[f][i] = base.z[f];
      if (e.frames[i].time < opt.settle) continue;
      e.depth.add(e.frames[i].z[f], e.true_depth.z[f][i]);
      e.depth_segment[static_cast<int>(depth_segment(e.true_depth, i, e.frames[i].walking))].add(e.frames[i].z[f],
                                                                                               e.true_depth.z[f][i]);
      e.baseline_depth.add(base.z[f], e.true_depth.z[f][i]);
    }
  }
  e.depth.finish();
  e.baseline_depth.finish();
  return e;
}

std::string subject_of(const std::string& trial) { return trial.substr(0, trial.find('_')); }

std::vector<wip::LearnSample> trial_learning_samples(const Motion& trial, const WipEvalOptions& opt) {
  wip::Settings settings = opt.settings;
  settings.mapping.depth = wip::DepthMapping::Document;
  const wip::Model model = wip::make_model(trial.skeleton, settings);
  wip::RunOptions ro;
  ro.calibrate = false;
  ro.keep_poses = false;
  const auto frames = wip::run_wip(model, tracker_frames_from_motion(trial, settings.signal.rate), ro).frames;
  const DepthTrack truth = true_depths(trial, settings.signal.rate);
  return wip::learning_samples(frames, truth.z[0], truth.z[1], model.leg_length(), opt.settle);
}

std::map<std::string, std::optional<wip::LearnedMapping>> learned_tables_by_subject(
    const std::map<std::string, std::vector<wip::LearnSample>>& samples_by_subject,
    const std::function<void(const std::string&)>& log) {
  std::map<std::string, std::optional<wip::LearnedMapping>> tables;
  for (const auto& [subject, own] : samples_by_subject) {
    std::vector<wip::LearnSample> train;
    for (const auto& [other, samples] : samples_by_subject)
      if (other != subject) train.insert(train.end(), samples.begin(), samples.end());
    try {
      tables[subject] = wip::build_learned_mapping(train);
    } catch (const Error& err) {
      tables[subject] = std::nullopt;
      if (log) log("learned mapping without subject " + subject + ": " + err.what() + "\n");
    }
  }
  return tables;
}

void evaluate_learned_depth(const Motion& trial, const wip::LearnedMapping& table, const WipEvalOptions& opt,
                            WipTrialEval& e) {
  wip::Settings settings = opt.settings;
  settings.mapping.depth = wip::DepthMapping::Learned;
  const wip::Model model = wip::make_model(trial.skeleton, settings, {}, &table);
  wip::RunOptions ro;
  ro.calibrate = false;
  ro.keep_poses = false;
  const auto frames = wip::run_wip(model, tracker_frames_from_motion(trial, settings.signal.rate), ro).frames;
  const std::size_t n = std::min(frames.size(), e.true_depth.time.size());
  e.depth_learned = {};
  for (auto& a : e.learned_segment) a = {};
  for (int f = 0; f < 2; ++f) {
    e.learned_z[f].assign(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      e.learned_z[f][i] = frames[i].z[f];
      if (frames[i].time < opt.settle) continue;
      e.depth_learned.add(frames[i].z[f], e.true_depth.z[f][i]);
      e.learned_segment[static_cast<int>(depth_segment(e.true_depth, i, frames[i].walking))].add(frames[i].z[f],
                                                                                               e.true_depth.z[f][i]);
    }
  }
  e.depth_learned.finish();
}

namespace {

// Swing intervals of one foot as plot bands.
std::vector<render::Band> swing_bands(std::span<const SwingEvent> swings, int foot, render::Rgb color,
                                      const std::string& label, double alpha = 0.18) {
  std::vector<render::Band> out;
  for (const auto& s : swings)
    if (s.foot == foot) out.emplace_back(s.off, s.strike, color, label, alpha);
  return out;
}

std::vector<double> column(std::span<const wip::Info> frames, double (*get)(const wip::Info&)) {
  std::vector<double> v;
  v.reserve(frames.size());
  for (const auto& f : frames) v.push_back(get(f));
  return v;
}

}  // namespace

void plot_wip_phases(const std::string& path, const std::string& title, std::span<const wip::Info> frames,
                      const Motion& avatar, const std::vector<int>& strip, const std::vector<double>* baseline_z,
                      const wip::GaitSettings& gait) {
  if (io::extension_of(path) != ".png") throw Error("phase plot '" + path + "' must end in .png");
  if (frames.empty()) throw Error("nothing to plot: no frames");
  const auto t = column(frames, [](const wip::Info& f) { return f.time; });
  const auto det = detected_swings(frames);
  render::LinePlot p;
  p.title = title;
  p.x_label = "time (s)";
  p.panel_height = 170;
  auto& ph = p.panels.emplace_back();
  ph.title = "ankle height above floor (filtered) with detected swings";
  ph.y_label = "h (m)";
  ph.series.emplace_back("left", t, column(frames, [](const wip::Info& f) { return f.h[0]; }), render::kLeftColor);
  ph.series.emplace_back("right", t, column(frames, [](const wip::Info& f) { return f.h[1]; }), render::kRightColor);
  ph.series.emplace_back("H1 in use (left)", t, column(frames, [](const wip::Info& f) { return f.h1[0]; }),
                         render::Rgb{0.4, 0.4, 0.45});
  ph.series.back().dashed = true;
  for (auto& b : swing_bands(det, 0, render::kLeftColor, "left swing")) ph.bands.push_back(b);
  for (auto& b : swing_bands(det, 1, render::kRightColor, "right swing")) ph.bands.push_back(b);
  auto& pv = p.panels.emplace_back();
  pv.title = "vertical velocity";
  pv.y_label = "v (m/s)";
  pv.series.emplace_back("left", t, column(frames, [](const wip::Info& f) { return f.v[0]; }), render::kLeftColor);
  pv.series.emplace_back("right", t, column(frames, [](const wip::Info& f) { return f.v[1]; }), render::kRightColor);
  pv.ref_lines.emplace_back(gait.v1, "V1");
  pv.ref_lines.emplace_back(-gait.v2, "-V2");
  auto& pp = p.panels.emplace_back();
  pp.title = "gait phase (0 double support, 1 initial, 2 mid, 3 terminal swing)";
  pp.y_label = "phase";
  pp.series.emplace_back("left", t, column(frames, [](const wip::Info& f) { return double(int(f.phase[0])); }),
                         render::kLeftColor);
  pp.series.emplace_back("right", t, column(frames, [](const wip::Info& f) { return int(f.phase[1]) + 0.08; }),
                         render::kRightColor);
  pp.y_min = -0.2;
  pp.y_max = 3.3;
  auto& pz = p.panels.emplace_back();
  pz.title = "IK-target depth (forward +, relative to the pelvis)";
  pz.y_label = "z (m)";
  pz.series.emplace_back("left", t, column(frames, [](const wip::Info& f) { return f.z[0]; }), render::kLeftColor);
  pz.series.emplace_back("right", t, column(frames, [](const wip::Info& f) { return f.z[1]; }), render::kRightColor);
  if (baseline_z) {
    pz.series.emplace_back("left, key-frame baseline", t, baseline_z[0], render::kLeftColor);
    pz.series.back().dashed = true;
  }
  auto& ps = p.panels.emplace_back();
  ps.title = "forward speed and body drop";
  ps.y_label = "m/s, m";
  ps.series.emplace_back("speed (m/s)", t, column(frames, [](const wip::Info& f) { return f.speed; }));
  ps.series.emplace_back("root offset (m)", t, column(frames, [](const wip::Info& f) { return f.root_offset; }));
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
  render::stack_pngs({tmp_plot, tmp_strip}, path);
  std::filesystem::remove(tmp_plot);
  std::filesystem::remove(tmp_strip);
}

std::string format_or_na(double v, const char* f) {
  if (!std::isfinite(v)) return "n/a";
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

std::string format_strict(const StrictScore& s) {
  return "precision " + format_or_na(s.precision, "%.3f") + ", recall " + format_or_na(s.recall, "%.3f") + ", F1 " +
         format_or_na(s.f1, "%.3f") + " (" + std::to_string(s.matched) + " of " + std::to_string(s.true_steps) +
         " true, " + std::to_string(s.detected) + " detected), foot-off latency median " +
         format_or_na(s.median_ms, "%.0f ms") + ", p90 " + format_or_na(s.p90_ms, "%.0f ms");
}

std::string describe_wip_run(std::span<const wip::Info> frames, double rate, std::span<const SwingEvent> truth) {
  if (frames.empty()) return "no frames\n";
  int steps = 0;
  for (const auto& f : frames) steps += ((f.events[0] | f.events[1]) & wip::kEventFootOff) ? 1 : 0;
  const auto& last = frames.back();
  const double span = last.time - frames.front().time;
  char buf[400];
  std::snprintf(buf, sizeof buf, "%zu frames at %.4g Hz: %d steps detected, walked %.2f m (mean %.2f m/s over %.1f s)\n",
                frames.size(), rate, steps, last.distance, last.distance / std::max(1e-9, span), span);
  std::string out = buf;
  if (truth.empty()) return out;  // no ground truth (tracker CSV) or no true steps
  const auto sc = match_foot_offs(detected_swings(frames), truth, 0.2, 0.5, last.time - 0.1);
  return out + "against the input's true foot-offs (+-200 ms, one to one): " + format_strict(sc) + "\n";
}

std::vector<int> strip_frames(const std::string& spec, std::span<const wip::Info> frames) {
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


namespace {

nlohmann::json score_json(const StepScore& s) {
  return {{"true_steps", s.true_steps},          {"detected", s.detected},   {"matched", s.matched},
          {"precision", s.precision},            {"recall", s.recall},       {"f1", s.f1},
          {"foot_off_latency_ms", s.off_latency_ms}, {"foot_strike_latency_ms", s.strike_latency_ms}};
}

// NaN (undefined) becomes null in the JSON.
nlohmann::json num(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json strict_json(const StrictScore& s) {
  return {{"tolerance_ms", s.tolerance_ms},    {"true_steps", s.true_steps},   {"detected", s.detected},
          {"matched", s.matched},              {"precision", num(s.precision)}, {"recall", num(s.recall)},
          {"f1", num(s.f1)},                   {"latency_median_ms", num(s.median_ms)},
          {"latency_p90_ms", num(s.p90_ms)},   {"latency_mean_ms", num(s.mean_ms)}};
}

std::string na(double v, const char* f) { return format_or_na(v, f); }

void write_trial_plot(const WipTrialEval& e, const std::string& path) {
  render::LinePlot p;
  p.title = e.name + ": detected (coloured) vs true (grey) swings; generated (document, learned) vs true vs baseline depth";
  p.x_label = "time (s)";
  p.panel_height = 150;
  const auto t = column(e.frames, [](const wip::Info& f) { return f.time; });
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
    if (e.learned_z[f].size() >= n) {
      std::vector<double> learned(e.learned_z[f].begin(), e.learned_z[f].begin() + static_cast<std::ptrdiff_t>(n));
      pz.series.emplace_back("learned mapping (other subjects)", tt, learned, render::Rgb{0.2, 0.6, 0.25});
    }
  }
  render::plot_lines(p, path);
}

// Running totals over the evaluated trials.
struct Totals {
  std::vector<StepScore> clean, noisy, fixed;
  std::vector<StrictScore> strict, strict_100, strict_noisy, strict_fixed;
  std::vector<StillSegment> still;
  Agreement depth, base;
  Agreement depth_class[2], learned, learned_class[2];  // [0] normal, [1] turning walks
  Agreement depth_segment[kDepthSegments], learned_segment[kDepthSegments];
  int learned_trials = 0;
  std::vector<SpeedTrial> speed;
  nlohmann::json trials = nlohmann::json::array();
  std::ostringstream rows;
  int failed = 0;
};

void add_trial(const WipTrialEval& e, const WipTrialEval& ef, Totals& t) {
  t.clean.push_back(e.steps);
  t.noisy.push_back(e.steps_noisy);
  t.fixed.push_back(ef.steps);
  t.strict.push_back(e.strict);
  t.strict_100.push_back(e.strict_100);
  t.strict_noisy.push_back(e.strict_noisy);
  t.strict_fixed.push_back(ef.strict);
  t.still.insert(t.still.end(), e.still.begin(), e.still.end());
  t.speed.push_back(e.speed);
  t.depth.merge(e.depth);
  t.base.merge(e.baseline_depth);
  t.depth_class[e.turning ? 1 : 0].merge(e.depth);
  for (int k = 0; k < kDepthSegments; ++k) t.depth_segment[k].merge(e.depth_segment[k]);
  if (e.depth_learned.samples > 1) {
    ++t.learned_trials;
    t.learned.merge(e.depth_learned);
    t.learned_class[e.turning ? 1 : 0].merge(e.depth_learned);
    for (int k = 0; k < kDepthSegments; ++k) t.learned_segment[k].merge(e.learned_segment[k]);
  }
  t.trials.push_back({{"trial", e.name},
                      {"duration_s", e.duration},
                      {"leg_length_m", e.leg_length},
                      {"strict_200ms", strict_json(e.strict)},
                      {"strict_100ms", strict_json(e.strict_100)},
                      {"strict_200ms_noisy", strict_json(e.strict_noisy)},
                      {"strict_200ms_fixed_thresholds", strict_json(ef.strict)},
                      {"lenient_overlap", score_json(e.steps)},
                      {"lenient_overlap_noisy", score_json(e.steps_noisy)},
                      {"depth_correlation", num(e.depth.correlation)},
                      {"depth_rms_cm", 100 * e.depth.rms},
                      {"baseline_depth_correlation", num(e.baseline_depth.correlation)},
                      {"baseline_depth_rms_cm", 100 * e.baseline_depth.rms},
                      {"subject", e.subject},
                      {"class", e.turning ? "turning" : "normal"},
                      {"heading_range_deg", e.true_depth.heading_range_deg},
                      {"real_speed_mps", e.speed.real_speed()},
                      {"wip_speed_mps", e.speed.wip_speed()},
                      {"learned_depth_correlation", e.depth_learned.samples > 1 ? num(e.depth_learned.correlation) : nullptr},
                      {"learned_depth_rms_cm", e.depth_learned.samples > 1 ? num(100 * e.depth_learned.rms) : nullptr},
                      {"plot", e.name + ".png"}});
  t.rows << "| " << e.name << " | " << na(e.duration, "%.1f") << " | " << e.strict.true_steps << " | "
         << e.strict.detected << " | " << e.strict.matched << " | " << na(e.strict.f1, "%.3f") << " | "
         << na(e.strict_100.f1, "%.3f") << " | " << na(e.strict_noisy.f1, "%.3f") << " | "
         << na(e.strict.median_ms, "%.0f") << " | " << na(e.steps.true_steps ? e.steps.f1 : NAN, "%.3f") << " | "
         << na(e.depth.correlation, "%.2f") << " | " << na(100 * e.depth.rms, "%.1f") << " | "
         << (e.turning ? "turning" : "normal") << " | "
         << (e.depth_learned.samples > 1 ? na(e.depth_learned.correlation, "%.2f") : "n/a") << " | "
         << (e.depth_learned.samples > 1 ? na(100 * e.depth_learned.rms, "%.1f") : "n/a") << " |\n";
}

Motion load_trial(const std::string& path, const WipEvalRun& run) {
  io::BvhReadOptions opt;
  opt.drop_first_frame = true;
  auto f = io::read_bvh(path, opt);
  if (run.log)
    for (const auto& w : f.report.warnings) run.log("legwork: " + path + ": " + w + "\n");
  return std::move(f.motion);
}

// The goals, each judged from this run's figures.
struct Goal {
  std::string name, value;
  bool met = false, known = true;
};

// The four step-detection goals for one detector's figures.
void detector_goals(const std::string& who, const DetectorSummary& d, std::vector<Goal>& g) {
  g.push_back({"strict step F1 >= 0.97" + who, na(d.strict.f1, "%.3f"), d.strict.f1 >= 0.97, std::isfinite(d.strict.f1)});
  g.push_back({"strict step F1 >= 0.95 with noise" + who, na(d.strict_noisy.f1, "%.3f"), d.strict_noisy.f1 >= 0.95,
               std::isfinite(d.strict_noisy.f1)});
  g.push_back({"median foot-off latency <= 60 ms" + who, na(d.strict.median_ms, "%.0f ms"), d.strict.median_ms <= 60,
               std::isfinite(d.strict.median_ms)});
  g.push_back({"<= 1 false step per minute on still segments (clean and noisy)" + who,
               na(d.false_steps_per_minute, "%.2f") + " / " + na(d.false_steps_per_minute_noisy, "%.2f") + " /min",
               d.false_steps_per_minute <= 1 && d.false_steps_per_minute_noisy <= 1,
               std::isfinite(d.false_steps_per_minute)});
}

std::vector<Goal> goals(const WipEvalSummary& s) {
  std::vector<Goal> g;
  g.push_back({"strict step F1 (+-200 ms) >= 0.97 over all " + std::to_string(s.trials) + " trials (the default settings)",
               na(s.strict.f1, "%.3f"), s.strict.f1 >= 0.97, std::isfinite(s.strict.f1)});
  g.push_back({"strict step F1 >= 0.95 with Kinect-like noise", na(s.strict_noisy.f1, "%.3f"),
               s.strict_noisy.f1 >= 0.95, std::isfinite(s.strict_noisy.f1)});
  g.push_back({"median foot-off latency <= 60 ms", na(s.strict.median_ms, "%.0f ms"), s.strict.median_ms <= 60,
               std::isfinite(s.strict.median_ms)});
  g.push_back({"<= 1 false step per minute on still segments",
               na(s.false_steps_per_minute, "%.2f /min") + " over " + na(s.still_minutes, "%.2f") + " min",
               s.false_steps_per_minute <= 1, std::isfinite(s.false_steps_per_minute)});
  for (const auto& d : s.detectors)
    if (!d.name.empty()) detector_goals(" (" + d.name + " detector)", d, g);
  if (s.cross_validated) {
    DetectorSummary cv;
    cv.strict = s.cv_strict;
    cv.strict_noisy = s.cv_noisy;
    cv.false_steps_per_minute = s.cv_false_per_minute;
    cv.false_steps_per_minute_noisy = s.cv_false_per_minute_noisy;
    detector_goals(" (adaptive detector, parameters cross-validated by subject)", cv, g);
  }
  if (s.speed.trials > 0) {
    const double ratio = s.speed.real_speed > 0 ? s.speed.wip_speed / s.speed.real_speed : NAN;
    g.push_back({"walking speed within 10 % of the capture's (pooled, the run's gain)",
                 na(s.speed.wip_speed, "%.2f") + " vs " + na(s.speed.real_speed, "%.2f") + " m/s",
                 std::abs(ratio - 1) <= 0.1, std::isfinite(ratio)});
  }
  g.push_back({"IK-target depth r >= 0.9 and RMS <= 8 cm (the document's mapping)",
               "r " + na(s.depth.correlation, "%.3f") + ", RMS " + na(100 * s.depth.rms, "%.1f cm"),
               s.depth.correlation >= 0.9 && s.depth.rms <= 0.08, s.depth.samples > 1});
  g.push_back({"IK-target depth r >= 0.9 and RMS <= 8 cm (learned mapping, cross-validated by subject)",
               "r " + na(s.learned.correlation, "%.3f") + ", RMS " + na(100 * s.learned.rms, "%.1f cm"),
               s.learned.correlation >= 0.9 && s.learned.rms <= 0.08, s.learned.samples > 1});
  return g;
}

std::string verdict(const Goal& g) { return !g.known ? "n/a" : g.met ? "met" : "not met"; }

nlohmann::json agreement_json(const Agreement& a) {
  if (a.samples < 2) return nullptr;
  return {{"r", num(a.correlation)}, {"rms_cm", num(100 * a.rms)}, {"samples", a.samples}};
}

// Depth agreement of both mappings, pooled and per trial class.
nlohmann::json depth_mapping_json(const WipEvalSummary& s) {
  return {{"document", {{"pooled", agreement_json(s.depth)},
                        {"normal", agreement_json(s.depth_normal)},
                        {"turning", agreement_json(s.depth_turning)}}},
          {"learned_cv_by_subject", {{"pooled", agreement_json(s.learned)},
                                     {"normal", agreement_json(s.learned_normal)},
                                     {"turning", agreement_json(s.learned_turning)},
                                     {"trials", s.learned_trials}}},
          {"turning_if_heading_range_deg_over", kTurningDegrees}};
}

// One segment's agreement with its share of the pooled squared error and the pooled RMS without it.
nlohmann::json segment_json(const Agreement& a, const Agreement& pooled) {
  nlohmann::json j = agreement_json(a);
  if (j.is_null()) return j;
  j["share_of_squared_error"] = num(pooled.se2 > 0 ? a.se2 / pooled.se2 : NAN);
  const int rest = pooled.samples - a.samples;
  j["pooled_rms_cm_without"] = rest > 0 ? num(100 * std::sqrt((pooled.se2 - a.se2) / rest)) : nullptr;
  return j;
}

// Both mappings' depth by DepthSegment.
nlohmann::json depth_segments_json(const WipEvalSummary& s) {
  nlohmann::json j = nlohmann::json::array();
  for (int k = 0; k < kDepthSegments; ++k)
    j.push_back({{"segment", depth_segment_name(static_cast<DepthSegment>(k))},
                 {"document", segment_json(s.depth_segment[k], s.depth)},
                 {"learned_cv_by_subject", segment_json(s.learned_segment[k], s.learned)}});
  return j;
}

// Both step detectors side by side (document = before, adaptive = after) and
// the adaptive one's cross-validation by subject when it ran.
nlohmann::json detectors_json(const WipEvalSummary& s) {
  nlohmann::json j;
  for (const auto& d : s.detectors) {
    if (d.name.empty()) continue;
    j[d.name] = {{"strict_200ms", strict_json(d.strict)},
                 {"strict_100ms", strict_json(d.strict_100)},
                 {"strict_200ms_noisy", strict_json(d.strict_noisy)},
                 {"false_steps", d.false_steps},
                 {"false_steps_noisy", d.false_steps_noisy},
                 {"false_steps_per_minute", num(d.false_steps_per_minute)},
                 {"false_steps_per_minute_noisy", num(d.false_steps_per_minute_noisy)}};
  }
  if (s.cross_validated) j["adaptive_cross_validated_by_subject"] = nlohmann::json::parse(s.tuning_json);
  return j;
}

std::string detectors_markdown(const WipEvalRun& run, const WipEvalSummary& s) {
  std::ostringstream md;
  md << "\n## Step detectors side by side (document = before, adaptive = after)\n\nThe default settings use the "
     << (run.options.settings.gait.detector == wip::StepDetector::Adaptive ? "adaptive" : "document") << " detector. "
     << "The adaptive detector's parameters are the ones chosen on all subjects (`legwork wip tune`): its rows here are "
        "in-sample; the cross-validated figures are below when the run was asked for them (`--cross-validate-detector`).\n\n"
        "| detector | F1 +-200 ms | F1 +-100 ms | F1 noisy | precision / recall | latency median / p90 ms | "
        "false steps on still segments (clean / noisy) |\n|---|---|---|---|---|---|---|\n";
  for (const auto& d : s.detectors)
    md << "| " << d.name << " | **" << na(d.strict.f1, "%.3f") << "** | " << na(d.strict_100.f1, "%.3f") << " | **"
       << na(d.strict_noisy.f1, "%.3f") << "** | " << na(d.strict.precision, "%.3f") << " / " << na(d.strict.recall, "%.3f")
       << " | " << na(d.strict.median_ms, "%.0f") << " / " << na(d.strict.p90_ms, "%.0f") << " | " << d.false_steps
       << " / " << d.false_steps_noisy << " (" << na(d.false_steps_per_minute, "%.2f") << " / "
       << na(d.false_steps_per_minute_noisy, "%.2f") << " per min) |\n";
  if (s.cross_validated) md << s.tuning_markdown;
  return md.str();
}

nlohmann::json speed_json(const SpeedSummary& v) {
  nlohmann::json folds = nlohmann::json::array();
  for (const auto& f : v.folds)
    folds.push_back({{"subject", f.subject}, {"gain", f.gain}, {"real_speed_mps", f.real_speed}, {"wip_speed_mps", f.wip_speed}});
  return {{"trials", v.trials},           {"gain", v.gain},
          {"real_speed_mps", v.real_speed}, {"wip_speed_mps", v.wip_speed},
          {"rms_error_mps", v.rms_error},   {"calibrated_gain", v.calibrated_gain},
          {"cv_by_subject", {{"wip_speed_mps", v.cv_wip_speed}, {"rms_error_mps", v.cv_rms_error}, {"folds", folds}}}};
}

nlohmann::json summary_json(const WipEvalRun& run, const WipEvalSummary& s, const Totals& t) {
  const auto& a = run.options.settings;
  nlohmann::json j;
  j["strict_200ms"] = strict_json(s.strict);
  j["strict_100ms"] = strict_json(s.strict_100);
  j["strict_200ms_noisy"] = strict_json(s.strict_noisy);
  j["strict_200ms_fixed_thresholds"] = strict_json(s.strict_fixed);
  j["still_minutes"] = s.still_minutes;
  j["false_steps_per_minute"] = num(s.false_steps_per_minute);
  j["false_steps_per_minute_noisy"] = num(s.false_steps_per_minute_noisy);
  j["still_segments"] = nlohmann::json::array();
  for (const auto& g : s.still)
    j["still_segments"].push_back({{"trial", g.trial}, {"begin_s", g.begin}, {"end_s", g.end}, {"false_steps", g.false_steps},
                                  {"false_steps_noisy", g.false_steps_noisy}});
  j["goals"] = nlohmann::json::array();
  for (const auto& g : goals(s)) j["goals"].push_back({{"goal", g.name}, {"value", g.value}, {"verdict", verdict(g)}});
  j["lenient_overlap"] = score_json(s.steps);  // secondary: any overlap of swings counts
  j["lenient_overlap_noisy"] = score_json(s.steps_noisy);
  j["lenient_overlap_fixed_thresholds"] = score_json(s.steps_fixed);
  j["depth_correlation"] = num(s.depth.correlation);
  j["depth_rms_cm"] = 100 * s.depth.rms;
  j["baseline_depth_correlation"] = num(s.baseline_depth.correlation);
  j["baseline_depth_rms_cm"] = 100 * s.baseline_depth.rms;
  j["depth_by_mapping"] = depth_mapping_json(s);
  j["depth_by_segment"] = depth_segments_json(s);
  j["detectors"] = detectors_json(s);
  j["walking_speed"] = speed_json(s.speed);
  j["trials"] = s.trials;
  j["trials_skipped"] = s.skipped;
  j["data"] = run.data;
  if (!run.note.empty()) j["note"] = run.note;
  j["baseline_clip"] = run.clip;
  j["settings"] = {{"tracker_rate_hz", a.signal.rate}, {"cutoff_hz", a.signal.cutoff},
                   {"h1_m", a.gait.h1},                {"v1_mps", a.gait.v1},
                   {"v2_mps", a.gait.v2},              {"adaptive", a.gait.adaptive},
                   {"detector", a.gait.detector == wip::StepDetector::Adaptive ? "adaptive" : "document"},
                   {"detector_parameters", DetectorParams::of(a).describe()},
                   {"noise_m", run.options.noise},     {"drop_rate", run.options.drop_rate},
                   {"seed", run.options.seed},         {"min_still_s", run.options.min_still},
                   {"truth", run.options.truth.learned ? "learned" : "fixed"}};
  j["per_trial"] = t.trials;
  return j;
}

std::string strict_row(const std::string& label, const StrictScore& s) {
  return "| " + label + " | " + na(s.precision, "%.3f") + " | " + na(s.recall, "%.3f") + " | **" + na(s.f1, "%.3f") +
         "** | " + std::to_string(s.matched) + " / " + std::to_string(s.true_steps) + " / " +
         std::to_string(s.detected) + " | " + na(s.median_ms, "%.0f") + " | " + na(s.p90_ms, "%.0f") + " |\n";
}

std::string agreement_cell(const Agreement& a) {
  if (a.samples < 2) return "n/a";
  return "r " + na(a.correlation, "%.3f") + ", RMS " + na(100 * a.rms, "%.1f") + " cm";
}

// Where the depth error comes from: each DepthSegment's share of the pooled squared error, both mappings.
std::string depth_segments_markdown(const WipEvalSummary& s) {
  std::ostringstream md;
  md << "\n### IK-target depth by segment\n\nFrames by what the body does (pelvis path over +-" << kTravelWindow
     << " s): backward or sideways = travelling more than 60 degrees off the heading at >= " << kSlowTravel
     << " m/s while walking; slow = pelvis under " << kSlowTravel << " m/s; turning = travel direction turning faster than "
     << kTurnRate << " degrees/s. Share = the segment's part of the mapping's pooled squared error.\n\n"
     << "| segment | samples | document | learned (cross-validated by subject) | learned: share of squared error | "
        "learned: pooled RMS without it |\n|---|---|---|---|---|---|\n";
  for (int k = 0; k < kDepthSegments; ++k) {
    const Agreement& l = s.learned_segment[k];
    const bool known = l.samples > 0 && s.learned.se2 > 0 && s.learned.samples > l.samples;
    md << "| " << depth_segment_name(static_cast<DepthSegment>(k)) << " | " << s.depth_segment[k].samples << " | "
       << agreement_cell(s.depth_segment[k]) << " | " << agreement_cell(l) << " | "
       << (known ? na(100 * l.se2 / s.learned.se2, "%.1f %%") : "n/a") << " | "
       << (known ? na(100 * std::sqrt((s.learned.se2 - l.se2) / (s.learned.samples - l.samples)), "%.2f cm") : "n/a")
       << " |\n";
  }
  return md.str();
}

std::string depth_markdown(const WipEvalSummary& s) {
  std::ostringstream md;
  md << "\n## IK-target depth vs the real feet, by mapping\n\nThe learned mapping is cross-validated by subject: "
        "each trial is scored with a table built only from the other subjects' walks ("
     << s.learned_trials << " trials scored). Turning walks: the walking heading spans more than " << kTurningDegrees
     << " degrees.\n\n| mapping | normal walks | turning walks | pooled |\n|---|---|---|---|\n"
     << "| document (equations 1-4) | " << agreement_cell(s.depth_normal) << " | " << agreement_cell(s.depth_turning)
     << " | " << agreement_cell(s.depth) << " |\n"
     << "| learned, cross-validated by subject | " << agreement_cell(s.learned_normal) << " | "
     << agreement_cell(s.learned_turning) << " | " << agreement_cell(s.learned) << " |\n";
  return md.str() + depth_segments_markdown(s);
}

std::string speed_markdown(const SpeedSummary& v) {
  std::ostringstream md;
  md << "\n## Walking speed against the capture's\n\nThe avatar's travel (step-speed gain " << na(v.gain, "%.2f")
     << ") against the pelvis's real path (averaged over +-0.5 s), over the scored time of " << v.trials
     << " trials. The gain that matches the real speed on all trials: **" << na(v.calibrated_gain, "%.2f")
     << "**; cross-validated by subject, each subject is scored with the gain chosen on the others.\n\n"
        "| | pooled speed m/s | RMS error of trial mean speeds m/s |\n|---|---|---|\n"
     << "| real (pelvis) | " << na(v.real_speed, "%.2f") << " | - |\n"
     << "| method, gain " << na(v.gain, "%.2f") << " | " << na(v.wip_speed, "%.2f") << " | " << na(v.rms_error, "%.2f") << " |\n"
     << "| method, gain cross-validated by subject | " << na(v.cv_wip_speed, "%.2f") << " | " << na(v.cv_rms_error, "%.2f")
     << " |\n\n| held-out subject | gain (from the others) | real m/s | method m/s |\n|---|---|---|---|\n";
  for (const auto& f : v.folds)
    md << "| " << f.subject << " | " << na(f.gain, "%.2f") << " | " << na(f.real_speed, "%.2f") << " | "
       << na(f.wip_speed, "%.2f") << " |\n";
  return md.str();
}

std::string summary_markdown(const WipEvalRun& run, const WipEvalSummary& s, const Totals& t) {
  std::ostringstream md;
  md << "# Walking-in-place evaluation on real walking\n\n";
  md << "Data: `" << run.data << "` (" << s.trials << " trials";
  if (s.skipped) md << ", " << s.skipped << " skipped";
  md << "). Each trial's own ankles drive the method at " << run.options.settings.signal.rate
     << " Hz (rolling floor, no calibration) with its own skeleton as the avatar. Ground truth: "
     << (run.options.truth.learned ? "per-foot contact from the ankle and toe heights against each joint's stance "
                                     "height and lift range learned from the trial (hysteresis)"
                                   : "the former fixed margin (3 cm over a rolling floor)")
     << ", swings >= " << run.options.truth.min_swing << " s.\n";
  if (!run.note.empty()) md << "\n**Note:** " << run.note << ".\n";
  md << "\n## Goals (computed from this run)\n\n| goal | value | verdict |\n|---|---|---|\n";
  for (const auto& g : goals(s)) md << "| " << g.name << " | " << g.value << " | **" << verdict(g) << "** |\n";
  md << "\n## Strict step scores (headline)\n\nDetected and true foot-offs of the same foot matched one to one "
        "within the tolerance, closest first; latency = detected - true (signed).\n\n"
        "| score | precision | recall | F1 | matched / true / detected | latency median ms | latency p90 ms |\n"
        "|---|---|---|---|---|---|---|\n"
     << strict_row("+-200 ms", s.strict) << strict_row("+-100 ms", s.strict_100)
     << strict_row("+-200 ms, " + na(100 * run.options.noise, "%.1f") + " cm noise + " +
                       na(100 * run.options.drop_rate, "%.0f") + "% drops",
                   s.strict_noisy)
     << strict_row("+-200 ms, the document's fixed H1/V1/V2", s.strict_fixed);
  md << detectors_markdown(run, s);
  md << "\nFalse steps on still segments (both feet in true contact for >= " << run.options.min_still
     << " s): " << na(s.false_steps_per_minute, "%.2f") << " per minute over " << na(s.still_minutes, "%.2f")
     << " min (" << s.still.size() << " segments, listed below); with noise "
     << na(s.false_steps_per_minute_noisy, "%.2f") << " per minute.\n";
  md << "\n## Secondary figures\n\n| measure | value |\n|---|---|\n"
     << "| lenient overlap F1 (a detected swing overlapping the true one at all counts) | "
     << na(s.steps.f1, "%.3f") << " (precision " << na(s.steps.precision, "%.3f") << ", recall "
     << na(s.steps.recall, "%.3f") << "; noisy " << na(s.steps_noisy.f1, "%.3f") << ") |\n"
     << "| IK-target depth vs real foot depth | r = **" << na(s.depth.correlation, "%.3f") << "**, RMS **"
     << na(100 * s.depth.rms, "%.1f") << " cm** |\n"
     << "| key-frame baseline depth vs real foot depth | r = " << na(s.baseline_depth.correlation, "%.3f")
     << ", RMS " << na(100 * s.baseline_depth.rms, "%.1f") << " cm |\n";
  md << depth_markdown(s) << speed_markdown(s.speed);
  md << "\n## Per trial\n\n| trial | s | true | detected | matched | F1 +-200 | F1 +-100 | F1 noisy | latency "
        "median ms | lenient overlap F1 | depth r | depth RMS cm | class | learned depth r | learned RMS cm |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n"
     << t.rows.str();
  md << "\n## Still segments\n\n| trial | from s | to s | false steps | false steps, noisy |\n|---|---|---|---|---|\n";
  for (const auto& g : s.still)
    md << "| " << g.trial << " | " << na(g.begin, "%.2f") << " | " << na(g.end, "%.2f") << " | " << g.false_steps
       << " | " << g.false_steps_noisy << " |\n";
  return md.str();
}

void summary_chart(const WipEvalSummary& s, const std::string& path) {
  render::BarChart bc;
  bc.title = "walking in place on " + std::to_string(s.trials) + " CMU walking trials";
  bc.groups = {"strict F1 +-200 ms", "strict F1 (noisy)", "lenient overlap F1", "depth r"};
  bc.series.emplace_back("method", std::vector<double>{s.strict.f1, s.strict_noisy.f1, s.steps.f1, s.depth.correlation});
  bc.series.emplace_back("document's fixed thresholds", std::vector<double>{s.strict_fixed.f1, NAN, s.steps_fixed.f1, NAN});
  bc.series.emplace_back("learned depth mapping (cross-validated by subject)",
                         std::vector<double>{NAN, NAN, NAN, s.learned.samples > 1 ? s.learned.correlation : NAN});
  bc.series.emplace_back("key-frame baseline", std::vector<double>{NAN, NAN, NAN, s.baseline_depth.correlation});
  render::plot_bars(bc, path);
}

void finish_summary(const Totals& t, WipEvalSummary& s) {
  s.trials = static_cast<int>(t.clean.size());
  s.skipped = t.failed;
  s.depth = t.depth;
  s.baseline_depth = t.base;
  s.depth.finish();
  s.baseline_depth.finish();
  Agreement* parts[] = {&s.depth_normal, &s.depth_turning, &s.learned, &s.learned_normal, &s.learned_turning};
  const Agreement* from[] = {&t.depth_class[0], &t.depth_class[1], &t.learned, &t.learned_class[0], &t.learned_class[1]};
  for (int i = 0; i < 5; ++i) *parts[i] = *from[i], parts[i]->finish();
  for (int k = 0; k < kDepthSegments; ++k) {
    s.depth_segment[k] = t.depth_segment[k];
    s.depth_segment[k].finish();
    s.learned_segment[k] = t.learned_segment[k];
    s.learned_segment[k].finish();
  }
  s.learned_trials = t.learned_trials;
  s.steps = combine(t.clean);
  s.steps_noisy = combine(t.noisy);
  s.steps_fixed = combine(t.fixed);
  s.strict = combine(t.strict);
  s.strict_100 = combine(t.strict_100);
  s.strict_noisy = combine(t.strict_noisy);
  s.strict_fixed = combine(t.strict_fixed);
  s.still = t.still;
  int false_steps = 0, false_noisy = 0;
  for (const auto& g : s.still)
    s.still_minutes += (g.end - g.begin) / 60, false_steps += g.false_steps, false_noisy += g.false_steps_noisy;
  s.false_steps_per_minute = s.still_minutes > 0 ? false_steps / s.still_minutes : NAN;
  s.false_steps_per_minute_noisy = s.still_minutes > 0 ? false_noisy / s.still_minutes : NAN;
}

// The learned mapping, cross-validated by subject: each trial is scored with
// a table built only from the other subjects' walks (n/a when they are too few).
void cross_validate_learned(const std::vector<Motion>& motions, std::vector<WipTrialEval>& evals, const WipEvalRun& run) {
  std::map<std::string, std::vector<wip::LearnSample>> by_subject;
  for (const auto& e : evals) by_subject[e.subject].insert(by_subject[e.subject].end(), e.learn.begin(), e.learn.end());
  const auto tables = learned_tables_by_subject(by_subject, run.log);
  for (std::size_t i = 0; i < evals.size(); ++i)
    if (const auto& table = tables.at(evals[i].subject)) evaluate_learned_depth(motions[i], *table, run.options, evals[i]);
}

// Both step detectors on the prepared trials and, if asked, the adaptive
// detector's parameters chosen by cross-validation by subject.
void score_detectors(const std::vector<DetectionTrial>& trials, const WipEvalRun& run, WipEvalSummary& s) {
  for (int d = 0; d < 2; ++d) {
    wip::Settings settings = run.options.settings;
    settings.gait.detector = d == 0 ? wip::StepDetector::Document : wip::StepDetector::Adaptive;
    std::vector<DetectionCounts> parts;
    for (const auto& t : trials) parts.push_back(score_detection(t, settings));
    const DetectionCounts c = pool(parts);
    DetectorSummary& out = s.detectors[d];
    out.name = d == 0 ? "document" : "adaptive";
    out.strict = c.strict;
    out.strict_100 = c.strict_100;
    out.strict_noisy = c.noisy;
    out.false_steps = c.false_steps;
    out.false_steps_noisy = c.false_steps_noisy;
    out.false_steps_per_minute = c.false_per_minute();
    out.false_steps_per_minute_noisy = c.false_per_minute_noisy();
  }
  if (!run.cross_validate_detector) return;
  const auto progress = io::progress_printer("legwork wip eval: detector parameter set");
  const DetectorTuning t = tune_detector(trials, run.options.settings, default_detector_grid(), [&](int i, int n) {
    if (run.log) progress(i, n, "");
  });
  if (run.log) run.log("\n");
  s.cross_validated = true;
  s.cv_strict = t.cross_validated.strict;
  s.cv_noisy = t.cross_validated.noisy;
  s.cv_false_per_minute = t.cross_validated.false_per_minute();
  s.cv_false_per_minute_noisy = t.cross_validated.false_per_minute_noisy();
  s.tuning_markdown = tuning_markdown(t);
  s.tuning_json = tuning_json(t);
}

}  // namespace

WipEvalSummary run_wip_evaluation(const WipEvalRun& run) {
  namespace fs = std::filesystem;
  if (run.files.empty()) throw Error("'" + run.data + "' holds no .bvh files");
  std::error_code ec;
  fs::create_directories(run.out, ec);
  if (ec || !fs::is_directory(run.out)) throw Error("cannot create the output folder '" + run.out + "'");
  const fs::path out(run.out);
  const Motion cycle = wip::extract_walk_cycle(load_trial(run.clip, run));
  WipEvalOptions fixed = run.options;  // the document's detector with its fixed thresholds, for comparison
  fixed.settings.gait.detector = wip::StepDetector::Document;
  fixed.settings.gait.adaptive = false;
  Totals t;
  std::vector<Motion> motions;
  std::vector<WipTrialEval> evals, evals_fixed;
  std::vector<DetectionTrial> detection;
  int index = 0;
  const auto progress = io::progress_printer("legwork wip eval: trial");
  for (const auto& file : run.files) {
    const std::string name = fs::path(file).stem().string();
    if (run.log) progress(index + 1, static_cast<int>(run.files.size()), name);
    WipTrialEval e, ef;
    try {
      Motion m = load_trial(file, run);
      e = evaluate_wip_trial(m, name, cycle, run.options, index);
      ef = evaluate_wip_trial(m, name, cycle, fixed, index);
      detection.push_back(prepare_detection_trial(m, name, run.options, index));
      motions.push_back(std::move(m));
    } catch (const Error& err) {
      if (run.log) run.log("legwork wip eval: skipping " + file + ": " + err.what() + "\n");
      ++t.failed;
      ++index;
      continue;
    }
    ++index;
    evals.push_back(std::move(e));
    evals_fixed.push_back(std::move(ef));
  }
  if (run.log) run.log("\n");
  cross_validate_learned(motions, evals, run);
  for (std::size_t i = 0; i < evals.size(); ++i) {
    add_trial(evals[i], evals_fixed[i], t);
    write_trial_plot(evals[i], (out / (evals[i].name + ".png")).string());
  }
  if (t.clean.empty()) throw Error("no trial in '" + run.data + "' could be evaluated");
  WipEvalSummary s;
  finish_summary(t, s);
  s.speed = summarize_speed(t.speed, wip::step_speed_gain(run.options.settings));
  score_detectors(detection, run, s);
  io::write_text_file((out / "report.json").string(), summary_json(run, s, t).dump(2) + "\n");
  io::write_text_file((out / "report.md").string(), summary_markdown(run, s, t));
  summary_chart(s, (out / "summary.png").string());
  s.written = {(out / "report.md").string(), (out / "report.json").string()};
  return s;
}

}  // namespace legwork::eval

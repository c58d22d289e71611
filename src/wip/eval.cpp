#include <legwork/core/series.hpp>
#include <legwork/wip/eval.hpp>

#include <legwork/core/fk.hpp>
#include <legwork/core/interpolate.hpp>

#include <algorithm>
#include <cmath>
#include <deque>

namespace legwork::wip {

namespace {


}  // namespace

std::vector<SwingEvent> true_swings(const Motion& m, const TruthParams& p) {
  const auto& r = m.skeleton.roles;
  if (!r.has(Role::LeftAnkle) || !r.has(Role::RightAnkle))
    throw Error("true gait events need ankle joints (roles LeftAnkle/RightAnkle)");
  const int n = m.frame_count(), nj = m.joint_count();
  if (n < 3) return {};
  const std::vector<Vec3> pos = joint_positions(m);
  auto at = [&](int f, int j) { return pos[static_cast<std::size_t>(f) * static_cast<std::size_t>(nj) + static_cast<std::size_t>(j)]; };
  const Role ankles[2] = {Role::LeftAnkle, Role::RightAnkle}, toes[2] = {Role::LeftToe, Role::RightToe};
  const int w = std::max(1, static_cast<int>(std::lround(p.floor_window * m.fps)));
  const int k = std::max(1, static_cast<int>(std::lround(0.01 * m.fps)));  // +-10 ms for speeds
  std::vector<SwingEvent> out;
  for (int foot = 0; foot < 2; ++foot) {
    const int ja = r[ankles[foot]];
    const int jt = r.has(toes[foot]) ? r[toes[foot]] : ja;
    std::vector<char> contact(static_cast<std::size_t>(n), 0);
    std::vector<double> height(static_cast<std::size_t>(n));
    for (int part = 0; part < 2; ++part) {
      const int j = part == 0 ? ja : jt;
      std::vector<double> y(static_cast<std::size_t>(n));
      for (int f = 0; f < n; ++f) y[static_cast<std::size_t>(f)] = at(f, j).y();
      const auto floor = rolling_min(y, w);
      for (int f = 0; f < n; ++f) {
        const int a = std::max(0, f - k), b = std::min(n - 1, f + k);
        const double speed = (at(b, j) - at(a, j)).norm() / ((b - a) / m.fps);
        const double above = y[static_cast<std::size_t>(f)] - floor[static_cast<std::size_t>(f)];
        if (above < p.height_tol && speed < p.speed_tol) contact[static_cast<std::size_t>(f)] = 1;
        if (part == 0) height[static_cast<std::size_t>(f)] = above;
      }
    }
    // Fill short touch-downs, then collect swings (runs without contact).
    const int min_stance = static_cast<int>(std::lround(p.min_stance * m.fps));
    for (int f = 0; f < n;) {
      if (!contact[static_cast<std::size_t>(f)]) { ++f; continue; }
      int e = f;
      while (e < n && contact[static_cast<std::size_t>(e)]) ++e;
      if (f > 0 && e < n && e - f < min_stance) std::fill(contact.begin() + f, contact.begin() + e, 0);
      f = e;
    }
    for (int f = 0; f < n;) {
      if (contact[static_cast<std::size_t>(f)]) { ++f; continue; }
      int e = f;
      double apex = 0;
      while (e < n && !contact[static_cast<std::size_t>(e)]) apex = std::max(apex, height[static_cast<std::size_t>(e++)]);
      const double t0 = f / m.fps, t1 = e / m.fps;
      // Swings cut by the clip's ends have no true foot-off or foot-strike.
      if (f > 0 && e < n && t1 - t0 >= p.min_swing) out.push_back({foot, t0, t1, apex});
      f = e;
    }
  }
  std::sort(out.begin(), out.end(), [](const SwingEvent& a, const SwingEvent& b) { return a.off < b.off; });
  return out;
}

std::vector<SwingEvent> detected_swings(std::span<const WipFrame> frames) {
  std::vector<SwingEvent> out;
  double off[2] = {-1, -1}, apex[2] = {0, 0};
  for (const auto& fr : frames)
    for (int f = 0; f < 2; ++f) {
      if (fr.events[f] & kEventFootOff) off[f] = fr.time, apex[f] = 0;
      if (off[f] >= 0) apex[f] = std::max(apex[f], fr.h[f]);
      if ((fr.events[f] & kEventFootStrike) && off[f] >= 0) {
        out.push_back({f, off[f], fr.time, apex[f]});
        off[f] = -1;
      }
    }
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
  for (int i = 0; i < n; ++i) {
    Vec3 left = Vec3::Zero();
    for (int k = std::max(0, i - w); k <= std::min(n - 1, i + w); ++k) left += hipline[static_cast<std::size_t>(k)];
    left.y() = 0;
    const Vec3 forward = left.normalized().cross(Vec3::UnitY());  // +x (left) x +y (up) = +z (forward)
    const auto iu = static_cast<std::size_t>(i);
    d.time[iu] = i / rate;
    for (int f = 0; f < 2; ++f) d.z[f][iu] = (ankle[f][iu] - pelvis[iu]).dot(forward);
  }
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

}  // namespace legwork::wip

namespace legwork::wip {

TrialEval evaluate_trial(const Motion& trial, const std::string& name, const Motion& cycle, const EvalOptions& opt,
                         int trial_index) {
  TrialEval e;
  e.name = name;
  e.duration = trial.duration();
  const double rate = opt.params.signal.rate;
  const WipModel model = make_wip_model(trial.skeleton, opt.params);
  e.leg_length = model.leg_length;
  e.truth = true_swings(trial, opt.truth);
  RunOptions ro;
  ro.calibrate = false;  // real walking has no still period: rolling floor
  ro.keep_poses = false;
  auto samples = samples_from_motion(trial, rate);
  e.frames = run_wip(model, samples, ro).frames;
  e.detected = detected_swings(e.frames);
  const double t_end = e.duration - 0.1;
  e.steps = score_steps(e.detected, e.truth, opt.settle, t_end);

  add_tracker_noise(samples, opt.noise, opt.drop_rate, opt.seed * 1000003ULL + static_cast<std::uint64_t>(trial_index));
  const auto noisy = run_wip(model, samples, ro).frames;
  e.detected_noisy = detected_swings(noisy);
  e.steps_noisy = score_steps(e.detected_noisy, e.truth, opt.settle, t_end);

  e.true_depth = true_depths(trial, rate);
  const auto base_model = make_keyframe_baseline(cycle, model.leg_length);
  auto base = make_baseline_state(base_model);
  const std::size_t n = std::min(e.frames.size(), e.true_depth.time.size());
  e.baseline_z[0].resize(n);
  e.baseline_z[1].resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    update_baseline(base_model, e.frames[i].walking, 1.0 / rate, base);
    for (int f = 0; f < 2; ++f) {
      e.baseline_z[f][i] = base.z[f];
      if (e.frames[i].time < opt.settle) continue;
      e.depth.add(e.frames[i].z[f], e.true_depth.z[f][i]);
      e.baseline_depth.add(base.z[f], e.true_depth.z[f][i]);
    }
  }
  e.depth.finish();
  e.baseline_depth.finish();
  return e;
}

}  // namespace legwork::wip

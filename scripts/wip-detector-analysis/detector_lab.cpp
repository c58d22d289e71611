// Step-detector lab (analysis tool, not part of the library; README.md here).
//   detector_lab DATA_DIR list  [key=value ...]   every missed true foot-off and false detection (clean run) with the
//                                                  detection signal around it
//   detector_lab DATA_DIR score [key=value ...]   pooled strict scores (clean, noisy), per subject, still segments
//   detector_lab DATA_DIR cv key=v1,v2,... ...     cross-validation by subject over the grid of the listed values
//                                                  (every combination; the other parameters at the given/default values)
// Keys: the adaptive detector's settings (see kKeys below).
#include <legwork/eval/wip_tune.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/wip/offline/run.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

using namespace legwork;

namespace {

double* field(wip::Settings& s, const std::string& k) {
  auto& g = s.gait;
  auto& p = s.signal;
  const std::map<std::string, double*> m = {
      {"detect_cutoff", &p.detect_cutoff}, {"baseline_tau", &p.baseline_tau}, {"noise_tau", &p.noise_tau},
      {"lift_fraction", &g.lift_fraction}, {"rise_fraction", &g.rise_fraction}, {"noise_factor", &g.noise_factor},
      {"rise_noise_factor", &g.rise_noise_factor}, {"min_lift", &g.min_lift}, {"min_rise", &g.min_rise},
      {"estimate_rate", &g.estimate_rate}, {"land_fraction", &g.land_fraction}, {"min_stance_time", &g.min_stance_time},
      {"velocity_fraction", &g.velocity_fraction},
      {"rest_time", &g.rest_time}, {"rest_lift", &g.rest_lift}, {"rest_rise", &g.rest_rise}, {"rest_noise_factor", &g.rest_noise_factor},
      {"settle_time", &g.settle_time}, {"min_swing_time", &g.min_swing_time},
  };
  auto it = m.find(k);
  if (it == m.end()) {
    std::fprintf(stderr, "unknown key %s\n", k.c_str());
    std::exit(2);
  }
  return it->second;
}

std::vector<double> parse_list(const std::string& v) {
  std::vector<double> out;
  std::size_t a = 0;
  while (a <= v.size()) {
    auto b = v.find(',', a);
    if (b == std::string::npos) b = v.size();
    out.push_back(std::stod(v.substr(a, b - a)));
    a = b + 1;
  }
  return out;
}

struct Trace {
  std::vector<double> t, hd[2], vd[2], h1[2], v1[2], apex[2], raw[2];
  std::vector<int> phase[2];
};

Trace trace(const eval::DetectionTrial& tr, const wip::Settings& s0) {
  wip::Settings s = s0;
  s.mapping.depth = wip::DepthMapping::Document;
  const wip::Model model = wip::make_model(tr.skeleton, s);
  wip::State st(model);
  Pose pose(model.skeleton());
  Trace out;
  for (const auto& fr : std::getenv("LAB_NOISY") ? tr.noisy : tr.clean) {
    wip::Info info;
    if (wip::update(model, fr, st, pose.ref(), &info) == UpdateStatus::Rejected) continue;
    out.t.push_back(info.time);
    for (int f = 0; f < 2; ++f) {
      out.hd[f].push_back(st.feet[f].hd);
      out.vd[f].push_back(st.feet[f].vd);
      out.h1[f].push_back(st.gait[f].h1(s.gait));
      out.v1[f].push_back(st.gait[f].v1(s.gait));
      out.apex[f].push_back(st.gait[f].apex_estimate);
      out.raw[f].push_back(fr.foot(f).position.y() - st.feet[f].floor);
      out.phase[f].push_back(static_cast<int>(st.gait[f].phase));
    }
  }
  return out;
}

void print_trace(const Trace& tr, int foot, double from, double to) {
  std::printf("      t      hd(cm) vd(m/s) H1(cm) V1   raw(cm) ph other-ph\n");
  for (std::size_t i = 0; i < tr.t.size(); ++i) {
    if (tr.t[i] < from || tr.t[i] > to) continue;
    std::printf("      %6.3f %6.2f %6.3f %6.2f %5.3f %6.2f %d %d\n", tr.t[i], 100 * tr.hd[foot][i], tr.vd[foot][i],
                100 * tr.h1[foot][i], tr.v1[foot][i], 100 * tr.raw[foot][i], tr.phase[foot][i], tr.phase[1 - foot][i]);
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: detector_lab DATA_DIR list|score|cv [key=value ...]\n");
    return 2;
  }
  const std::string dir = argv[1], mode = argv[2];
  eval::WipEvalOptions opt;
  std::vector<std::pair<std::string, std::vector<double>>> grid_keys;
  bool traces = std::getenv("LAB_TRACES") != nullptr;
  const bool noisy = std::getenv("LAB_NOISY") != nullptr;  // list: the noisy run
  for (int i = 3; i < argc; ++i) {
    std::string a = argv[i];
    auto eq = a.find('=');
    std::string k = a.substr(0, eq), v = a.substr(eq + 1);
    auto vals = parse_list(v);
    if (vals.size() > 1 || mode == "cv") grid_keys.push_back({k, vals});
    else *field(opt.settings, k) = vals[0];
  }
  std::vector<std::string> files;
  for (auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().extension() == ".bvh") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  std::vector<eval::DetectionTrial> trials;
  for (std::size_t i = 0; i < files.size(); ++i) {
    io::BvhReadOptions o;
    o.drop_first_frame = true;
    trials.push_back(eval::prepare_detection_trial(io::read_bvh(files[i], o).motion,
                                                   std::filesystem::path(files[i]).stem().string(), opt, static_cast<int>(i)));
  }
  if (mode == "score") {
    std::vector<eval::DetectionCounts> all;
    std::map<std::string, std::vector<eval::DetectionCounts>> by;
    for (const auto& t : trials) {
      auto c = eval::score_detection(t, opt.settings);
      all.push_back(c);
      by[t.subject].push_back(c);
    }
    for (auto& [sub, v] : by) {
      auto c = eval::pool(v);
      std::printf("subject %-4s F1 %.3f (miss %d, fp %d) noisy %.3f (miss %d, fp %d)\n", sub.c_str(), c.strict.f1,
                  c.strict.true_steps - c.strict.matched, c.strict.detected - c.strict.matched, c.noisy.f1,
                  c.noisy.true_steps - c.noisy.matched, c.noisy.detected - c.noisy.matched);
    }
    auto c = eval::pool(all);
    std::printf("ALL F1 %.4f P %.3f R %.3f (true %d det %d match %d) F1@100 %.3f | noisy F1 %.4f (det %d match %d) | "
                "latency median %.0f p90 %.0f noisy median %.0f | false still %d / %d over %.2f min\n",
                c.strict.f1, c.strict.precision, c.strict.recall, c.strict.true_steps, c.strict.detected, c.strict.matched,
                c.strict_100.f1, c.noisy.f1, c.noisy.detected, c.noisy.matched, c.strict.median_ms, c.strict.p90_ms,
                c.noisy.median_ms, c.false_steps, c.false_steps_noisy, c.still_minutes);
    return 0;
  }
  if (mode == "cv") {
    std::vector<wip::Settings> points(1, opt.settings);
    for (auto& [k, vals] : grid_keys) {
      std::vector<wip::Settings> next;
      for (auto& p : points)
        for (double v : vals) {
          auto q = p;
          *field(q, k) = v;
          next.push_back(q);
        }
      points = next;
    }
    // Score every point on every trial, then the by-subject selection rule of eval::tune_detector.
    std::vector<std::vector<eval::DetectionCounts>> per(points.size());
    for (std::size_t g = 0; g < points.size(); ++g) {
      for (const auto& t : trials) per[g].push_back(eval::score_detection(t, points[g]));
      auto c = eval::pool(per[g]);
      std::fprintf(stderr, "point %zu/%zu:", g + 1, points.size());
      for (auto& [k, vals] : grid_keys) std::fprintf(stderr, " %s=%g", k.c_str(), *field(points[g], k));
      std::fprintf(stderr, "  in-sample F1 %.4f noisy %.4f lat %.0f false %d/%d\n", c.strict.f1, c.noisy.f1,
                   c.strict.median_ms, c.false_steps, c.false_steps_noisy);
    }
    std::map<std::string, std::vector<std::size_t>> by;
    for (std::size_t i = 0; i < trials.size(); ++i) by[trials[i].subject].push_back(i);
    auto choose = [&](const std::vector<char>& use) {
      int best = -1, best_any = -1;
      double sc = -1, sc_any = -1;
      for (std::size_t g = 0; g < points.size(); ++g) {
        std::vector<eval::DetectionCounts> parts;
        for (std::size_t i = 0; i < use.size(); ++i)
          if (use[i]) parts.push_back(per[g][i]);
        auto c = eval::pool(parts);
        double o = (std::isfinite(c.strict.f1) ? c.strict.f1 : 0) + (std::isfinite(c.noisy.f1) ? c.noisy.f1 : 0);
        bool ok = (!(c.still_minutes > 0) || (c.false_per_minute() <= 1 && c.false_per_minute_noisy() <= 1)) &&
                  c.strict.median_ms <= 60;
        if (o > sc_any) sc_any = o, best_any = static_cast<int>(g);
        if (ok && o > sc) sc = o, best = static_cast<int>(g);
      }
      return best >= 0 ? best : best_any;
    };
    std::vector<eval::DetectionCounts> held;
    for (auto& [sub, mem] : by) {
      std::vector<char> train(trials.size(), 1);
      for (auto i : mem) train[i] = 0;
      int g = choose(train);
      std::vector<eval::DetectionCounts> parts;
      for (auto i : mem) parts.push_back(per[static_cast<std::size_t>(g)][i]);
      auto c = eval::pool(parts);
      held.push_back(c);
      std::printf("fold %-4s chose", sub.c_str());
      for (auto& [k, vals] : grid_keys) std::printf(" %s=%g", k.c_str(), *field(points[static_cast<std::size_t>(g)], k));
      std::printf(": F1 %.3f noisy %.3f\n", c.strict.f1, c.noisy.f1);
    }
    auto c = eval::pool(held);
    int ga = choose(std::vector<char>(trials.size(), 1));
    std::printf("HELD OUT F1 %.4f (true %d det %d match %d) noisy %.4f (det %d match %d) latency median %.0f noisy %.0f "
                "false %d / %d\nchosen on all:",
                c.strict.f1, c.strict.true_steps, c.strict.detected, c.strict.matched, c.noisy.f1, c.noisy.detected,
                c.noisy.matched, c.strict.median_ms, c.noisy.median_ms, c.false_steps, c.false_steps_noisy);
    for (auto& [k, vals] : grid_keys) std::printf(" %s=%g", k.c_str(), *field(points[static_cast<std::size_t>(ga)], k));
    std::printf("\n");
    return 0;
  }
  // list
  wip::Settings s = opt.settings;
  s.mapping.depth = wip::DepthMapping::Document;
  for (const auto& t : trials) {
    const wip::Model model = wip::make_model(t.skeleton, s);
    wip::RunOptions ro;
    ro.calibrate = false;
    ro.keep_poses = false;
    const auto det = eval::detected_swings(wip::run_wip(model, noisy ? t.noisy : t.clean, ro).frames);
    const auto fps = eval::unmatched_detections(det, t.truth, 0.2);
    // Misses: true foot-offs inside the window with no detection matched (recompute the matching's complement).
    const auto unmatched_truth = eval::unmatched_detections(t.truth, det, 0.2);
    std::vector<SwingEvent> misses;
    for (const auto& u : unmatched_truth)
      if (u.off >= t.t_begin && u.off <= t.t_end) misses.push_back(u);
    if (misses.empty() && fps.empty()) continue;
    Trace tr = trace(t, s);
    for (const auto& m : misses) {
      double nearest = 1e9;
      for (const auto& d : det)
        if (d.foot == m.foot && std::abs(d.off - m.off) < std::abs(nearest)) nearest = d.off - m.off;
      // Other foot's last true strike before this foot-off.
      double other_strike = -1e9, other_off = -1e9;
      for (const auto& o : t.truth)
        if (o.foot != m.foot) {
          if (o.strike <= m.off + 0.05) other_strike = std::max(other_strike, o.strike);
          if (o.off <= m.off) other_off = std::max(other_off, o.off);
        }
      double maxhd = -1, maxvd = -1;
      for (std::size_t i = 0; i < tr.t.size(); ++i)
        if (tr.t[i] >= m.off - 0.1 && tr.t[i] <= std::min(m.strike, m.off + 0.4)) {
          maxhd = std::max(maxhd, tr.hd[m.foot][i]);
          maxvd = std::max(maxvd, tr.vd[m.foot][i]);
        }
      std::printf("MISS %s foot %d off %.3f strike %.3f (swing %.0f ms, true apex %.1f cm) nearest det %+.0f ms; "
                  "other foot: last strike %+.0f ms, last off %+.0f ms; max hd %.1f cm, max vd %.2f\n",
                  t.name.c_str(), m.foot, m.off, m.strike, 1000 * (m.strike - m.off), 100 * m.apex, 1000 * nearest,
                  1000 * (other_strike - m.off), 1000 * (other_off - m.off), 100 * maxhd, maxvd);
      if (traces) print_trace(tr, m.foot, m.off - 0.4, std::min(m.strike, m.off + 0.5));
    }
    for (const auto& d : fps) {
      if (d.off < t.t_begin || d.off > t.t_end) continue;
      bool still = false;
      for (const auto& g : t.still) still |= d.off >= g.begin && d.off <= g.end;
      double nearest = 1e9;
      for (const auto& u : t.truth)
        if (u.foot == d.foot && std::abs(d.off - u.off) < std::abs(nearest)) nearest = d.off - u.off;
      std::printf("FP   %s foot %d off %.3f strike %.3f (apex %.1f cm) nearest true off %+.0f ms%s\n", t.name.c_str(),
                  d.foot, d.off, d.strike, 100 * d.apex, 1000 * nearest, still ? " STILL" : "");
      if (traces) print_trace(tr, d.foot, d.off - 0.4, d.off + 0.5);
    }
  }
  return 0;
}

// legwork.eval: role tracks and the metrics of legwork/eval/metrics.hpp.
#include "bindings.hpp"

#include <legwork/eval/combined.hpp>
#include <legwork/eval/metrics.hpp>
#include <legwork/eval/wip.hpp>

#include <cmath>
#include <cstdio>
#include <span>

namespace legwork::py {
namespace {
namespace eval_binding {

using namespace pybind11::literals;
using namespace legwork::eval;

RoleTrack track_from_arrays(double fps, const pb::handle& positions, const std::vector<bool>& present) {
  require_rate(fps, "fps");
  const Array p = require_array(positions, "positions", {kAny, kRoleCount, 3}, "(frames, 21 roles, 3) metres");
  if (present.size() != static_cast<std::size_t>(kRoleCount))
    value_error("present: expected " + std::to_string(kRoleCount) + " flags (one per role, see legwork.eval.ROLES), got " +
                std::to_string(present.size()));
  std::array<bool, kRoleCount> flags{};
  for (int r = 0; r < kRoleCount; ++r) flags[static_cast<std::size_t>(r)] = present[static_cast<std::size_t>(r)];
  RoleTrack t = make_track(fps, static_cast<int>(p.shape(0)), flags);
  std::copy(p.data(), p.data() + p.size(), t.positions.front().data());
  return t;
}

void bind_track(pb::module_& m) {
  std::vector<std::string> roles;
  for (int r = 0; r < kRoleCount; ++r) roles.emplace_back(role_name(static_cast<Role>(r)));
  m.attr("ROLES") = roles;
  std::vector<std::string> parts;
  for (int p = 0; p < kPartCount; ++p) parts.emplace_back(part_name(static_cast<Part>(p)));
  m.attr("PARTS") = parts;
  pb::class_<RoleTrack>(m, "RoleTrack", "Role-joint positions over time (frames, 21 roles in ROLES order, 3), metres.")
      .def(pb::init(&track_from_arrays), "fps"_a, "positions"_a, "present"_a,
           "RoleTrack(fps: Hz, positions: float64 (frames, 21, 3) metres model space, present: 21 bools)")
      .def_readonly("fps", &RoleTrack::fps)
      .def_readonly("frames", &RoleTrack::frames)
      .def_property_readonly("present", [](const RoleTrack& t) { return std::vector<bool>(t.present.begin(), t.present.end()); })
      .def_property_readonly(
          "positions",
          [](const pb::object& self) {
            auto& t = self.cast<RoleTrack&>();
            return view(t.positions.empty() ? nullptr : t.positions.front().data(), {t.frames, kRoleCount, 3}, self, false);
          },
          "float64 (frames, 21, 3) metres (read-only view; zero where a role is absent)");
  m.def("role_track", &role_track, "motion"_a, "FK of every frame, keeping the role joints.");
}

void bind_metrics(pb::module_& m) {
  pb::class_<TrialMetrics>(m, "TrialMetrics", "Metrics of one output track against ground truth.")
      .def_readonly("frames", &TrialMetrics::frames)
      .def_property_readonly("part_cm", [](const TrialMetrics& t) {
        pb::dict d;
        for (int p = 0; p < kPartCount; ++p) d[pb::str(std::string(part_name(static_cast<Part>(p))))] = t.part_cm[static_cast<std::size_t>(p)];
        return d;
      }, "dict part name -> mean per-joint position error, cm")
      .def_readonly("mpjpe_cm", &TrialMetrics::mpjpe_cm, "mean per-joint position error over role joints, cm")
      .def_readonly("mpjve_cm_s", &TrialMetrics::mpjve_cm_s, "mean per-joint velocity error, cm/s")
      .def_readonly("jitter", &TrialMetrics::jitter, "output mean jerk, 10^2 m/s^3")
      .def_readonly("jitter_truth", &TrialMetrics::jitter_truth, "ground truth mean jerk, 10^2 m/s^3")
      .def_readonly("hand_correlation", &TrialMetrics::hand_correlation, "[left, right] Pearson r of hand positions")
      .def_readonly("foot_skating_cm", &TrialMetrics::foot_skating_cm, "mean foot slide in contact, cm per frame")
      .def_readonly("foot_skating_truth_cm", &TrialMetrics::foot_skating_truth_cm)
      .def_readonly("foot_contact_fraction", &TrialMetrics::foot_contact_fraction);
  m.def(
      "evaluate_trial",
      [](const RoleTrack& out, const RoleTrack& truth, double contact_height) {
        MetricOptions opt;
        opt.contact_height = contact_height;
        return evaluate_trial(out, truth, opt);
      },
      "output"_a, "truth"_a, "contact_height"_a = 0.03,
      "Every metric of `output` against `truth` (same frames and rate); legwork.Error if they differ or share no role.");
  m.def("mean_jerk", &mean_jerk, "track"_a, "Mean jerk magnitude over role joints and frames, m/s^3.");
  m.def(
      "foot_skating",
      [](const RoleTrack& t, double h) {
        const FootSkate s = foot_skating(t, h);
        return pb::make_tuple(s.slide_m, s.contact_fraction);
      },
      "track"_a, "contact_height"_a = 0.03,
      "(mean horizontal slide per frame of foot joints in contact, metres; fraction of foot-joint frames in contact).");
  m.def(
      "mpjpe", [](const RoleTrack& o, const RoleTrack& t) { return evaluate_trial(o, t).mpjpe_cm; }, "output"_a, "truth"_a,
      "Mean per-joint position error over the role joints, cm.");
  m.def(
      "mpjve", [](const RoleTrack& o, const RoleTrack& t) { return evaluate_trial(o, t).mpjve_cm_s; }, "output"_a, "truth"_a,
      "Mean per-joint velocity error over the role joints, cm/s.");
}

void bind_steps(pb::module_& m) {
  pb::class_<StepScore>(m, "StepScore", "Step detection against true gait events (one-to-one matching).")
      .def_readonly("true_steps", &StepScore::true_steps)
      .def_readonly("detected", &StepScore::detected)
      .def_readonly("matched", &StepScore::matched)
      .def_readonly("precision", &StepScore::precision)
      .def_readonly("recall", &StepScore::recall)
      .def_readonly("f1", &StepScore::f1)
      .def_readonly("off_latency_ms", &StepScore::off_latency_ms, "mean detected - true foot-off, ms")
      .def_readonly("strike_latency_ms", &StepScore::strike_latency_ms, "mean detected - true foot-strike, ms");
  m.def(
      "detected_swings", [](const std::vector<wip::Info>& frames) { return detected_swings(frames); }, "frames"_a,
      "Swings (legwork.wip.SwingEvent) seen by the gait machines in a list of legwork.wip.Info, one per consumed frame.");
  pb::class_<StrictScore>(m, "StrictScore",
                          "Step detection scored as the field does (legwork.eval.match_foot_offs): rates are NaN where\n"
                          "undefined (no detections, no true steps); latencies in ms, signed (detected - true foot-off).")
      .def_readonly("tolerance_ms", &StrictScore::tolerance_ms)
      .def_readonly("true_steps", &StrictScore::true_steps)
      .def_readonly("detected", &StrictScore::detected)
      .def_readonly("matched", &StrictScore::matched)
      .def_readonly("precision", &StrictScore::precision)
      .def_readonly("recall", &StrictScore::recall)
      .def_readonly("f1", &StrictScore::f1)
      .def_readonly("latencies_ms", &StrictScore::latencies_ms, "one per matched step")
      .def_readonly("median_ms", &StrictScore::median_ms)
      .def_readonly("p90_ms", &StrictScore::p90_ms)
      .def_readonly("mean_ms", &StrictScore::mean_ms)
      .def("__repr__", [](const StrictScore& s) { return "StrictScore(+-" + format_or_na(s.tolerance_ms, "%.0f") + " ms: " + format_strict(s) + ")"; });
  auto check_window = [](double tolerance, double t_begin, double t_end) {
    if (!(std::isfinite(tolerance) && tolerance > 0 && tolerance < 10))
      value_error("tolerance: expected seconds in (0, 10), e.g. 0.2 for the field's +-200 ms, got " + std::to_string(tolerance));
    if (!(std::isfinite(t_begin) && std::isfinite(t_end) && t_begin <= t_end))
      value_error("t_begin, t_end: expected finite seconds with t_begin <= t_end, got " + std::to_string(t_begin) + ", " +
                  std::to_string(t_end));
  };
  m.def(
      "match_foot_offs",
      [check_window](const std::vector<SwingEvent>& detected, const std::vector<SwingEvent>& truth, double t_begin,
                     double t_end, double tolerance) {
        check_window(tolerance, t_begin, t_end);
        return match_foot_offs(detected, truth, tolerance, t_begin, t_end);
      },
      "detected"_a, "truth"_a, "t_begin"_a, "t_end"_a, "tolerance"_a = 0.2,
      "The field's standard step score, `legwork wip eval`'s headline: detected and true foot-offs of the same foot\n"
      "matched one to one within +-tolerance seconds, closest pairs first; only true foot-offs in [t_begin, t_end]\n"
      "count, and a detection there with no partner is a false step. truth: legwork.wip.foot_swings(motion,\n"
      "end_swings=True). Returns legwork.eval.StrictScore.");
  m.def(
      "unmatched_detections",
      [check_window](const std::vector<SwingEvent>& detected, const std::vector<SwingEvent>& truth, double tolerance) {
        check_window(tolerance, 0, 0);
        return unmatched_detections(detected, truth, tolerance);
      },
      "detected"_a, "truth"_a, "tolerance"_a = 0.2,
      "The detections match_foot_offs leaves without a true partner: the false steps, wherever they are.");
  m.def(
      "combine",
      [](const std::vector<StrictScore>& scores) {
        for (const auto& s : scores)
          if (s.tolerance_ms != scores.front().tolerance_ms)
            value_error("scores: expected one tolerance, got " + format_or_na(scores.front().tolerance_ms, "%.0f") + " and " +
                        format_or_na(s.tolerance_ms, "%.0f") + " ms");
        return combine(std::span<const StrictScore>(scores));
      },
      "scores"_a, "StrictScores of several trials pooled: counts summed, rates and latencies from all matches.");
  pb::class_<StillSegment>(m, "StillSegment", "A still stretch of a trial (both feet in contact, ground truth) and its false steps.")
      .def_readonly("begin", &StillSegment::begin, "seconds")
      .def_readonly("end", &StillSegment::end, "seconds")
      .def_readonly("false_steps", &StillSegment::false_steps, "detected foot-offs inside that match no true one")
      .def("__repr__", [](const StillSegment& g) {
        char buf[120];
        std::snprintf(buf, sizeof buf, "StillSegment(begin=%.3f, end=%.3f, false_steps=%d)", g.begin, g.end, g.false_steps);
        return std::string(buf);
      });
  m.def(
      "still_segments",
      [check_window](const Motion& motion, const std::vector<SwingEvent>& detected, double t_begin, double t_end,
                     double min_duration, double tolerance) {
        check_window(tolerance, t_begin, t_end);
        require_seconds(min_duration, "min_duration");
        ContactOptions truth;
        truth.end_swings = true;
        const auto unmatched = unmatched_detections(detected, foot_swings(motion, truth), tolerance);
        return still_segments(motion, "", truth, unmatched, min_duration, t_begin, t_end);
      },
      "motion"_a, "detected"_a, "t_begin"_a, "t_end"_a, "min_duration"_a = 1.0, "tolerance"_a = 0.2,
      "The still stretches of a walk, as `legwork wip eval` scores false steps: both feet in contact (the truth of\n"
      "legwork.wip.foot_swings) for at least min_duration seconds within [t_begin, t_end], each with the detected\n"
      "foot-offs inside that match no true one within +-tolerance. False steps per minute = their sum over the\n"
      "segments' minutes.");
  m.def(
      "score_steps",
      [](const std::vector<SwingEvent>& detected, const std::vector<SwingEvent>& truth, double t_begin, double t_end) {
        return score_steps(detected, truth, t_begin, t_end);
      },
      "detected"_a, "truth"_a, "t_begin"_a, "t_end"_a,
        "The lenient overlap score (a secondary figure; match_foot_offs is the field's): swings of the same foot\n"
        "whose intervals overlap are matched one to one, however late; swings outside [t_begin, t_end] seconds are\n"
        "ignored. truth: legwork.wip.foot_swings(motion).");
  m.def(
      "evaluate_combined",
      [](const std::vector<std::string>& files, const std::string& database, const std::string& wip_table, double rate) {
        require_rate(rate, "rate");
        CombinedEvalRun run;
        run.files = files;
        run.database = database;
        run.wip_table = wip_table;
        run.rate = rate;
        const auto report = evaluate_combined(run);
        return pb::module_::import("json").attr("loads")(report.dump());
      },
      "files"_a, "database"_a = "", "wip_table"_a = "", "rate"_a = 30.0,
      "One avatar, two sources, scored on walking BVH trials as `legwork eval combined` does: the IK avatar,\n"
      "the combined avatar (document's and learned legs), and with `database` (.lwdb) accentuation and the\n"
      "combined avatar with an accentuated upper body. wip_table: a learned table for the learned-legs rows\n"
      "(default: each trial's learned from the other subjects among `files`). Returns report.json's dict:\n"
      "'methods' (frame-weighted means of full_body_cm, lower_body_cm, left/right_hand_cm, foot_skating_cm),\n"
      "'trials', 'skipped', 'truth_foot_skating_cm'. legwork.Error for no trials or a bad database/table.");
}

}  // namespace eval_binding
}  // namespace

void bind_eval(pb::module_& m) {
  using namespace eval_binding;  // its helpers and the module names they use
  bind_track(m);
  bind_metrics(m);
  bind_steps(m);
}

}  // namespace legwork::py

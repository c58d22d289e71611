// legwork.wip: walking-in-place legs on the per-frame contract.
#include "bindings.hpp"

#include <legwork/core/contacts.hpp>
#include <legwork/wip/offline/learn.hpp>
#include <legwork/wip/offline/run.hpp>
#include <legwork/wip/offline/synthetic.hpp>
#include <legwork/wip/wip.hpp>

#include <cmath>
#include <cstdio>

namespace legwork::py {
namespace {
namespace wip_binding {

using namespace pybind11::literals;
using namespace legwork::wip;

template <class T>
pb::tuple pair(const T (&a)[2]) {
  return pb::make_tuple(a[0], a[1]);
}

void bind_settings(pb::module_& m) {
  pb::class_<SignalSettings>(m, "SignalSettings", "Ankle-height signal filtering.")
      .def(pb::init<>())
      .def_readwrite("rate", &SignalSettings::rate, "nominal tracker rate, Hz")
      .def_readwrite("cutoff", &SignalSettings::cutoff, "low-pass cutoff, Hz")
      .def_readwrite("order", &SignalSettings::order)
      .def_readwrite("buffer_seconds", &SignalSettings::buffer_seconds)
      .def_readwrite("confidence_tau", &SignalSettings::confidence_tau, "seconds")
      .def_readwrite("floor_tau", &SignalSettings::floor_tau, "seconds; 0 = fixed floor")
      .def_readwrite("detect_cutoff", &SignalSettings::detect_cutoff, "adaptive detector: low-pass of its signal, Hz")
      .def_readwrite("baseline_tau", &SignalSettings::baseline_tau, "adaptive detector: stance baseline, seconds")
      .def_readwrite("noise_tau", &SignalSettings::noise_tau, "adaptive detector: tracker jitter estimate, seconds");
  pb::enum_<StepDetector>(m, "StepDetector", "Foot-off detection: the document's thresholds or the adaptive detector.")
      .value("Document", StepDetector::Document)
      .value("Adaptive", StepDetector::Adaptive);
  pb::class_<GaitSettings>(m, "GaitSettings", "Gait-phase thresholds (metres, m/s, seconds).")
      .def(pb::init<>())
      .def_readwrite("h1", &GaitSettings::h1)
      .def_readwrite("v1", &GaitSettings::v1)
      .def_readwrite("v2", &GaitSettings::v2)
      .def_readwrite("land_fraction", &GaitSettings::land_fraction)
      .def_readwrite("min_stance_time", &GaitSettings::min_stance_time)
      .def_readwrite("max_ascent_time", &GaitSettings::max_ascent_time)
      .def_readwrite("lost_confidence", &GaitSettings::lost_confidence)
      .def_readwrite("adaptive", &GaitSettings::adaptive)
      .def_readwrite("detector", &GaitSettings::detector, "legwork.wip.StepDetector")
      .def_readwrite("lift_fraction", &GaitSettings::lift_fraction)
      .def_readwrite("rise_fraction", &GaitSettings::rise_fraction)
      .def_readwrite("noise_factor", &GaitSettings::noise_factor)
      .def_readwrite("rise_noise_factor", &GaitSettings::rise_noise_factor)
      .def_readwrite("min_lift", &GaitSettings::min_lift, "metres")
      .def_readwrite("min_rise", &GaitSettings::min_rise, "m/s")
      .def_readwrite("rest_time", &GaitSettings::rest_time,
                     "seconds both feet down before the start-step thresholds apply (0 = off)")
      .def_readwrite("rest_lift", &GaitSettings::rest_lift, "start steps: lowest foot-off height, metres")
      .def_readwrite("rest_rise", &GaitSettings::rest_rise, "start steps: lowest foot-off speed, m/s")
      .def_readwrite("rest_noise_factor", &GaitSettings::rest_noise_factor,
                     "start steps: foot-off height >= this x the tracker jitter")
      .def_readwrite("settle_time", &GaitSettings::settle_time,
                     "seconds of steady height in terminal swing that count as landed (0 = off)")
      .def_readwrite("min_swing_time", &GaitSettings::min_swing_time,
                     "seconds after a foot-off before the swing can land (0 = off)");
  pb::enum_<SpeedModel>(m, "SpeedModel").value("StepSpeed", SpeedModel::StepSpeed).value("StepFrequency", SpeedModel::StepFrequency);
  pb::enum_<DepthMapping>(m, "DepthMapping", "Fore-aft IK-target depths: the document's equations or the learned table.")
      .value("Document", DepthMapping::Document)
      .value("Learned", DepthMapping::Learned);
  pb::class_<MappingSettings>(m, "MappingSettings", "Step mapping onto the avatar (metres, seconds, m/s).")
      .def(pb::init<>())
      .def_readwrite("depth", &MappingSettings::depth, "legwork.wip.DepthMapping (Learned needs a table in make_model)")
      .def_readwrite("reference_leg", &MappingSettings::reference_leg)
      .def_readwrite("step_length", &MappingSettings::step_length)
      .def_readwrite("user_step_height", &MappingSettings::user_step_height)
      .def_readwrite("lift_scale", &MappingSettings::lift_scale)
      .def_readwrite("stop_time", &MappingSettings::stop_time)
      .def_readwrite("speed_model", &MappingSettings::speed_model)
      .def_readwrite("speed_gain", &MappingSettings::speed_gain)
      .def_readwrite("max_speed", &MappingSettings::max_speed);
  pb::class_<Settings>(m, "Settings", "Walking-in-place options (legwork::wip::Settings): signal, gait, mapping.")
      .def(pb::init<>())
      .def_readwrite("signal", &Settings::signal)
      .def_readwrite("gait", &Settings::gait)
      .def_readwrite("mapping", &Settings::mapping);
}

void bind_runtime(pb::module_& m) {
  pb::enum_<GaitPhase>(m, "GaitPhase")
      .value("DoubleSupport", GaitPhase::DoubleSupport)
      .value("InitialSwing", GaitPhase::InitialSwing)
      .value("MidSwing", GaitPhase::MidSwing)
      .value("TerminalSwing", GaitPhase::TerminalSwing);
  auto [model, state] = def_model_state<Model, State>(m, &reset, "Immutable walking-in-place model of an avatar skeleton (copied).",
                                                      "One avatar's memory between frames (filters, gait machines, floor).");
  state.def_readonly("calibrated", &State::calibrated);
  model.def_property_readonly("leg_length", &Model::leg_length, "metres")
      .def_property_readonly("root_height", &Model::root_height, "standing root height above the floor, metres");
  pb::class_<LearnedMapping>(m, "LearnedMapping", "Depth table learned from real walks (legwork wip learn).")
      .def_readonly("apex_mean", &LearnedMapping::apex_mean, "metres")
      .def_readonly("amplitude_intercept", &LearnedMapping::amplitude_intercept, "depth amplitude / leg at apex 0")
      .def_readonly("amplitude_slope", &LearnedMapping::amplitude_slope, "depth amplitude / leg per metre of apex")
      .def("amplitude", &LearnedMapping::amplitude, "apex"_a, "cadence"_a,
           "depth amplitude / leg length for a step apex (m) and cadence (strides/s)")
      .def_readonly("turn_intercept", &LearnedMapping::turn_intercept, "the depth's gain while not turning")
      .def_readonly("turn_slope", &LearnedMapping::turn_slope, "its change per rad/s of the head's smoothed turn rate")
      .def("turn_gain", &LearnedMapping::turn_gain, "turn_rate"_a,
           "the depth's gain at a smoothed head turn rate (rad/s), clamped to [0, 2]: steps shorten in turns")
      .def_readonly("samples", &LearnedMapping::samples)
      .def("lookup", &LearnedMapping::lookup, "own"_a, "other"_a, "lead"_a, "since"_a,
           "depth / amplitude for cycle coordinates own, other (0..2); lead 1 = this foot landed last, 0 not, -1 unknown;\n"
           "since: seconds since that landing");
  m.def("read_learned_mapping", &read_learned_mapping, "path"_a,
        "The learned table file (data/wip/learned_mapping.txt); legwork.Error naming the line and field.");
  m.def(
      "make_model",
      [](const Skeleton& s, const Settings& st, const LearnedMapping* learned) { return make_model(s, st, {}, learned); },
      "avatar"_a, "settings"_a = Settings{}, "learned"_a = nullptr,
      "Model from an avatar skeleton with legs; legwork.Error naming missing roles. learned: the table for\n"
      "settings.mapping.depth = DepthMapping.Learned (legwork.wip.read_learned_mapping).");
  m.def("step_speed_gain", &step_speed_gain, "settings"_a,
        "The step-speed model's gain: settings.mapping.speed_gain when > 0, else the detector's calibrated gain.");
  m.def("set_floor", &set_floor, "state"_a, "left"_a, "right"_a, "Tracker-space floor height under each ankle, metres.");
  def_fields(pb::class_<Info>(m, "Info", "Per-frame diagnostics ([left, right] pairs).")
      .def(pb::init<>())
      .def_readonly("time", &Info::time, "seconds")
      .def_property_readonly("phase", [](const Info& i) { return pair(i.phase); })
      .def_property_readonly("h", [](const Info& i) { return pair(i.h); }, "filtered ankle height above the floor, metres")
      .def_property_readonly("v", [](const Info& i) { return pair(i.v); }, "its velocity, m/s")
      .def_property_readonly("z", [](const Info& i) { return pair(i.z); }, "IK-target depth, metres (forward +)")
      .def_property_readonly("y", [](const Info& i) { return pair(i.y); }, "IK-target height, metres")
      .def_readonly("speed", &Info::speed, "forward speed, m/s")
      .def_readonly("distance", &Info::distance, "distance walked, metres")
      .def_readonly("heading", &Info::heading, "radians, 0 = +z")
      .def_readonly("turn_rate", &Info::turn_rate, "the head yaw's speed, rad/s, smoothed (the learned mapping shortens steps in turns)")
      .def_readonly("walking", &Info::walking));
  def_update(m, &update,
             "One frame: the feet devices' heights in (the head's yaw steers when usable); `out` (a legwork.core.Pose\n"
             "of model.skeleton()) written; returns legwork.core.UpdateStatus. out=None advances the gait, the\n"
             "IK targets and `info` exactly as with a pose but does not solve the legs (about a quarter of the time):\n"
             "for step detection and depth studies that need no body.",
             /*pose_optional=*/true);
}

// Whole clips (legwork/wip/offline/run.hpp): what `legwork wip` and `legwork
// wip eval` run, for researchers scoring detectors from Python.
struct PyRun {
  pb::object frames, motion;
  FloorCalibration calibration;
};

void bind_offline(pb::module_& m) {
  pb::class_<FloorCalibration>(m, "FloorCalibration", "Floor calibration from standing still (legwork.wip.calibrate_floor).")
      .def_readonly("ok", &FloorCalibration::ok)
      .def_property_readonly("floor", [](const FloorCalibration& c) { return pair(c.floor); }, "(left, right) ankle heights, metres")
      .def_property_readonly("spread", [](const FloorCalibration& c) { return pair(c.spread); }, "(left, right) std of the height, metres")
      .def_readonly("message", &FloorCalibration::message, "what was calibrated, or why not");
  m.def(
      "calibrate_floor",
      [](const std::vector<TrackerFrame>& frames, double seconds, double max_std) {
        require_seconds(seconds, "seconds");
        if (!(std::isfinite(max_std) && max_std > 0)) value_error("max_std: expected a positive height spread in metres, got " + std::to_string(max_std));
        return calibrate_floor(frames, seconds, max_std);
      },
      "frames"_a, "seconds"_a = 3.0, "max_std"_a = 0.03,
      "Each ankle's mean height over the first `seconds` of a list of legwork.core.TrackerFrame; ok = False (message\n"
      "says why) when an ankle's height varies by more than max_std metres or too few samples are usable.");
  // Run's frames and motion become Python objects once, when the run returns
  // (a def_readonly vector would be copied into a new list at every read).
  pb::class_<PyRun>(m, "Run", "A clip run through one avatar (legwork.wip.run).")
      .def_readonly("frames", &PyRun::frames, "list of legwork.wip.Info, one per consumed (not rejected) frame")
      .def_readonly("motion", &PyRun::motion,
                    "the avatar at those frames (legwork.core.Motion at settings.signal.rate), None when run with keep_poses=False")
      .def_readonly("calibration", &PyRun::calibration, "the floor calibration (ok = False when not calibrated)")
      .def("__len__", [](const PyRun& r) { return pb::len(r.frames); });
  m.def(
      "run",
      [](const Model& model, const std::vector<TrackerFrame>& frames, bool calibrate, double calibration_seconds, bool keep_poses) {
        if (calibrate) require_seconds(calibration_seconds, "calibration_seconds");
        RunOptions opt;
        opt.calibrate = calibrate;
        opt.calibration_seconds = calibration_seconds;
        opt.keep_poses = keep_poses;
        Run run;
        {
          pb::gil_scoped_release release;
          run = run_wip(model, frames, opt);
        }
        PyRun out;
        out.frames = pb::cast(std::move(run.frames));
        out.motion = keep_poses ? pb::cast(std::move(run.motion)) : pb::none();
        out.calibration = std::move(run.calibration);
        return out;
      },
      "model"_a, "frames"_a, "calibrate"_a = true, "calibration_seconds"_a = 3.0, "keep_poses"_a = true,
      "One avatar over a list of legwork.core.TrackerFrame, as `legwork wip` runs a clip: the floor calibrated from\n"
      "the first calibration_seconds of standing (legwork.Error naming the ankle when the user is not still; pass\n"
      "calibrate=False for a rolling floor, as `legwork wip eval` does on real walks), then update() per frame.\n"
      "keep_poses=False does not solve the legs (Run.motion is None; every Info is the same).");
  m.def(
      "add_tracker_noise",
      [](std::vector<TrackerFrame> frames, double noise, double drop_rate, std::uint64_t seed) {
        if (!(std::isfinite(noise) && noise >= 0)) value_error("noise: expected a jitter >= 0 metres, got " + std::to_string(noise));
        if (!(drop_rate >= 0 && drop_rate <= 1)) value_error("drop_rate: expected a fraction in [0, 1], got " + std::to_string(drop_rate));
        add_tracker_noise(frames, noise, drop_rate, seed);
        return frames;
      },
      "frames"_a, "noise"_a = 0.015, "drop_rate"_a = 0.02, "seed"_a = 1,
      "A copy of the frames with seeded Kinect-like corruption of the feet: Gaussian jitter (metres, per coordinate)\n"
      "and dropped samples (valid = False), as `legwork wip eval`'s noisy run (its seed: seed x 1000003 + the\n"
      "trial's index).");
}

}  // namespace wip_binding
}  // namespace

void bind_wip(pb::module_& m) {
  using namespace wip_binding;  // its helpers and the module names they use
  bind_settings(m);
  bind_runtime(m);
  bind_offline(m);
  pb::class_<SwingEvent>(m, "SwingEvent",
                         "One swing of a foot: foot (0 left, 1 right), off/strike times (s), apex (m), cut (the clip ended\n"
                         "mid-swing). Made by foot_swings / legwork.eval.detected_swings, or by hand to score another detector.")
      .def(pb::init([](int foot, double off, double strike, double apex, bool cut) {
             if (foot != 0 && foot != 1) value_error("foot: expected 0 (left) or 1 (right), got " + std::to_string(foot));
             if (!(std::isfinite(off) && std::isfinite(strike) && strike >= off))
               value_error("off, strike: expected finite seconds with strike >= off, got " + std::to_string(off) + ", " +
                           std::to_string(strike));
             return SwingEvent{foot, off, strike, apex, cut};
           }),
           "foot"_a, "off"_a, "strike"_a, "apex"_a = 0.0, "cut"_a = false)
      .def_readonly("foot", &SwingEvent::foot)
      .def_readonly("off", &SwingEvent::off)
      .def_readonly("strike", &SwingEvent::strike)
      .def_readonly("apex", &SwingEvent::apex)
      .def_readonly("cut", &SwingEvent::cut)
      .def("__repr__", [](const SwingEvent& e) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "SwingEvent(foot=%d, off=%.4f, strike=%.4f, apex=%.4f%s)", e.foot, e.off, e.strike,
                      e.apex, e.cut ? ", cut=True" : "");
        return std::string(buf);
      });
  m.def(
      "foot_swings",
      [](const Motion& mo, bool end_swings) {
        ContactOptions opt;
        opt.end_swings = end_swings;
        return foot_swings(mo, opt);
      },
      "motion"_a, "end_swings"_a = false,
      "Ground-truth swings of a walking motion (toe off to first contact; each foot's stance height learned from\n"
      "the trial). end_swings=True also gives a last swing the clip's end cuts (strike = the clip's end, cut set):\n"
      "the truth `legwork wip eval` scores foot-offs against (legwork.eval.match_foot_offs).");
}

}  // namespace legwork::py

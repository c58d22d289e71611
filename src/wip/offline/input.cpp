#include <legwork/wip/offline/input.hpp>

#include <legwork/io/tracker_csv.hpp>
#include <legwork/wip/offline/run.hpp>
#include <legwork/core/contacts.hpp>

#include <cstdio>

namespace legwork::wip {

TrackerInput tracker_input_from_csv(const std::string& path) {
  TrackerInput in;
  const auto table = io::read_tracker_csv(path);
  in.frames = io::frames_from_table(table, path, {Device::LeftFoot, Device::RightFoot});
  in.rate = median_rate(in.frames, path);
  in.what = "tracker CSV " + path;
  return in;
}

TrackerInput tracker_input_from_motion(const Motion& m, const std::string& name, double rate) {
  const auto& r = m.skeleton.roles;
  if (!r.has(Role::LeftAnkle) || !r.has(Role::RightAnkle))
    throw Error(name + ": motion has no ankle joints (roles LeftAnkle/RightAnkle unresolved): cannot use it as a tracker");
  TrackerInput in;
  in.frames = tracker_frames_from_motion(m, rate);
  if (in.frames.empty()) throw Error(name + ": the motion has no frames to track");
  in.truth = foot_swings(m, {.end_swings = true});  // scored by foot-off: a swing the clip's end cuts was taken
  in.rate = rate;
  in.still_start = false;
  in.what = "ankles of " + name + " (" + std::to_string(m.frame_count()) + " frames, sampled at " +
            std::to_string(static_cast<int>(rate)) + " Hz)";
  return in;
}

TrackerInput tracker_input_synthetic(const SyntheticOptions& o) {
  TrackerInput in;
  auto tr = synthetic_stepping(o);
  in.frames = std::move(tr.frames);
  in.truth = std::move(tr.swings);
  in.rate = o.rate;
  char buf[200];
  std::snprintf(buf, sizeof buf, "synthetic in-place stepping (%.1f steps/s, %.2f m lift, noise %.1f cm, seed %llu)",
                o.cadence, o.step_height, 100 * o.noise, static_cast<unsigned long long>(o.seed));
  in.what = buf;
  return in;
}

}  // namespace legwork::wip

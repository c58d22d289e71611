#include <legwork/wip/offline/run.hpp>
#include <legwork/core/stats.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace legwork::wip {

namespace {

// Mean and std of one ankle's usable heights over the first `seconds`;
// n = usable samples, total = samples in the window.
struct HeightStats {
  double mean = 0, spread = 0;
  int n = 0, total = 0;
};
HeightStats height_stats(std::span<const TrackerFrame> frames, int f, double seconds) {
  HeightStats s;
  const double t0 = frames.front().time;
  double sum = 0, sum2 = 0;
  for (const auto& fr : frames) {
    if (fr.time - t0 > seconds) break;
    ++s.total;
    if (!usable(fr.foot(f))) continue;
    const double y = fr.foot(f).position.y();
    sum += y;
    sum2 += y * y;
    ++s.n;
  }
  if (s.n > 0) {
    s.mean = sum / s.n;
    s.spread = std::sqrt(std::max(0.0, sum2 / s.n - s.mean * s.mean));
  }
  return s;
}

}  // namespace

FloorCalibration calibrate_floor(std::span<const TrackerFrame> frames, double seconds, double max_std) {
  FloorCalibration c;
  if (frames.empty()) {
    c.message = "no tracker samples to calibrate the floor from";
    return c;
  }
  for (int f = 0; f < 2; ++f) {
    const HeightStats s = height_stats(frames, f, seconds);
    const char* side = f == 0 ? "left" : "right";
    if (s.n < std::max(3, s.total / 2)) {
      c.message = std::string("cannot calibrate the floor: only ") + std::to_string(s.n) + " of " + std::to_string(s.total) +
                  " " + side + " ankle samples in the first " + std::to_string(seconds).substr(0, 4) + " s are valid";
      return c;
    }
    c.floor[f] = s.mean;
    c.spread[f] = s.spread;
  }
  for (int f = 0; f < 2; ++f)
    if (c.spread[f] > max_std) {
      char buf[320];
      std::snprintf(buf, sizeof buf,
                    "cannot calibrate the floor: the user is not standing still during the first %.1f s "
                    "(%s ankle height varies by %.1f cm std, limit %.1f cm). Stand still for the calibration, "
                    "or skip it (rolling floor).",
                    seconds, f == 0 ? "left" : "right", 100 * c.spread[f], 100 * max_std);
      c.message = buf;
      return c;
    }
  c.ok = true;
  char buf[160];
  std::snprintf(buf, sizeof buf, "floor calibrated over %.1f s: ankle heights %.3f / %.3f m (std %.1f / %.1f cm)", seconds,
                c.floor[0], c.floor[1], 100 * c.spread[0], 100 * c.spread[1]);
  c.message = buf;
  return c;
}

Run run_wip(const Model& model, std::span<const TrackerFrame> frames, const RunOptions& opt) {
  Run run;
  State state(model);
  if (opt.calibrate) {
    run.calibration = calibrate_floor(frames, opt.calibration_seconds);
    if (!run.calibration.ok) throw Error(run.calibration.message);
    set_floor(state, run.calibration.floor[0], run.calibration.floor[1]);
  }
  run.frames.reserve(frames.size());
  if (opt.keep_poses) run.motion = Motion(model.skeleton(), model.settings().signal.rate, 0);
  // Without poses to keep, the legs are not solved (update() with an empty pose).
  Pose pose = opt.keep_poses ? Pose(model.skeleton()) : Pose();
  Info info;
  for (const auto& fr : frames) {
    if (update(model, fr, state, pose.ref(), &info) == UpdateStatus::Rejected) continue;
    run.frames.push_back(info);
    if (opt.keep_poses) run.motion.push_back(pose);
  }
  return run;
}

double median_rate(std::span<const TrackerFrame> frames, const std::string& source) {
  if (frames.size() < 3) throw Error(source + ": fewer than 3 samples");
  std::vector<double> dts;
  for (std::size_t i = 1; i < frames.size(); ++i) dts.push_back(frames[i].time - frames[i - 1].time);
  const double dt = median(std::move(dts));
  if (!(dt > 0) || !std::isfinite(1.0 / dt)) throw Error(source + ": cannot tell the sample rate (median time step " +
                                                         std::to_string(dt) + " s)");
  return 1.0 / dt;
}

std::string format_info_csv(std::span<const Info> frames) {
  std::ostringstream o;
  o << "time,phase_left,phase_right,h_left,h_right,v_left,v_right,confidence_left,confidence_right,h1_left,h1_right,"
       "z_target_left,z_target_right,z_left,z_right,y_left,y_right,root_offset,speed,distance,walking,events_left,"
       "events_right,root_x,root_y,root_z\n";
  char buf[512];
  for (const auto& f : frames) {
    std::snprintf(buf, sizeof buf,
                  "%.4f,%s,%s,%.5f,%.5f,%.4f,%.4f,%.3f,%.3f,%.4f,%.4f,%.5f,%.5f,%.5f,%.5f,%.5f,%.5f,%.5f,%.4f,%.4f,%d,%u,%u,"
                  "%.4f,%.4f,%.4f\n",
                  f.time, std::string(phase_name(f.phase[0])).c_str(), std::string(phase_name(f.phase[1])).c_str(), f.h[0],
                  f.h[1], f.v[0], f.v[1], f.confidence[0], f.confidence[1], f.h1[0], f.h1[1], f.z_target[0],
                  f.z_target[1], f.z[0], f.z[1], f.y[0], f.y[1], f.root_offset, f.speed, f.distance, f.walking ? 1 : 0,
                  f.events[0], f.events[1], f.root_position.x(), f.root_position.y(), f.root_position.z());
    o << buf;
  }
  return o.str();
}

}  // namespace legwork::wip

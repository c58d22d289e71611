#include <legwork/wip/tracker.hpp>

#include <legwork/core/fk.hpp>
#include <legwork/core/interpolate.hpp>

#include <algorithm>
#include <cmath>
#include <random>

namespace legwork::wip {

namespace {

const io::TrackedPoint* find_point(const io::TrackerTable& t, std::initializer_list<const char*> names) {
  for (const char* n : names)
    for (const auto& p : t.points)
      if (p.name == n) return &p;
  return nullptr;
}

bool finite(const Vec3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

}  // namespace

std::vector<TrackerSample> samples_from_table(const io::TrackerTable& table, const std::string& source) {
  const io::TrackedPoint* pts[2] = {
      find_point(table, {"left_ankle", "left_foot", "ankle_l", "l_ankle", "LeftAnkle", "LeftFoot"}),
      find_point(table, {"right_ankle", "right_foot", "ankle_r", "r_ankle", "RightAnkle", "RightFoot"})};
  if (!pts[0] || !pts[1]) {
    std::string names;
    for (const auto& p : table.points) names += (names.empty() ? "" : ", ") + p.name;
    throw Error(source + ": walking-in-place needs columns for the points 'left_ankle' and 'right_ankle' (" +
                std::string(!pts[0] ? "left" : "right") + " missing); points present: " +
                (names.empty() ? "none" : names));
  }
  std::vector<TrackerSample> out(static_cast<std::size_t>(table.sample_count()));
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (i > 0 && !(table.time[i] > table.time[i - 1]))
      throw Error(source + ": time is not strictly increasing at sample " + std::to_string(i));
    out[i].time = table.time[i];
    for (int f = 0; f < 2; ++f) {
      const auto& p = *pts[f];
      out[i].ankle[f] = p.position[i];
      out[i].valid[f] = (i < p.valid.size() ? p.valid[i] != 0 : true) && finite(p.position[i]);
    }
  }
  return out;
}

io::TrackerTable table_from_samples(const std::vector<TrackerSample>& samples) {
  io::TrackerTable t;
  t.points.resize(2);
  t.points[0].name = "left_ankle";
  t.points[1].name = "right_ankle";
  for (const auto& s : samples) {
    t.time.push_back(s.time);
    for (int f = 0; f < 2; ++f) {
      const double nan = std::nan("");
      t.points[static_cast<std::size_t>(f)].position.push_back(s.valid[f] ? s.ankle[f] : Vec3(nan, nan, nan));
      t.points[static_cast<std::size_t>(f)].valid.push_back(s.valid[f] ? 1 : 0);
    }
  }
  return t;
}

std::vector<TrackerSample> samples_from_motion(const Motion& m, double rate) {
  const auto& r = m.skeleton.roles;
  if (!r.has(Role::LeftAnkle) || !r.has(Role::RightAnkle))
    throw Error("motion has no ankle joints (roles LeftAnkle/RightAnkle unresolved): cannot use it as a tracker");
  const int ja[2] = {r[Role::LeftAnkle], r[Role::RightAnkle]};
  Pose pose(m.skeleton);
  std::vector<Vec3> pos(static_cast<std::size_t>(m.joint_count()));
  const int n = static_cast<int>(std::floor(m.duration() * rate + 1e-9)) + 1;
  std::vector<TrackerSample> out(static_cast<std::size_t>(std::max(n, 0)));
  for (int i = 0; i < n; ++i) {
    const double t = i / rate;
    sample_motion(m, t, pose.ref());
    forward_positions(m.skeleton, pose, pos);
    auto& s = out[static_cast<std::size_t>(i)];
    s.time = t;
    for (int f = 0; f < 2; ++f) s.ankle[f] = pos[static_cast<std::size_t>(ja[f])];
  }
  return out;
}

SyntheticTrack synthetic_stepping(const SyntheticOptions& o) {
  if (!(o.rate > 0) || !(o.duration > 0) || !(o.cadence > 0))
    throw Error("synthetic stepping: rate, duration and cadence must be positive");
  SyntheticTrack tr;
  std::mt19937_64 rng(o.seed);
  std::normal_distribution<double> jitter(0.0, 1.0);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const double step_period = 1.0 / o.cadence;
  const double swing = std::clamp(o.swing_fraction, 0.1, 1.6) * step_period;
  const double lift[2] = {o.step_height, o.step_height * (1.0 - o.asymmetry)};
  auto paused = [&](double t0, double t1) {
    return o.pause_length > 0 && t1 > o.pause_start && t0 < o.pause_start + o.pause_length;
  };
  // Swings alternate left, right, ...; a swing overlapping a pause is skipped.
  int foot = kLeft;
  for (double t0 = o.stand_time; t0 + swing < o.duration; t0 += step_period) {
    if (paused(t0, t0 + swing)) {
      foot = kLeft;  // resume with the left foot, like a fresh start
      continue;
    }
    tr.swings.push_back({foot, t0, t0 + swing, lift[foot]});
    foot = 1 - foot;
  }
  const int n = static_cast<int>(std::floor(o.duration * o.rate)) + 1;
  tr.samples.resize(static_cast<std::size_t>(n));
  std::size_t next[2] = {0, 0};
  for (int i = 0; i < n; ++i) {
    const double t = i / o.rate;
    TrackerSample& s = tr.samples[static_cast<std::size_t>(i)];
    s.time = t;
    for (int f = 0; f < 2; ++f) {
      double h = 0;
      for (std::size_t k = next[f]; k < tr.swings.size(); ++k) {
        const auto& sw = tr.swings[k];
        if (sw.foot != f) continue;
        if (sw.off > t) break;
        if (t <= sw.strike) {
          // Quick lift, slower lowering: the phase is skewed toward early swing.
          const double u = (t - sw.off) / (sw.strike - sw.off);
          const double w = std::pow(u, 0.8);
          h = sw.apex * std::pow(std::sin(kPi * w), 2);
          break;
        }
        next[f] = k + 1;
      }
      const double side = f == kLeft ? 0.5 : -0.5;
      s.ankle[f] = Vec3(side * o.stance_width + o.noise * jitter(rng), o.floor_y + o.ankle_height + h + o.noise * jitter(rng),
                        0.02 * h + o.noise * jitter(rng));
      s.valid[f] = true;
      if (uni(rng) < o.drop_rate) s.valid[f] = false;
      if (uni(rng) < o.nan_rate) {
        s.valid[f] = false;
        s.ankle[f] = Vec3::Constant(std::nan(""));
      }
    }
  }
  return tr;
}

void add_tracker_noise(std::vector<TrackerSample>& samples, double noise, double drop_rate, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> jitter(0.0, 1.0);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (auto& s : samples)
    for (int f = 0; f < 2; ++f) {
      s.ankle[f] += noise * Vec3(jitter(rng), jitter(rng), jitter(rng));
      if (uni(rng) < drop_rate) s.valid[f] = false;
    }
}

}  // namespace legwork::wip

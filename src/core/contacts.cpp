#include <legwork/core/contacts.hpp>

#include <legwork/core/fk.hpp>
#include <legwork/core/series.hpp>
#include <legwork/core/stats.hpp>

#include <algorithm>
#include <cmath>

namespace legwork {
namespace {

struct JointTrack {
  std::vector<double> y, speed;
};

// Height and speed (over +-10 ms) of joint `j` in every frame.
JointTrack track(const Motion& m, const std::vector<Vec3>& pos, int j) {
  const int n = m.frame_count(), nj = m.joint_count();
  auto at = [&](int f) { return pos[static_cast<std::size_t>(f) * static_cast<std::size_t>(nj) + static_cast<std::size_t>(j)]; };
  const int k = std::max(1, static_cast<int>(std::lround(0.01 * m.fps)));
  JointTrack t;
  t.y.resize(static_cast<std::size_t>(n));
  t.speed.resize(static_cast<std::size_t>(n));
  for (int f = 0; f < n; ++f) {
    const int a = std::max(0, f - k), b = std::min(n - 1, f + k);
    t.y[static_cast<std::size_t>(f)] = at(f).y();
    t.speed[static_cast<std::size_t>(f)] = (at(b) - at(a)).norm() / ((b - a) / m.fps);
  }
  return t;
}

// The former detector: within height_tol of a rolling floor and slow.
std::vector<char> contact_fixed(const JointTrack (&parts)[2], double fps, const ContactOptions& p) {
  const std::size_t n = parts[0].y.size();
  const int w = std::max(1, static_cast<int>(std::lround(p.floor_window * fps)));
  std::vector<char> contact(n, 0);
  for (const auto& t : parts) {
    const auto floor = rolling_min(t.y, w);
    for (std::size_t f = 0; f < n; ++f)
      if (t.y[f] - floor[f] < p.height_tol && t.speed[f] < p.speed_tol) contact[f] = 1;
  }
  return contact;
}

// Floor under a joint that follows a drifting floor without lag: the median
// height of its slow (resting) frames within +-w frames; where none is slow,
// its rolling minimum.
std::vector<double> resting_floor(const JointTrack& t, int w, double speed_tol) {
  const int n = static_cast<int>(t.y.size());
  const auto fallback = rolling_min(t.y, w);
  std::vector<double> floor(t.y.size()), window;
  for (int f = 0; f < n; ++f) {
    window.clear();
    for (int k = std::max(0, f - w); k <= std::min(n - 1, f + w); ++k)
      if (t.speed[static_cast<std::size_t>(k)] < speed_tol) window.push_back(t.y[static_cast<std::size_t>(k)]);
    floor[static_cast<std::size_t>(f)] = window.empty() ? fallback[static_cast<std::size_t>(f)] : percentile(window, 0.5);
  }
  return floor;
}

// Per-joint stance height and lift range learned from the trial, with hysteresis.
std::vector<char> contact_learned(const JointTrack (&parts)[2], double fps, const ContactOptions& p) {
  const std::size_t n = parts[0].y.size();
  const int w = std::max(1, static_cast<int>(std::lround(p.floor_window * fps)));
  std::vector<double> above[2];
  double off[2], on[2];
  for (int i = 0; i < 2; ++i) {
    const auto floor = resting_floor(parts[i], w, p.speed_tol);
    above[i].resize(n);
    for (std::size_t f = 0; f < n; ++f) above[i][f] = parts[i].y[f] - floor[f];
    const double stance = percentile(above[i], p.stance_percentile);
    const double range = percentile(above[i], p.lift_percentile) - stance;
    off[i] = stance + std::max(p.lift_off * range, p.min_lift_off);
    on[i] = stance + std::max(p.lift_on * range, p.min_lift_on);
  }
  std::vector<char> contact(n, 0);
  bool down = true;
  for (std::size_t f = 0; f < n; ++f) {
    if (down) {
      down = above[0][f] <= off[0] || above[1][f] <= off[1];
    } else {
      for (int i = 0; i < 2; ++i) down = down || (above[i][f] < on[i] && parts[i].speed[f] < p.speed_tol);
    }
    contact[f] = down ? 1 : 0;
  }
  return contact;
}

// Touch-downs shorter than min_stance (inside the clip) do not split a swing.
void fill_short_stances(std::vector<char>& contact, int min_stance) {
  const int n = static_cast<int>(contact.size());
  for (int f = 0; f < n;) {
    if (!contact[static_cast<std::size_t>(f)]) { ++f; continue; }
    int e = f;
    while (e < n && contact[static_cast<std::size_t>(e)]) ++e;
    if (f > 0 && e < n && e - f < min_stance) std::fill(contact.begin() + f, contact.begin() + e, 0);
    f = e;
  }
}

}  // namespace

std::array<std::vector<char>, 2> foot_contacts(const Motion& m, const ContactOptions& p) {
  const auto& r = m.skeleton.roles;
  if (!r.has(Role::LeftAnkle) || !r.has(Role::RightAnkle))
    throw Error("foot contacts need ankle joints (roles left_ankle/right_ankle)");
  const int n = m.frame_count();
  std::array<std::vector<char>, 2> out;
  if (n < 3) {
    out[0].assign(static_cast<std::size_t>(std::max(0, n)), 1);
    out[1] = out[0];
    return out;
  }
  const std::vector<Vec3> pos = joint_positions(m);
  const Role ankles[2] = {Role::LeftAnkle, Role::RightAnkle}, toes[2] = {Role::LeftToe, Role::RightToe};
  for (int foot = 0; foot < 2; ++foot) {
    const int ja = r[ankles[foot]];
    const int jt = r.has(toes[foot]) ? r[toes[foot]] : ja;
    const JointTrack parts[2] = {track(m, pos, ja), track(m, pos, jt)};
    auto& c = out[static_cast<std::size_t>(foot)];
    c = p.learned ? contact_learned(parts, m.fps, p) : contact_fixed(parts, m.fps, p);
    fill_short_stances(c, static_cast<int>(std::lround(p.min_stance * m.fps)));
  }
  return out;
}

std::vector<SwingEvent> foot_swings(const Motion& m, const ContactOptions& p) {
  const auto contacts = foot_contacts(m, p);
  const int n = m.frame_count();
  if (n < 3) return {};
  const auto& r = m.skeleton.roles;
  const Role ankles[2] = {Role::LeftAnkle, Role::RightAnkle};
  const std::vector<Vec3> pos = joint_positions(m);
  std::vector<SwingEvent> out;
  for (int foot = 0; foot < 2; ++foot) {
    const auto& contact = contacts[static_cast<std::size_t>(foot)];
    const JointTrack ankle = track(m, pos, r[ankles[foot]]);
    const double rest = percentile(ankle.y, p.stance_percentile);
    for (int f = 0; f < n;) {
      if (contact[static_cast<std::size_t>(f)]) { ++f; continue; }
      int e = f;
      double apex = 0;
      while (e < n && !contact[static_cast<std::size_t>(e)]) apex = std::max(apex, ankle.y[static_cast<std::size_t>(e++)] - rest);
      const double t0 = f / m.fps, t1 = e / m.fps;
      // A swing cut by the clip's start has no true foot-off; one cut by its
      // end has no strike (kept, flagged, on request: its foot-off is real).
      // min_swing drops lifts that came back down quickly (blips); a lift the
      // end cuts is still under way, so only a 50 ms minimum applies to it.
      const bool cut = e >= n;
      const double shortest = cut ? std::min(p.min_swing, 0.05) : p.min_swing;
      if (f > 0 && (!cut || p.end_swings) && t1 - t0 >= shortest) out.push_back({foot, t0, t1, apex, cut});
      f = e;
    }
  }
  std::sort(out.begin(), out.end(), [](const SwingEvent& a, const SwingEvent& b) { return a.off < b.off; });
  return out;
}

}  // namespace legwork

namespace legwork {

std::vector<int> foot_strikes(const Motion& m, int foot, const ContactOptions& p) {
  if (foot != 0 && foot != 1) throw Error("foot_strikes: foot must be 0 (left) or 1 (right)");
  const std::vector<char> contact = foot_contacts(m, p)[static_cast<std::size_t>(foot)];
  const int n = static_cast<int>(contact.size());
  const int min_swing = static_cast<int>(std::lround(p.min_swing * m.fps));
  std::vector<int> out;
  // A swing already under way at the clip's start still ends in a true strike.
  for (int f = 0; f < n;) {
    if (contact[static_cast<std::size_t>(f)]) { ++f; continue; }
    int e = f;
    while (e < n && !contact[static_cast<std::size_t>(e)]) ++e;
    if (e < n && (f == 0 || e - f >= min_swing)) out.push_back(e);
    f = e;
  }
  return out;
}

}  // namespace legwork

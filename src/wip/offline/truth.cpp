#include <legwork/wip/offline/truth.hpp>

#include <legwork/core/fk.hpp>
#include <legwork/core/series.hpp>

#include <algorithm>
#include <cmath>

namespace legwork::wip {

std::vector<SwingEvent> true_swings(const Motion& m, const TruthOptions& p) {
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

}  // namespace legwork::wip

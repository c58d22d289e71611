// Uneven ground (see ground.hpp).
#include <legwork/walkcycle/ground.hpp>

#include <legwork/core/rotation.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace legwork::walkcycle {

double Ground::height(double x, double z) const {
  switch (kind) {
    case Kind::Flat:
      return 0.0;
    case Kind::Slope: {
      const double d = (x - origin.x()) * direction.x() + (z - origin.z()) * direction.z();
      return grade * std::clamp(d, 0.0, length);
    }
    case Kind::HeightField: {
      const double u = std::clamp((x - origin.x()) / cell, 0.0, columns - 1.0);
      const double v = std::clamp((z - origin.z()) / cell, 0.0, rows - 1.0);
      const int c = std::min(static_cast<int>(u), columns - 2), r = std::min(static_cast<int>(v), rows - 2);
      const double fu = u - c, fv = v - r;
      auto h = [&](int rr, int cc) { return heights[static_cast<std::size_t>(rr * columns + cc)]; };
      return (1 - fv) * ((1 - fu) * h(r, c) + fu * h(r, c + 1)) + fv * ((1 - fu) * h(r + 1, c) + fu * h(r + 1, c + 1));
    }
    case Kind::Stairs: {
      const double d = (x - origin.x()) * direction.x() + (z - origin.z()) * direction.z();
      return d < 0 ? 0.0 : rise * std::min(count, static_cast<int>(std::floor(d / run)) + 1);
    }
  }
  return 0.0;
}

std::string Ground::describe() const {
  char buf[160];
  if (kind == Kind::Slope) {
    if (length < 1e8) std::snprintf(buf, sizeof buf, "slope %.1f %% over %.2f m", grade * 100, length);
    else std::snprintf(buf, sizeof buf, "slope %.1f %%", grade * 100);
  } else if (kind == Kind::HeightField) {
    const auto [lo, hi] = std::minmax_element(heights.begin(), heights.end());
    std::snprintf(buf, sizeof buf, "height field %d x %d, %.2f m cells, %.3f-%.3f m", columns, rows, cell, *lo, *hi);
  } else if (kind == Kind::Stairs) {
    std::snprintf(buf, sizeof buf, "stairs %s, %d steps of %.3f m rise, %.3f m run", rise > 0 ? "up" : "down", count,
                  std::abs(rise), run);
  } else {
    return "flat";
  }
  return buf;
}

double fit_on_tread(const Ground& ground, const FootExtent& e, double& height) {
  auto h = [&](double s) { return ground.height(ground.origin + s * ground.direction); };
  const double margin = 0.02;
  const int steps = static_cast<int>(std::clamp(ground.run, 0.0, Ground::kMaxRun) / 0.01);  // (a NaN run searches none)
  for (int i = 0; i <= steps; ++i)
    for (int sign : {-1, 1}) {
      const double d = sign * 0.01 * i, tread = h(e.ball_lo + d);
      if (h(e.ball_lo + d - margin) != tread || h(e.ball_hi + d + margin) != tread) continue;
      if (h(e.lo + d) > tread || h(e.hi + d + margin) > tread) continue;
      height = tread;
      return d;
    }
  height = std::max(h(e.lo), h(e.hi));
  return 0.0;
}

Quat fit_to_ground(const Ground& ground, const FootPivots& foot, bool anchor_ball, Transform& ankle, Quat& full) {
  full = Quat::Identity();
  if (ground.flat() || ground.stepped()) return full;  // (stairs: planted flat by plant_on_treads)
  const Vec3 heel = ankle.apply(foot.heel_local), ball = ankle.apply(foot.ball_local);
  const Vec3 up = Vec3::UnitY();
  const double flat = std::clamp(1.0 - std::abs(ball.y() - heel.y()) / 0.05, 0.0, 1.0);
  full = Quat::FromTwoVectors(ball - heel, (ball + ground.height(ball) * up) - (heel + ground.height(heel) * up));
  const Quat q = Quat::Identity().slerp(flat, full);
  const Vec3 a = anchor_ball ? ball : heel;
  ankle.translation = a + ground.height(a) * up + q * (ankle.translation - a);
  ankle.rotation = (q * ankle.rotation).normalized();
  return q;
}

}  // namespace legwork::walkcycle

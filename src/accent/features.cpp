#include <legwork/accent/features.hpp>

#include <cmath>

namespace legwork::accent {

void window_from_frames(std::span<const TrackerFrame> frames, std::size_t end, int hand, double scale, HandWindow& out) {
  for (int i = 0; i < kWindow; ++i) {
    const TrackerFrame& fr = frames[end - static_cast<std::size_t>(window_lag(i))];
    out[static_cast<std::size_t>(i)] = (fr.hand(hand).position - fr.head().position) * scale;
  }
}

void raw_feature(const HandWindow& w, double db_fps, RawFeature& out) {
  const double fps = db_fps / kStride;
  int o = 0;
  for (int i = 0; i < kWindow; ++i)
    for (int a = 0; a < 3; ++a) out[static_cast<std::size_t>(o++)] = w[static_cast<std::size_t>(i)][a];
  // Backward differences: v_i = (p_i - p_{i-1}) fps, a_i = (v_i - v_{i-1}) fps.
  std::array<Vec3, kWindow> v;
  for (int i = 1; i < kWindow; ++i) {
    const auto iu = static_cast<std::size_t>(i);
    v[iu] = (w[iu] - w[iu - 1]) * fps;
    for (int a = 0; a < 3; ++a) out[static_cast<std::size_t>(o++)] = v[iu][a];
  }
  for (int i = 2; i < kWindow; ++i) {
    const auto iu = static_cast<std::size_t>(i);
    const Vec3 acc = (v[iu] - v[iu - 1]) * fps;
    for (int a = 0; a < 3; ++a) out[static_cast<std::size_t>(o++)] = acc[a];
  }
}

void FeatureSpace::project(const HandWindow& w, Feature& out) const {
  for (int r = 0; r < kDim; ++r) {
    const double* row = projection.data() + static_cast<std::ptrdiff_t>(r) * kPosDim;
    double s = 0;
    for (int i = 0; i < kWindow; ++i) {
      const Vec3& p = w[static_cast<std::size_t>(i)];
      s += row[3 * i] * p.x() + row[3 * i + 1] * p.y() + row[3 * i + 2] * p.z();
    }
    out[static_cast<std::size_t>(r)] = static_cast<float>(s);
  }
}

double FeatureSpace::raw_distance(const HandWindow& a, const HandWindow& b) const {
  RawFeature fa, fb;
  raw_feature(a, fps, fa);
  raw_feature(b, fps, fb);
  double s = 0;
  for (std::size_t d = 0; d < fa.size(); ++d) {
    const double x = scale[d] * (fa[d] - fb[d]);
    s += x * x;
  }
  return std::sqrt(s);
}

void fill_align(const HandWindow& left, const HandWindow& right, AlignXZ& out) {
  for (int i = 0; i < kWindow; ++i) {
    const auto iu = static_cast<std::size_t>(i);
    out[static_cast<std::size_t>(2 * i)] = static_cast<float>(left[iu].x());
    out[static_cast<std::size_t>(2 * i + 1)] = static_cast<float>(left[iu].z());
    out[static_cast<std::size_t>(2 * kWindow + 2 * i)] = static_cast<float>(right[iu].x());
    out[static_cast<std::size_t>(2 * kWindow + 2 * i + 1)] = static_cast<float>(right[iu].z());
  }
}

namespace {
// Each sample's weight c_i = (i + 1) / kWindow, rising over the window for
// both hands ([hand][sample], as AlignXZ), so the latest samples (the pose we
// output) count most; and their sum.
constexpr std::size_t kAlignSamples = 2 * kWindow;
constexpr std::array<double, kAlignSamples> kAlignWeight = [] {
  std::array<double, kAlignSamples> c{};
  for (std::size_t p = 0; p < kAlignSamples; ++p) c[p] = static_cast<double>(p % kWindow + 1) / kWindow;
  return c;
}();
constexpr double kAlignWeightSum = kWindow + 1.0;  // 2 hands x the sum of (i + 1) / kWindow, (kWindow + 1) / 2

// The closed form's sums: the aligning angle is atan2(num, den).
void align_sums(const AlignQuery& q, const AlignXZ& s, double& num, double& den) {
  double sxs = 0, szs = 0, cross = 0, dot = 0;
  for (std::size_t p = 0; p < kAlignSamples; ++p) {
    const double c = kAlignWeight[p];
    const double cxq = q.cxz[2 * p], czq = q.cxz[2 * p + 1], xs = s[2 * p], zs = s[2 * p + 1];
    sxs += c * xs, szs += c * zs;
    cross += cxq * zs - xs * czq;
    dot += cxq * xs + czq * zs;
  }
  num = cross - (q.sx * szs - sxs * q.sz) / kAlignWeightSum;
  den = dot - (q.sx * sxs + q.sz * szs) / kAlignWeightSum;
}
}  // namespace

AlignQuery align_query(const AlignXZ& q) {
  AlignQuery a;
  for (std::size_t k = 0; k < 2 * kAlignSamples; ++k) a.cxz[k] = kAlignWeight[k / 2] * q[k];
  for (std::size_t p = 0; p < kAlignSamples; ++p) {
    a.sx += a.cxz[2 * p];
    a.sz += a.cxz[2 * p + 1];
  }
  return a;
}

double align_yaw(const AlignQuery& q, const AlignXZ& s) {
  double num = 0, den = 0;
  align_sums(q, s, num, den);
  if (std::abs(num) < 1e-300 && std::abs(den) < 1e-300) return 0.0;
  return std::atan2(num, den);
}

Quat align_turn(const AlignQuery& q, const AlignXZ& s) {
  double num = 0, den = 0;
  align_sums(q, s, num, den);
  if (std::abs(num) < 1e-300 && std::abs(den) < 1e-300) return Quat::Identity();
  // The angle's cosine and sine, then the half angle's (cos >= 0, the angle in
  // (-pi, pi]), each from the better-conditioned of the two half-angle forms.
  const double r = std::sqrt(num * num + den * den);
  if (!(r > 0)) return Quat::Identity();  // the squares underflowed (no turn to speak of)
  const double c = den / r, sn = num / r;
  double ch, sh;
  if (c >= 0) {
    ch = std::sqrt(0.5 * (1 + c));
    sh = sn / (2 * ch);
  } else {
    sh = std::copysign(std::sqrt(0.5 * (1 - c)), sn);
    ch = sn / (2 * sh);
  }
  return Quat(ch, 0, sh, 0);
}

}  // namespace legwork::accent

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
  static_assert(sizeof(HandWindow) == kPosDim * sizeof(double), "a hand window is kPosDim packed doubles");
  const Eigen::Map<const Eigen::Matrix<double, kDim, kPosDim, Eigen::RowMajor>> p(projection.data());
  const Eigen::Map<const Eigen::Matrix<double, kPosDim, 1>> x(w[0].data());
  Eigen::Map<Eigen::Matrix<float, kDim, 1>>(out.data()) = (p * x).cast<float>();
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

// The closed form's sums: the aligning angle is atan2(num, den), with
//   num = sum c (x_q - xm_q) z_s - c (z_q - zm_q) x_s,  den = sum c (x_q - xm_q) x_s + c (z_q - zm_q) z_s
// (the candidate's own centroid drops out against the query's centred samples).
// Each sample's (x, z) pair is one two-lane packet; the lanes are added at the end.
void align_sums(const AlignQuery& q, const AlignXZ& s, double& num, double& den) {
  using Pair = Eigen::Array2d;
  Pair dot = Pair::Zero(), cross = Pair::Zero();
  for (std::size_t p = 0; p < kAlignSamples; ++p) {
    const Pair xz = Eigen::Map<const Eigen::Array2f>(s.data() + 2 * p).cast<double>();
    const Pair cq = Eigen::Map<const Pair>(q.cxz.data() + 2 * p);
    dot += cq * xz;              // c x_q x_s, c z_q z_s
    cross += cq * xz.reverse();  // c x_q z_s, c z_q x_s
  }
  num = cross[0] - cross[1];
  den = dot[0] + dot[1];
}
}  // namespace

AlignQuery align_query(const AlignXZ& q) {
  double sx = 0, sz = 0;  // the weighted centroid
  for (std::size_t p = 0; p < kAlignSamples; ++p) {
    sx += kAlignWeight[p] * q[2 * p];
    sz += kAlignWeight[p] * q[2 * p + 1];
  }
  sx /= kAlignWeightSum;
  sz /= kAlignWeightSum;
  AlignQuery a;
  for (std::size_t p = 0; p < kAlignSamples; ++p) {
    a.cxz[2 * p] = kAlignWeight[p] * (q[2 * p] - sx);
    a.cxz[2 * p + 1] = kAlignWeight[p] * (q[2 * p + 1] - sz);
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

#pragma once
// Hand-motion features of the accentuation engine (CoolMoves, section 3.1.2).
//
// A feature describes one hand over a window of kWindow samples taken every
// kStride samples at the database rate (9 samples 2 apart = 178 ms at 90 Hz;
// format 6, issue 12's longer context: the document's window was 9
// consecutive samples, 100 ms): the hand's head-relative position at every
// sample (world axes, no rotation normalisation, metres), its velocity
// (backward differences, kWindow-1 samples, m/s) and its acceleration (second
// backward differences, kWindow-2 samples, m/s^2).
// That "raw" feature has kRawDim = 72 numbers, laid out
//   [p0 p1 .. p8 | v1 .. v8 | a2 .. a8], each an (x, y, z) triple.
// Matching uses the L2 distance between raw features after a per-dimension
// scale (1 / standard deviation over the database, times a group weight for
// positions, velocities and accelerations). Because velocity and acceleration
// are linear in the positions, that weighted 72-d distance is exactly an L2
// distance between kDim = 27 numbers: FeatureSpace::project maps the 27
// head-relative window coordinates to them (a 27x27 matrix that also rotates
// onto principal axes so KD-trees split well). Runtime code: no allocation.
#include <legwork/core/tracker.hpp>
#include <legwork/core/types.hpp>

#include <array>
#include <cstddef>
#include <span>

namespace legwork::accent {

inline constexpr int kWindow = 9;                         // samples per window
inline constexpr int kStride = 2;                         // database-rate samples between window samples
// Database-rate samples from window sample i back to the window's end.
constexpr int window_lag(int i) { return (kWindow - 1 - i) * kStride; }
inline constexpr int kPosDim = 3 * kWindow;               // 27
inline constexpr int kRawDim = 3 * (3 * kWindow - 3);     // 72
inline constexpr int kDim = kPosDim;                      // projected feature size

using HandWindow = std::array<Vec3, kWindow>;  // head-relative positions, oldest first
using RawFeature = std::array<double, kRawDim>;
using Feature = std::array<float, kDim>;

// The live query window of hand `hand` (0 left, 1 right) ending on
// frames[end], from a whole recording at the database rate (end >=
// window_lag(0)): head-relative positions times `scale` (database height /
// user height), as the engine forms it. For offline measurements (the
// evaluation's and the benchmark's fast-search recall); the engine keeps a
// ring of recent samples instead.
void window_from_frames(std::span<const TrackerFrame> frames, std::size_t end, int hand, double scale, HandWindow& out);

// Raw feature of one hand window sampled at `fps` (layout above).
void raw_feature(const HandWindow& w, double fps, RawFeature& out);

// The stored normalisation and projection (one for both hands).
struct FeatureSpace {
  double fps = 90.0;
  std::array<double, kRawDim> scale{};      // per raw dimension: group weight / std
  std::array<double, 3> group_weight{1, 1, 1};  // position, velocity, acceleration
  std::array<double, kDim * kDim> projection{};  // row-major kDim x kPosDim

  // Projected feature of a window: ||project(a) - project(b)|| equals the
  // scaled raw-feature distance (up to float rounding).
  void project(const HandWindow& w, Feature& out) const;
  // The scaled raw-feature distance, computed the long way (tests, docs).
  double raw_distance(const HandWindow& a, const HandWindow& b) const;
};

// Weighted closed-form rotation about the vertical (y) axis that best maps the
// database window s onto the live window q (Kovar & Gleicher; CoolMoves eq. in
// 3.1.4): both hands' x/z positions, weights c_i = (i+1)/kWindow rising over
// the window, centroids removed. Apply as Eigen::AngleAxisd(theta, Vec3::UnitY())
// to s. Inputs: xz pairs per sample, [hand][sample][x,z].
using AlignXZ = std::array<float, 2 * kWindow * 2>;  // [hand 0/1][sample][x/z]
// The live window's part of the closed form, computed once per frame for all
// its candidates: each sample's offset from the window's weighted centroid
// (xm, zm), times its weight.
struct AlignQuery {
  std::array<double, 2 * kWindow * 2> cxz{};  // c_i (x_i - xm), c_i (z_i - zm): [hand][sample][x/z]
};
AlignQuery align_query(const AlignXZ& q);
double align_yaw(const AlignQuery& q, const AlignXZ& s);
// The same rotation as a quaternion, yaw_rotation(align_yaw(q, s)) up to
// rounding, without the angle's atan2, cos and sin (the per-candidate path).
Quat align_turn(const AlignQuery& q, const AlignXZ& s);
void fill_align(const HandWindow& left, const HandWindow& right, AlignXZ& out);

}  // namespace legwork::accent

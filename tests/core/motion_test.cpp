// FK, interpolation, resampling and mirroring on real CMU motion.
#include <legwork/core/fk.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/core/measure.hpp>
#include <legwork/core/mirror.hpp>
#include <legwork/io/bvh.hpp>

#include "cmu_sample.hpp"
#include "testdata.hpp"

#include <random>

using namespace legwork;

namespace {
Motion walk() { return testdata::load_sample("cmu/bvh/walking/07_01.bvh"); }
double quat_distance(const Quat& a, const Quat& b) { return 1.0 - std::abs(a.dot(b)); }
}  // namespace

TEST(ForwardKinematics, MatchesChainedTransformsAndBatch) {
  Motion m = walk();
  const auto& s = m.skeleton;
  std::vector<Transform> g(static_cast<std::size_t>(s.joint_count()));
  forward_kinematics(s, m.frame(10), g);
  // Oracle: walk from the joint to the root composing transforms explicitly.
  for (int j = 0; j < s.joint_count(); ++j) {
    Transform t;
    for (int k = j; k >= 0; k = s.parents[static_cast<std::size_t>(k)]) {
      Transform local{m.frame(10).rotations[static_cast<std::size_t>(k)], m.frame(10).translations[static_cast<std::size_t>(k)]};
      t = local * t;
    }
    EXPECT_LT((t.translation - g[static_cast<std::size_t>(j)].translation).norm(), 1e-12);
    EXPECT_LT(quat_distance(t.rotation, g[static_cast<std::size_t>(j)].rotation), 1e-12);
  }
  auto all = joint_positions(m);
  const auto n = static_cast<std::size_t>(s.joint_count());
  for (std::size_t j = 0; j < n; ++j) EXPECT_LT((all[10 * n + j] - g[j].translation).norm(), 1e-12);
}

TEST(ForwardKinematics, LocalFromModelInvertsFk) {
  Motion m = walk();
  const auto& s = m.skeleton;
  const auto n = static_cast<std::size_t>(s.joint_count());
  std::vector<Transform> g(n);
  forward_kinematics(s, m.frame(50), g);
  std::vector<Quat> model(n), local(n);
  for (std::size_t j = 0; j < n; ++j) model[j] = g[j].rotation;
  local_from_model_rotations(s, model, local);
  for (std::size_t j = 0; j < n; ++j) EXPECT_LT(quat_distance(local[j], m.frame(50).rotations[j]), 1e-12);
}

TEST(ForwardKinematics, WalkingFeetStartNearTheFloor) {
  Motion m = walk();
  const auto& r = m.skeleton.roles;
  auto p = joint_positions(m);
  const auto n = static_cast<std::size_t>(m.joint_count());
  double floor = 1e9;
  for (const auto& v : p) floor = std::min(floor, v.y());
  const double lf = p[static_cast<std::size_t>(r[Role::LeftToe])].y(), rf = p[static_cast<std::size_t>(r[Role::RightToe])].y();
  EXPECT_LT(std::min(lf, rf) - floor, 0.05);
  const double head = p[static_cast<std::size_t>(r[Role::Head])].y() - floor;
  EXPECT_GT(head, 1.2);
  EXPECT_LT(head, 1.9);
  (void)n;
}

TEST(Interpolate, SlerpIsShortestArcAndEndpointExact) {
  Quat a(Eigen::AngleAxisd(0.3, Vec3::UnitY()));
  Quat b(Eigen::AngleAxisd(1.1, Vec3::UnitY()));
  Quat neg_b(-b.w(), -b.x(), -b.y(), -b.z());
  EXPECT_LT(quat_distance(slerp(a, neg_b, 0.5), Quat(Eigen::AngleAxisd(0.7, Vec3::UnitY()))), 1e-12);
  EXPECT_LT(quat_distance(slerp(a, b, 0.0), a), 1e-15);
  EXPECT_LT(quat_distance(slerp(a, b, 1.0), b), 1e-12);
  EXPECT_LT(quat_distance(nlerp(a, neg_b, 0.5), Quat(Eigen::AngleAxisd(0.7, Vec3::UnitY()))), 1e-12);
}

TEST(Resample, To90HzKeepsDurationAndPositionsWithin1cm) {
  Motion m = walk();  // 120 Hz
  Motion r = resample(m, 90.0);
  EXPECT_NEAR(r.fps, 90.0, 1e-12);
  EXPECT_NEAR(r.duration(), m.duration(), 1.0 / 90.0);
  auto pm = joint_positions(m), pr = joint_positions(r);
  const auto n = static_cast<std::size_t>(m.joint_count());
  // Shared instants: every 3rd frame at 90 Hz is every 4th at 120 Hz.
  double worst = 0;
  int checked = 0;
  for (int f = 0; 3 * f < r.frame_count() && 4 * f < m.frame_count(); ++f, ++checked)
    for (std::size_t j = 0; j < n; ++j)
      worst = std::max(worst, (pr[static_cast<std::size_t>(3 * f) * n + j] - pm[static_cast<std::size_t>(4 * f) * n + j]).norm());
  EXPECT_GT(checked, 50);
  EXPECT_LT(worst, 0.01);
  // In-between instants stay close too (interpolation, not sample-and-hold).
  double mid_worst = 0;
  for (int f = 1; f + 1 < r.frame_count(); f += 3) {
    const double t = f / 90.0;
    const int i = static_cast<int>(t * 120.0);
    mid_worst = std::max(mid_worst, (pr[static_cast<std::size_t>(f) * n] - pm[static_cast<std::size_t>(i) * n]).norm());
  }
  EXPECT_LT(mid_worst, 0.05);
}

TEST(Resample, RejectsBadRateAndTrimsConcatenates) {
  Motion m = walk();
  EXPECT_THROW(resample(m, 0.0), Error);
  EXPECT_THROW(trim(m, 5, 2), Error);
  EXPECT_THROW(trim(m, 0, m.frame_count()), Error);
  Motion a = trim(m, 0, 9), b = trim(m, 10, 19);
  Motion c = concatenate(a, b);
  ASSERT_EQ(c.frame_count(), 20);
  EXPECT_LT((c.frame(15).translations[0] - m.frame(15).translations[0]).norm(), 1e-15);
  EXPECT_THROW(concatenate(a, resample(b, 60)), Error);
}

TEST(Mirror, TwiceIsIdentity) {
  Motion m = walk();
  Motion mm = mirror_motion(mirror_motion(m));
  for (int f = 0; f < m.frame_count(); f += 7)
    for (int j = 0; j < m.joint_count(); ++j) {
      const auto ju = static_cast<std::size_t>(j);
      EXPECT_LT(quat_distance(mm.frame(f).rotations[ju], m.frame(f).rotations[ju]), 1e-15);
      EXPECT_LT((mm.frame(f).translations[ju] - m.frame(f).translations[ju]).norm(), 1e-15);
    }
}

TEST(Mirror, MirroredLeftHandFollowsReflectedRightHand) {
  Motion m = walk();
  Motion mir = mirror_motion(m);
  const auto& r = m.skeleton.roles;
  auto p = joint_positions(m), q = joint_positions(mir);
  const auto n = static_cast<std::size_t>(m.joint_count());
  for (int f = 0; f < m.frame_count(); f += 5) {
    const auto base = static_cast<std::size_t>(f) * n;
    Vec3 right = p[base + static_cast<std::size_t>(r[Role::RightHand])];
    Vec3 mirrored_left = q[base + static_cast<std::size_t>(r[Role::LeftHand])];
    EXPECT_LT((mirrored_left - mirror_vector(right)).norm(), 1e-9) << "frame " << f;
    // Central joints stay on the reflected path of themselves.
    Vec3 head = p[base + static_cast<std::size_t>(r[Role::Head])];
    EXPECT_LT((q[base + static_cast<std::size_t>(r[Role::Head])] - mirror_vector(head)).norm(), 1e-9);
  }
}

TEST(Mirror, MirroredWalkStillWalksForward) {
  Motion m = walk();
  Motion mir = mirror_motion(m);
  const Vec3 d0 = m.frame(m.frame_count() - 1).translations[0] - m.frame(0).translations[0];
  const Vec3 d1 = mir.frame(mir.frame_count() - 1).translations[0] - mir.frame(0).translations[0];
  EXPECT_NEAR(d0.z(), d1.z(), 1e-12);
  EXPECT_NEAR(d0.x(), -d1.x(), 1e-12);
}

TEST(Resample, HugeRateIsRefusedBeforeAllocating) {
  // 'convert --rate 1000000' wrote a 2.4 GB file using 6.9 GB; 1e300 Hz overflowed the frame count.
  const Motion m = io::load_bvh(testdata::sample("cmu/bvh/walking/07_01.bvh").string());
  for (double rate : {1e6, 1e300}) {
    try {
      (void)resample(m, rate);
      ADD_FAILURE() << rate << " Hz: expected an error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("joints, more than 67108864 joint poses"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(resampled_frame_count(m, 30), resample(m, 30).frame_count());
}

// Interpolation, resampling, trimming and concatenation (src/core/interpolate.cpp)
// on real CMU motion.
#include <legwork/core/fk.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/io/bvh.hpp>

#include "core_samples.hpp"
#include "error_message.hpp"
#include "testdata.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace legwork;
using testdata::message_of;

namespace {
double angle_between(const Quat& a, const Quat& b) { return a.angularDistance(b); }

void expect_same_pose(ConstPoseRef a, ConstPoseRef b, double tol) {
  ASSERT_EQ(a.joint_count(), b.joint_count());
  for (std::size_t j = 0; j < a.rotations.size(); ++j) {
    EXPECT_LT(testdata::quat_distance(a.rotations[j], b.rotations[j]), tol) << "joint " << j;
    EXPECT_LT((a.translations[j] - b.translations[j]).norm(), tol) << "joint " << j;
  }
}
}  // namespace

TEST(Interpolate, SlerpIsShortestArcAndEndpointExact) {
  Quat a(Eigen::AngleAxisd(0.3, Vec3::UnitY()));
  Quat b(Eigen::AngleAxisd(1.1, Vec3::UnitY()));
  Quat neg_b(-b.w(), -b.x(), -b.y(), -b.z());
  EXPECT_LT(testdata::quat_distance(slerp(a, neg_b, 0.5), Quat(Eigen::AngleAxisd(0.7, Vec3::UnitY()))), 1e-12);
  EXPECT_LT(testdata::quat_distance(slerp(a, b, 0.0), a), 1e-15);
  EXPECT_LT(testdata::quat_distance(slerp(a, b, 1.0), b), 1e-12);
  EXPECT_LT(testdata::quat_distance(nlerp(a, neg_b, 0.5), Quat(Eigen::AngleAxisd(0.7, Vec3::UnitY()))), 1e-12);
}

TEST(Interpolate, SlerpTurnsAtConstantRateBetweenRealJointRotations) {
  // Two frames half a stride apart of the walk's left hip: the angle from a grows linearly in t.
  const Motion m = testdata::walk();
  const auto hip = static_cast<std::size_t>(m.skeleton.roles[Role::LeftHip]);
  const Quat a = m.frame(0).rotations[hip], b = m.frame(60).rotations[hip];
  const double total = angle_between(a, b);
  ASSERT_GT(total, 0.2);  // the hip really turns (well past where slerp falls back to nlerp)
  for (double t : {0.1, 0.25, 0.5, 0.8}) {
    EXPECT_NEAR(angle_between(a, slerp(a, b, t)), t * total, 1e-9) << "t=" << t;
    EXPECT_NEAR(angle_between(slerp(a, b, t), b), (1 - t) * total, 1e-9) << "t=" << t;
  }
}

TEST(Interpolate, SlerpAgreesWithEigensOnEveryJointOfRealFrames) {
  // Every joint between frames a quarter of a second apart, and a second apart, of the walk
  // (both hemispheres, past the nlerp fallback): the same rotation as Eigen's own slerp.
  const Motion m = testdata::walk();
  int compared = 0;
  double worst = 0;
  for (int gap : {30, 120})
    for (int f = 0; f + gap < m.frame_count(); f += 17)
      for (std::size_t j = 0; j < m.frame(f).rotations.size(); ++j) {
        const Quat a = m.frame(f).rotations[j], b = m.frame(f + gap).rotations[j];
        if (std::abs(a.dot(b)) > 0.9995) continue;
        for (double t : {0.1, 0.5, 0.9}) {
          const Quat q = slerp(a, b, t), e = a.slerp(t, b);
          worst = std::max(worst, std::min((q.coeffs() - e.coeffs()).norm(), (q.coeffs() + e.coeffs()).norm()));
          EXPECT_NEAR(q.norm(), 1.0, 1e-15);
          ++compared;
        }
      }
  ASSERT_GT(compared, 100);
  EXPECT_LT(worst, 1e-13);
}

TEST(Interpolate, SampleMotionAtAFrameTimeIsThatFrameAndClampsOutside) {
  const Motion m = testdata::walk();
  Pose p(m.skeleton);
  for (int f : {0, 1, 57, m.frame_count() - 1}) {
    sample_motion(m, f / m.fps, p.ref());
    expect_same_pose(p, m.frame(f), 1e-12);
  }
  sample_motion(m, -3.0, p.ref());
  expect_same_pose(p, m.frame(0), 1e-15);
  sample_motion(m, m.duration() + 10.0, p.ref());
  expect_same_pose(p, m.frame(m.frame_count() - 1), 1e-15);
}

TEST(Interpolate, BlendHalfwayLerpsTranslationsAndMatchesSampleBetweenFrames) {
  const Motion m = testdata::walk();
  Pose half(m.skeleton), sampled(m.skeleton);
  blend_poses(m.frame(30), m.frame(31), 0.5, half.ref());
  const auto root = 0u;
  EXPECT_LT((half.translations[root] - 0.5 * (m.frame(30).translations[root] + m.frame(31).translations[root])).norm(), 1e-12);
  sample_motion(m, 30.5 / m.fps, sampled.ref());
  expect_same_pose(half, sampled, 1e-12);
}

TEST(Resample, To90HzKeepsDurationAndPositionsWithin1cm) {
  Motion m = testdata::walk();  // 120 Hz
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
  Motion m = testdata::walk();
  EXPECT_THROW(resample(m, 0.0), Error);
  EXPECT_THROW(trim(m, 5, 2), Error);
  EXPECT_THROW(trim(m, 0, m.frame_count()), Error);
  Motion a = trim(m, 0, 9), b = trim(m, 10, 19);
  Motion c = concatenate(a, b);
  ASSERT_EQ(c.frame_count(), 20);
  EXPECT_LT((c.frame(15).translations[0] - m.frame(15).translations[0]).norm(), 1e-15);
  EXPECT_THROW(concatenate(a, resample(b, 60)), Error);
}

TEST(Resample, ErrorsSayWhatIsWrong) {
  const Motion m = testdata::walk();
  EXPECT_EQ(message_of([&] { (void)resample(m, -2.0); }), "resample: frame rate must be positive, got -2.000000");
  EXPECT_NE(message_of([&] { (void)resample(m, std::nan("")); }).find("resample: frame rate must be positive"), std::string::npos);
  EXPECT_EQ(message_of([&] { (void)trim(m, 0, m.frame_count()); }),
            "trim: frames 0:" + std::to_string(m.frame_count()) + " are outside 0:" + std::to_string(m.frame_count() - 1));
  Motion renamed = m;
  renamed.skeleton.names[1] += "_other";
  EXPECT_EQ(message_of([&] { (void)concatenate(m, renamed); }), "concatenate: the motions have different skeletons");
  EXPECT_EQ(message_of([&] { (void)concatenate(m, resample(m, 60)); }), "concatenate: frame rates differ; resample first");
}

TEST(Resample, AtTheOwnRateReproducesEveryFrame) {
  const Motion m = testdata::walk();
  const Motion r = resample(m, m.fps);
  ASSERT_EQ(r.frame_count(), m.frame_count());
  for (int f = 0; f < m.frame_count(); f += 13) expect_same_pose(r.frame(f), m.frame(f), 1e-12);
  Motion empty(m.skeleton, m.fps, 0);
  EXPECT_EQ(resampled_frame_count(empty, 30), 0);
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

// The Accentuator on real held-out CMU trials.
#include <legwork/accent/accentuator.hpp>
#include <legwork/accent/builder.hpp>
#include <legwork/core/fk.hpp>
#include <legwork/core/interpolate.hpp>

#include "accent_testing.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace legwork::accent {
namespace {

struct HandErrors {
  double left = 0, right = 0, body = 0;
};

// Mean distance between the input's and the output's hands (and all role joints).
HandErrors measure(const Motion& input90, const Motion& out) {
  const auto& ri = input90.skeleton.roles;
  const auto& ro = out.skeleton.roles;
  HandErrors e;
  int n_body = 0;
  for (int f = 0; f < out.frame_count(); ++f) {
    const auto pi = joint_positions(input90.skeleton, input90.frame(f));
    const auto po = joint_positions(out.skeleton, out.frame(f));
    e.left += (pi[static_cast<std::size_t>(ri[Role::LeftHand])] - po[static_cast<std::size_t>(ro[Role::LeftHand])]).norm();
    e.right += (pi[static_cast<std::size_t>(ri[Role::RightHand])] - po[static_cast<std::size_t>(ro[Role::RightHand])]).norm();
    for (int r = 0; r < kRoleCount; ++r)
      if (ri.joint[static_cast<std::size_t>(r)] >= 0 && ro.joint[static_cast<std::size_t>(r)] >= 0) {
        e.body += (pi[static_cast<std::size_t>(ri.joint[static_cast<std::size_t>(r)])] - po[static_cast<std::size_t>(ro.joint[static_cast<std::size_t>(r)])]).norm();
        ++n_body;
      }
  }
  e.left /= out.frame_count();
  e.right /= out.frame_count();
  e.body /= std::max(n_body, 1);
  return e;
}

class HeldOut : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const auto trials = testing::sample_trials({"walking/05_01", "walking/07_01", "walking/07_12", "walking/10_04",
                                                "walking/16_15", "walking/16_21", "running/09_01", "running/16_36",
                                                "boxing/13_18"});
    db_ = new Database(build_database(trials, BuildConfig{}));
    db_->build_index();
    input_ = new Motion(resample(testing::sample_trial("walking/07_02").motion, 90.0));
  }
  static void TearDownTestSuite() {
    delete db_;
    delete input_;
  }
  static Database* db_;
  static Motion* input_;
};
Database* HeldOut::db_ = nullptr;
Motion* HeldOut::input_ = nullptr;

TEST_F(HeldOut, HandsFollowTheInputAndThePoseIsSane) {
  for (SearchMode mode : {SearchMode::BruteForce, SearchMode::Fast}) {
    AccentConfig cfg;
    cfg.search = mode;
    const AccentRun run = accentuate_motion(*db_, cfg, *input_);
    ASSERT_EQ(run.output.frame_count(), input_->frame_count());
    for (const auto& q : run.output.all_rotations()) ASSERT_TRUE(std::isfinite(q.norm()) && std::abs(q.norm() - 1) < 1e-6);
    for (const auto& t : run.output.all_translations()) ASSERT_TRUE(t.allFinite());
    const HandErrors e = measure(*input_, run.output);
    int matched = 0;
    for (const auto& i : run.info) matched += i.status == FrameStatus::Matched;
    std::printf("[ figures  ] mode %d: hands %.1f / %.1f cm, role joints %.1f cm, matched %d/%d frames, %.0f frames/s\n",
                static_cast<int>(mode), 100 * e.left, 100 * e.right, 100 * e.body, matched, run.output.frame_count(),
                run.output.frame_count() / run.seconds);
    EXPECT_LT(e.left, 0.08);
    EXPECT_LT(e.right, 0.08);
    EXPECT_GT(matched, run.output.frame_count() * 9 / 10);
  }
}

}  // namespace
}  // namespace legwork::accent

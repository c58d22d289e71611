// Pose and Motion storage (src/core/motion.cpp) on a real CMU motion. FK,
// interpolation and mirroring have their own fk_, interpolate_ and mirror_test.cpp.
#include <legwork/core/motion.hpp>

#include "core_samples.hpp"

#include <gtest/gtest.h>

using namespace legwork;


TEST(Motion, RestPoseAndNewFramesUseTheSkeletonsOffsets) {
  const Motion m = testdata::walk();
  const Pose rest(m.skeleton);
  ASSERT_EQ(rest.joint_count(), m.joint_count());
  EXPECT_EQ(rest.translations, m.skeleton.rest_offsets);
  for (const auto& q : rest.rotations) EXPECT_EQ(q.coeffs(), Quat::Identity().coeffs());
  Motion grown = m;
  grown.resize(m.frame_count() + 2);
  ASSERT_EQ(grown.frame_count(), m.frame_count() + 2);
  const auto last = grown.frame(grown.frame_count() - 1);
  for (std::size_t j = 0; j < last.translations.size(); ++j) EXPECT_EQ(last.translations[j], m.skeleton.rest_offsets[j]);
  // Existing frames are untouched by growing.
  EXPECT_EQ(grown.frame(5).translations[0], m.frame(5).translations[0]);
}

TEST(Motion, FramesAreContiguousFrameMajorViews) {
  Motion m = testdata::walk();
  const auto n = static_cast<std::size_t>(m.joint_count());
  ASSERT_EQ(m.all_translations().size(), n * static_cast<std::size_t>(m.frame_count()));
  EXPECT_EQ(&m.frame(3).translations[2], &m.all_translations()[3 * n + 2]);
  EXPECT_EQ(m.frame(3).joint_count(), m.joint_count());
  EXPECT_NEAR(m.duration(), (m.frame_count() - 1) / m.fps, 1e-12);
  Motion copy = m;
  copy.set_frame(0, m.frame(7));
  EXPECT_EQ(copy.frame(0).translations[0], m.frame(7).translations[0]);
  copy.push_back(m.frame(9));
  ASSERT_EQ(copy.frame_count(), m.frame_count() + 1);
  EXPECT_EQ(copy.frame(copy.frame_count() - 1).rotations[4].coeffs(), m.frame(9).rotations[4].coeffs());
}

TEST(Motion, PushingAPoseOfAnotherRigIsAnError) {
  Motion m = testdata::walk();
  Skeleton small;
  small.add_joint("root", -1, Vec3::Zero());
  const Pose p(small);
  try {
    m.push_back(p);
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "Motion::push_back: pose has the wrong joint count");
  }
}

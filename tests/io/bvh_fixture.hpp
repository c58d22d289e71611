#pragma once
// A two-joint BVH (root + spine with an End Site) whose header the reader,
// writer and error tests share; each test appends its own two motion lines
// (or uses kTinyBvh's). And expect_same_motion, the round-trip comparison.
// Line numbers:  1 HIERARCHY, 2 ROOT, 4 OFFSET, 5 CHANNELS, 6 JOINT Spine,
// 8 OFFSET, 9 CHANNELS, 10 End Site, 12 OFFSET, 16 MOTION, 17 Frames,
// 18 Frame Time, 19-20 motion lines.
#include <legwork/io/bvh.hpp>

#include <gtest/gtest.h>

#include <algorithm>

#include <string>

namespace legwork::testdata {
inline const std::string kTinyBvhHeader =
    "HIERARCHY\n"
    "ROOT Hips\n"
    "{\n"
    "  OFFSET 0 0 0\n"
    "  CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation\n"
    "  JOINT Spine\n"
    "  {\n"
    "    OFFSET 0 0.5 0\n"
    "    CHANNELS 3 Zrotation Yrotation Xrotation\n"
    "    End Site\n"
    "    {\n"
    "      OFFSET 0 0.5 0\n"
    "    }\n"
    "  }\n"
    "}\n"
    "MOTION\n"
    "Frames: 2\n"
    "Frame Time: 0.1\n";

// The tiny file with two motion lines: Spine rotated Z 10, Y 20, X 30 in both;
// frame 1 moves and turns the root.
inline const std::string kTinyBvh = kTinyBvhHeader +
                                    "0 1 0 0 0 0 10 20 30\n"
                                    "0.25 1 0.1 5 -7 3 10 20 30\n";

// Reads the tiny file as metres: the toy skeleton is 1 m tall, so no unit guessing.
inline io::BvhReadOptions metres() {
  io::BvhReadOptions o;
  o.scale = 1.0;
  return o;
}
// a and b have the same skeleton, frame rate and poses (rotations up to
// sign, every value within tol).
inline void expect_same_motion(const Motion& a, const Motion& b, double tol) {
  ASSERT_EQ(a.joint_count(), b.joint_count());
  ASSERT_EQ(a.frame_count(), b.frame_count());
  EXPECT_NEAR(a.fps, b.fps, 1e-6 * a.fps);
  for (int j = 0; j < a.joint_count(); ++j) {
    const auto ju = static_cast<std::size_t>(j);
    EXPECT_EQ(a.skeleton.names[ju], b.skeleton.names[ju]);
    EXPECT_EQ(a.skeleton.parents[ju], b.skeleton.parents[ju]);
    EXPECT_LT((a.skeleton.rest_offsets[ju] - b.skeleton.rest_offsets[ju]).norm(), tol) << a.skeleton.names[ju];
    EXPECT_EQ(a.skeleton.has_end_site[ju], b.skeleton.has_end_site[ju]);
    EXPECT_LT((a.skeleton.end_sites[ju] - b.skeleton.end_sites[ju]).norm(), tol);
  }
  double worst_rot = 0, worst_tr = 0;
  for (int f = 0; f < a.frame_count(); ++f)
    for (int j = 0; j < a.joint_count(); ++j) {
      const auto ju = static_cast<std::size_t>(j);
      const Quat& qa = a.frame(f).rotations[ju];
      const Quat& qb = b.frame(f).rotations[ju];
      // q and -q are the same rotation.
      worst_rot = std::max(worst_rot, std::min((qa.coeffs() - qb.coeffs()).cwiseAbs().maxCoeff(),
                                               (qa.coeffs() + qb.coeffs()).cwiseAbs().maxCoeff()));
      worst_tr = std::max(worst_tr, (a.frame(f).translations[ju] - b.frame(f).translations[ju]).cwiseAbs().maxCoeff());
    }
  EXPECT_LT(worst_rot, tol);
  EXPECT_LT(worst_tr, tol);
}
}  // namespace legwork::testdata

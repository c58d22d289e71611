// Two-bone IK on the CMU skeleton and on random chains, checked against FK
// and against a numeric (damped Gauss-Newton) solver.
#include <legwork/core/fk.hpp>
#include <legwork/ik/two_bone.hpp>
#include <legwork/io/bvh.hpp>

#include "cmu_sample.hpp"
#include "testdata.hpp"

#include <cmath>
#include <random>

namespace legwork::ik {
namespace {

struct Rig {
  Motion motion;
  Pose pose;
  std::vector<Transform> model;
};

Rig cmu_rig(int frame = 100) {
  Rig r;
  r.motion = testdata::load_sample("cmu/bvh/walking/07_01.bvh");
  r.pose = Pose(r.motion.skeleton);
  auto f = r.motion.frame(frame);
  std::copy(f.rotations.begin(), f.rotations.end(), r.pose.rotations.begin());
  std::copy(f.translations.begin(), f.translations.end(), r.pose.translations.begin());
  r.model.resize(static_cast<std::size_t>(r.motion.joint_count()));
  forward_kinematics(r.motion.skeleton, r.pose, r.model);
  return r;
}

Vec3 pos(const std::vector<Transform>& m, int j) { return m[static_cast<std::size_t>(j)].translation; }

TEST(TwoBone, ReachesTargetsOnCmuLegAndModelMatchesFk) {
  Rig r = cmu_rig();
  const Skeleton& s = r.motion.skeleton;
  const TwoBoneChain leg = left_leg(s);
  ASSERT_GE(leg.root, 0);
  const Vec3 hip = pos(r.model, leg.root);
  const double reach = (pos(r.model, leg.mid) - hip).norm() + (pos(r.model, leg.end) - pos(r.model, leg.mid)).norm();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 200; ++i) {
    Vec3 dir(u(rng), -std::abs(u(rng)) - 0.3, u(rng));
    const double dist = reach * (0.35 + 0.6 * std::abs(u(rng)));
    TwoBoneTarget t;
    t.position = hip + dist * dir.normalized();
    t.hint = 0.5 * (hip + t.position) + Vec3(0, 0, 0.3);
    solve_two_bone(s, leg, t, r.pose.ref(), r.model);
    EXPECT_LT((pos(r.model, leg.end) - t.position).norm(), 1e-5) << "target " << i;
    // The written local rotations reproduce the model frames.
    std::vector<Transform> fk(r.model.size());
    forward_kinematics(s, r.pose, fk);
    for (int j : {leg.root, leg.mid, leg.end}) {
      EXPECT_LT((pos(fk, j) - pos(r.model, j)).norm(), 1e-9);
      EXPECT_LT(fk[static_cast<std::size_t>(j)].rotation.angularDistance(r.model[static_cast<std::size_t>(j)].rotation), 1e-9);
    }
    EXPECT_LT((pos(fk, leg.end) - t.position).norm(), 1e-5);
    // Bone lengths are kept.
    EXPECT_NEAR((pos(fk, leg.mid) - hip).norm() + (pos(fk, leg.end) - pos(fk, leg.mid)).norm(), reach, 1e-9);
  }
}

TEST(TwoBone, ArmChainsReachTheirTargetsWithTheElbowTowardTheHint) {
  Rig r = cmu_rig(50);
  const Skeleton& s = r.motion.skeleton;
  for (const TwoBoneChain& arm : {left_arm(s), right_arm(s)}) {
    ASSERT_GE(arm.end, 0);
    const Vec3 shoulder = pos(r.model, arm.root);
    TwoBoneTarget t;
    t.position = shoulder + Vec3(0.05, -0.15, 0.3);  // hand in front of the chest
    t.hint = shoulder + Vec3(0, -0.4, -0.1);        // elbow down and back
    solve_two_bone(s, arm, t, r.pose.ref(), r.model);
    EXPECT_LT((pos(r.model, arm.end) - t.position).norm(), 1e-5);
    EXPECT_LT(pos(r.model, arm.mid).y(), shoulder.y());
  }
}

TEST(TwoBone, UnreachableTargetGivesStraightChainPointingAtIt) {
  Rig r = cmu_rig();
  const Skeleton& s = r.motion.skeleton;
  const TwoBoneChain leg = right_leg(s);
  const Vec3 hip = pos(r.model, leg.root);
  const double lab = (pos(r.model, leg.mid) - hip).norm();
  const double lcb = (pos(r.model, leg.end) - pos(r.model, leg.mid)).norm();
  for (const Vec3& far : {Vec3(0.3, -5, 0.8), Vec3(0, -(lab + lcb) * 1.0001, 0), Vec3(4, 0, 0)}) {
    TwoBoneTarget t;
    t.position = hip + far;
    t.hint = hip + Vec3(0, -0.4, 0.3);
    solve_two_bone(s, leg, t, r.pose.ref(), r.model);
    const Vec3 end = pos(r.model, leg.end), mid = pos(r.model, leg.mid);
    EXPECT_NEAR((end - hip).norm(), lab + lcb, 1e-9);
    EXPECT_GT((end - hip).normalized().dot(far.normalized()), 1 - 1e-9);
    EXPECT_GT((mid - hip).normalized().dot(far.normalized()), 1 - 1e-6);
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(std::isfinite(end[k]));
  }
}

TEST(TwoBone, HintChoosesTheKneeSide) {
  Rig r = cmu_rig();
  const Skeleton& s = r.motion.skeleton;
  const TwoBoneChain leg = left_leg(s);
  const Vec3 hip = pos(r.model, leg.root);
  const double reach = (pos(r.model, leg.mid) - hip).norm() + (pos(r.model, leg.end) - pos(r.model, leg.mid)).norm();
  const Vec3 target = hip + Vec3(0, -0.8 * reach, 0.05);
  for (double side : {1.0, -1.0}) {
    for (const Vec3& axis : {Vec3(Vec3::UnitZ()), Vec3(Vec3::UnitX())}) {
      TwoBoneTarget t;
      t.position = target;
      t.hint = 0.5 * (hip + target) + side * 0.29 * axis;
      solve_two_bone(s, leg, t, r.pose.ref(), r.model);
      const Vec3 knee = pos(r.model, leg.mid);
      const Vec3 d = (target - hip).normalized();
      Vec3 bend = (knee - hip) - (knee - hip).dot(d) * d;
      Vec3 want = (t.hint - hip) - (t.hint - hip).dot(d) * d;
      EXPECT_GT(bend.normalized().dot(want.normalized()), 1 - 1e-9);
      EXPECT_LT((pos(r.model, leg.end) - target).norm(), 1e-5);
    }
  }
}

TEST(TwoBone, HintOnTheChainLineAndBadInputAreSafe) {
  Rig r = cmu_rig();
  const Skeleton& s = r.motion.skeleton;
  const TwoBoneChain leg = left_leg(s);
  const Vec3 hip = pos(r.model, leg.root);
  TwoBoneTarget t;
  t.position = hip + Vec3(0, -0.6, 0.1);
  t.hint = hip + 2.0 * (t.position - hip);  // on the hip-target line
  solve_two_bone(s, leg, t, r.pose.ref(), r.model);
  EXPECT_LT((pos(r.model, leg.end) - t.position).norm(), 1e-5);
  const Pose before = r.pose;
  t.position = Vec3(std::nan(""), 0, 0);
  solve_two_bone(s, leg, t, r.pose.ref(), r.model);
  for (std::size_t j = 0; j < before.rotations.size(); ++j)
    EXPECT_TRUE(before.rotations[j].isApprox(r.pose.rotations[j]));
}

TEST(TwoBone, WeightsBlendPositionAndRotation) {
  Rig r = cmu_rig();
  const Skeleton& s = r.motion.skeleton;
  const TwoBoneChain leg = left_leg(s);
  const Vec3 hip = pos(r.model, leg.root);
  const Vec3 start = pos(r.model, leg.end);
  TwoBoneTarget t;
  t.position = hip + Vec3(0.05, -0.6, 0.2);
  t.hint = hip + Vec3(0, -0.3, 0.5);
  t.position_weight = 0.5;
  solve_two_bone(s, leg, t, r.pose.ref(), r.model);
  EXPECT_LT((pos(r.model, leg.end) - 0.5 * (start + t.position)).norm(), 1e-5);
  t.position_weight = 1.0;
  t.rotation = Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
  t.rotation_weight = 1.0;
  solve_two_bone(s, leg, t, r.pose.ref(), r.model);
  std::vector<Transform> fk(r.model.size());
  forward_kinematics(s, r.pose, fk);
  EXPECT_LT(fk[static_cast<std::size_t>(leg.end)].rotation.angularDistance(t.rotation), 1e-9);
}

// ---- numeric oracle -------------------------------------------------------
// Chain a -> b -> c with bone vectors u (a->b) and v (b->c). The numeric solver
// rotates them by model-space rotation vectors p1 (root) and p2 (mid) and
// minimises |end - target|^2 + eps^2 |knee - H|^2, H a point far along the
// hint: among the knee circle of exact solutions, the closest to H is the one
// in the hint's half-plane, which is what the analytic solver promises.
struct NumericChain {
  Vec3 a, u, v;
  Vec3 knee(const Eigen::Matrix<double, 6, 1>& p) const { return a + rot(p.head<3>()) * u; }
  Vec3 end(const Eigen::Matrix<double, 6, 1>& p) const { return knee(p) + rot(p.tail<3>()) * (rot(p.head<3>()) * v); }
  static Quat rot(const Vec3& w) {
    const double n = w.norm();
    return n < 1e-15 ? Quat::Identity() : Quat(Eigen::AngleAxisd(n, w / n));
  }
};

Eigen::Matrix<double, 6, 1> residual(const NumericChain& ch, const Eigen::Matrix<double, 6, 1>& p, const Vec3& target,
                                     const Vec3& far_hint, double eps) {
  Eigen::Matrix<double, 6, 1> r;
  r.head<3>() = ch.end(p) - target;
  r.tail<3>() = eps * (ch.knee(p) - far_hint);
  return r;
}

Eigen::Matrix<double, 6, 1> solve_numeric(const NumericChain& ch, const Vec3& target, const Vec3& far_hint) {
  Eigen::Matrix<double, 6, 1> p = Eigen::Matrix<double, 6, 1>::Zero();
  for (double eps : {1e-1, 1e-2, 1e-3}) {
    double lambda = 1e-3;
    for (int it = 0; it < 400; ++it) {
      auto r = residual(ch, p, target, far_hint, eps);
      Eigen::Matrix<double, 6, 6> J;
      for (int k = 0; k < 6; ++k) {
        auto q = p;
        q[k] += 1e-7;
        J.col(k) = (residual(ch, q, target, far_hint, eps) - r) / 1e-7;
      }
      const Eigen::Matrix<double, 6, 6> A = J.transpose() * J + lambda * Eigen::Matrix<double, 6, 6>::Identity();
      const Eigen::Matrix<double, 6, 1> step = A.ldlt().solve(-J.transpose() * r);
      const auto trial = p + step;
      if (residual(ch, trial, target, far_hint, eps).squaredNorm() < r.squaredNorm()) {
        p = trial;
        lambda = std::max(lambda * 0.3, 1e-12);
      } else {
        lambda *= 10;
      }
      if (step.norm() < 1e-13) break;
    }
  }
  return p;
}

TEST(TwoBone, MatchesNumericSolverOnRandomChains) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> u(-1, 1), len(0.2, 0.6);
  int compared = 0;
  for (int trial = 0; trial < 40; ++trial) {
    Skeleton s;
    s.add_joint("root", -1, Vec3::Zero());
    s.add_joint("mid", 0, len(rng) * Vec3(u(rng), -1, u(rng) * 0.3).normalized());
    s.add_joint("end", 1, len(rng) * Vec3(u(rng) * 0.3, -1, u(rng)).normalized());
    Pose pose(s);
    pose.translations[0] = Vec3(u(rng), 1 + u(rng), u(rng));
    for (auto& q : pose.rotations) q = Quat(Eigen::AngleAxisd(0.5 * u(rng), Vec3(u(rng), u(rng), u(rng)).normalized()));
    std::vector<Transform> model(3);
    forward_kinematics(s, pose, model);
    const Vec3 a = model[0].translation;
    const double lab = (model[1].translation - a).norm(), lcb = (model[2].translation - model[1].translation).norm();
    const double lo = std::abs(lab - lcb), hi = lab + lcb;
    const double dist = lo + (hi - lo) * (0.15 + 0.8 * (0.5 + 0.5 * u(rng)));
    TwoBoneTarget t;
    t.position = a + dist * Vec3(u(rng), u(rng), u(rng)).normalized();
    t.hint = a + Vec3(u(rng), u(rng), u(rng));
    const Vec3 d = (t.position - a).normalized();
    Vec3 pole = (t.hint - a) - (t.hint - a).dot(d) * d;
    if (pole.norm() < 0.1) continue;
    NumericChain ch{a, model[1].translation - a, model[2].translation - model[1].translation};
    const auto p = solve_numeric(ch, t.position, a + 10.0 * pole.normalized());
    ASSERT_LT((ch.end(p) - t.position).norm(), 1e-4) << "numeric solver failed on chain " << trial;
    solve_two_bone(s, {0, 1, 2}, t, pose.ref(), model);
    EXPECT_LT((model[2].translation - t.position).norm(), 1e-5);
    EXPECT_LT((model[1].translation - ch.knee(p)).norm(), 2e-3) << "chain " << trial;
    ++compared;
  }
  EXPECT_GE(compared, 30);
}

}  // namespace
}  // namespace legwork::ik

// The real EuRoC V1_01 excerpt in ../shared/data evaluated against itself after known perturbations.
#include <gtest/gtest.h>

#include "synthetic.hpp"
#include "twinslam/eval/evaluate.hpp"
#include "twinslam/trajectory/io.hpp"

namespace twinslam::eval {
namespace {

Trajectory micro_gt() { return read_dataset_groundtruth(std::string(TWINSLAM_SHARED_DIR) + "/data/euroc-v1-01-micro"); }

TEST(EurocMicro, ReadsTheGroundTruth) {
  const Trajectory gt = micro_gt();
  EXPECT_EQ(gt.size(), 2895u);
  EXPECT_EQ(gt.poses.front().stamp_ns, 1'403'715'273'262'140'000);
}

TEST(EurocMicro, ConstantXOffsetWithoutAlignmentIsTheOffset) {
  const Trajectory gt = micro_gt();
  Trajectory est = gt;
  for (auto& pose : est.poses) pose.T_XB.translation().x() += 0.1;
  const EvalResult r = evaluate(gt, est, {});
  EXPECT_EQ(r.n, gt.size());
  EXPECT_NEAR(r.ate.pos.rmse, 0.1, 1e-9);
  EXPECT_NEAR(r.ate.pos.max, 0.1, 1e-9);
  EXPECT_NEAR(r.ate.rot.rmse, 0.0, 1e-9);
  EXPECT_NEAR(r.length_m, path_length(gt), 1e-9);
  // A translation is what se3 alignment removes.
  EvalConfig se3;
  se3.align = AlignMode::SE3;
  EXPECT_LT(evaluate(gt, est, se3).ate.pos.rmse, 1e-9);
}

TEST(EurocMicro, KnownYawAndShiftIsRemovedByPosYaw) {
  const Trajectory gt = micro_gt();
  Similarity S;
  S.R_WL = test::rotation_zyx(1.0, 0.0, 0.0);
  S.t_W = Eigen::Vector3d(-3.0, 4.0, 0.5);
  const Trajectory est = test::transformed(gt, S);
  const EvalResult none = evaluate(gt, est, {});
  EXPECT_GT(none.ate.pos.rmse, 1.0);
  EXPECT_NEAR(none.ate.rot.rmse, 180.0 / M_PI, 1e-9);  // 1 rad yaw on every pose
  EvalConfig posyaw;
  posyaw.align = AlignMode::PosYaw;
  const EvalResult aligned = evaluate(gt, est, posyaw);
  EXPECT_LT(aligned.ate.pos.rmse, 1e-9);
  EXPECT_LT(aligned.ate.rot.rmse, 1e-6);
}

TEST(EurocMicro, FiveMillisecondShiftAssociatesEveryPose) {
  const Trajectory gt = micro_gt();  // 20 Hz
  Trajectory est = gt;
  for (auto& pose : est.poses) pose.stamp_ns -= 5'000'000;
  const EvalResult r = evaluate(gt, est, {});
  EXPECT_EQ(r.n, gt.size());
  EXPECT_LT(r.ate.pos.max, 1e-12);
}

}  // namespace
}  // namespace twinslam::eval

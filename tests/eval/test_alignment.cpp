// Alignment recovers a known transform exactly (Umeyama for se3/sim3, closed-form yaw for posyaw).
#include <gtest/gtest.h>

#include "synthetic.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/eval/evaluate.hpp"

namespace twinslam::eval {
namespace {

Similarity known(double scale, double yaw, double pitch, double roll) {
  Similarity S;
  S.scale = scale;
  S.R_WL = test::rotation_zyx(yaw, pitch, roll);
  S.t_W = Eigen::Vector3d(12.5, -7.25, 3.0);
  return S;
}

void expect_recovered(const Similarity& got, const Similarity& want) {
  EXPECT_NEAR(got.scale, want.scale, 1e-9);
  EXPECT_LT((got.R_WL - want.R_WL).norm(), 1e-9);
  EXPECT_LT((got.t_W - want.t_W).norm(), 1e-9);
}

TEST(Alignment, Se3RecoversKnownRigidTransform) {
  const Trajectory gt = test::helix(2000);
  const Similarity S = known(1.0, 0.7, -0.3, 0.2);
  const Trajectory est = test::transformed(gt, test::inverse(S));  // estimate in L, S maps it back to W
  EvalConfig config;
  config.align = AlignMode::SE3;
  const EvalResult r = evaluate(gt, est, config);
  expect_recovered(r.S_WL, S);
  EXPECT_LT(r.ate.pos.rmse, 1e-9);
  EXPECT_LT(r.ate.rot.rmse, 1e-6);  // degrees; the angle of a 1e-15 rotation through atan2 is exact to ~1e-13 rad
}

TEST(Alignment, Sim3RecoversKnownSimilarity) {
  const Trajectory gt = test::helix(2000);
  const Similarity S = known(2.5, -1.2, 0.4, -0.1);
  const Trajectory est = test::transformed(gt, test::inverse(S));
  EvalConfig config;
  config.align = AlignMode::Sim3;
  const EvalResult r = evaluate(gt, est, config);
  expect_recovered(r.S_WL, S);
  EXPECT_LT(r.ate.pos.rmse, 1e-9);
}

TEST(Alignment, PosYawRecoversYawAndTranslation) {
  const Trajectory gt = test::helix(2000);
  const Similarity S = known(1.0, 2.9, 0.0, 0.0);  // yaw close to pi: no small-angle shortcut
  const Trajectory est = test::transformed(gt, test::inverse(S));
  EvalConfig config;
  config.align = AlignMode::PosYaw;
  const EvalResult r = evaluate(gt, est, config);
  expect_recovered(r.S_WL, S);
  EXPECT_LT(r.ate.pos.rmse, 1e-9);
}

TEST(Alignment, PosYawLeavesRollAndPitchErrorsVisible) {
  // A tilted estimate cannot be explained by yaw + translation: 4-DoF alignment must not hide it.
  const Trajectory gt = test::helix(2000);
  const Trajectory est = test::transformed(gt, known(1.0, 0.5, 0.1, 0.0));
  EvalConfig config;
  config.align = AlignMode::PosYaw;
  EXPECT_GT(evaluate(gt, est, config).ate.rot.rmse, 5.0);  // 0.1 rad pitch = 5.7 deg
}

TEST(Alignment, NoneKeepsTheEstimateAsIs) {
  const Trajectory gt = test::helix(500);
  const Trajectory est = test::transformed(gt, known(1.0, 0.0, 0.0, 0.0));  // shifted by |t_W|
  const EvalResult r = evaluate(gt, est, {});
  EXPECT_NEAR(r.ate.pos.rmse, Eigen::Vector3d(12.5, -7.25, 3.0).norm(), 1e-9);
  EXPECT_EQ(r.align_pairs, 0u);
}

TEST(Alignment, FirstNPairsOnlyUsesTheStart) {
  // The estimate equals S^-1 gt for the first 100 poses, then is pushed 1 m up: aligning on the first 100 poses
  // recovers S exactly, and the error afterwards is exactly the push.
  const Trajectory gt = test::helix(1000);
  const Similarity S = known(1.0, 0.3, 0.1, -0.2);
  Trajectory est = test::transformed(gt, test::inverse(S));
  for (std::size_t k = 100; k < est.size(); ++k) {
    est.poses[k].T_XB.translation() += S.R_WL.transpose() * Eigen::Vector3d(0, 0, 1.0);
  }
  EvalConfig config;
  config.align = AlignMode::SE3;
  config.align_first = 100;
  const EvalResult r = evaluate(gt, est, config);
  expect_recovered(r.S_WL, S);
  EXPECT_EQ(r.align_pairs, 100u);
  EXPECT_NEAR(r.ate.pos.max, 1.0, 1e-9);
  EXPECT_NEAR(r.ate.pos.min, 0.0, 1e-9);
}

TEST(Alignment, FirstPoseOnlyUsesItsOrientation) {
  const Trajectory gt = test::helix(300);
  const Similarity S = known(1.0, 0.8, 0.0, 0.0);
  const Trajectory est = test::transformed(gt, test::inverse(S));
  EvalConfig config;
  config.align = AlignMode::PosYaw;
  config.align_first = 1;
  expect_recovered(evaluate(gt, est, config).S_WL, S);
}

TEST(Alignment, Sim3NeedsThreePoses) {
  const Trajectory gt = test::helix(10);
  EvalConfig config;
  config.align = AlignMode::Sim3;
  config.align_first = 2;
  EXPECT_THROW(evaluate(gt, gt, config), InputError);
}

TEST(Alignment, ParsesModeNamesAndRejectsOthers) {
  EXPECT_EQ(parse_align_mode("posyaw"), AlignMode::PosYaw);
  EXPECT_EQ(to_string(parse_align_mode("sim3")), "sim3");
  try {
    parse_align_mode("se2");
    FAIL() << "se2 accepted";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("none, posyaw, se3 or sim3"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace twinslam::eval

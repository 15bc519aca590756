// GNSS fusion (issue 13, vio-gnss): the position factor's residual and Jacobians (against central differences), its
// whitening by the full covariance, and the provider's bookkeeping: a fix attaches to the nearest keyframe within
// max_dt_s, waits for one, is counted when none can come, and leaves with its keyframe into the prior.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include <ceres/ceres.h>

#include "twinslam/core/error.hpp"
#include "twinslam/estimator/gnss_provider.hpp"
#include "twinslam/estimator/imu_state.hpp"

namespace twinslam::estimator {
namespace {

using Vec3 = Eigen::Vector3d;

TEST(GnssPositionFactor, ResidualIsTheWhitenedAntennaErrorAndJacobiansEqualNumericOnes) {
  // Body at p_L with yaw 90 deg in L, moving at v_L; T_WL: yaw 30 deg and an offset; antenna 0.5 m ahead of B.
  const Vec3 lever_B(0.5, 0, 0.2);
  const double dt = 0.2;
  double pose[7] = {4.0, -2.0, 10.0, 0, 0, std::sin(M_PI / 4), std::cos(M_PI / 4)};  // q_LB x y z w
  double sb[9] = {1.0, 0.5, -0.2, 0, 0, 0, 0, 0, 0};
  double T_WL[4] = {100.0, 50.0, 3.0, 30.0 * M_PI / 180.0};
  // The antenna in L: p + v dt + R_LB l = (4 + 0.2 - 0, -2 + 0.1 + 0.5, 10 - 0.04 + 0.2).
  const Vec3 a_L(4.2, -1.4, 10.16);
  const double c = std::cos(T_WL[3]), s = std::sin(T_WL[3]);
  const Vec3 a_W(c * a_L.x() - s * a_L.y() + 100.0, s * a_L.x() + c * a_L.y() + 50.0, a_L.z() + 3.0);
  Eigen::Matrix3d cov;
  cov << 4.0, 1.0, 0.0, 1.0, 2.0, 0.5, 0.0, 0.5, 9.0;
  const Vec3 z_W = a_W + Vec3(1.0, -2.0, 0.5);
  std::unique_ptr<ceres::CostFunction> f(new_gnss_position_factor(z_W, cov, dt, lever_B));
  double r[3];
  const double* params[3] = {pose, sb, T_WL};
  ASSERT_TRUE(f->Evaluate(params, r, nullptr));
  // Whitened: r^T r = e^T C^-1 e for e = antenna - fix.
  const Vec3 e = a_W - z_W;
  EXPECT_NEAR(Eigen::Map<Vec3>(r).squaredNorm(), e.dot(cov.inverse() * e), 1e-9);
  Eigen::Matrix<double, 3, 7, Eigen::RowMajor> J_pose;
  Eigen::Matrix<double, 3, 9, Eigen::RowMajor> J_sb;
  Eigen::Matrix<double, 3, 4, Eigen::RowMajor> J_twl;
  double* jac[3] = {J_pose.data(), J_sb.data(), J_twl.data()};
  ASSERT_TRUE(f->Evaluate(params, r, jac));
  const auto numeric = [&](double* block, int i) {
    const double h = 1e-6, v = block[i];
    Vec3 rp, rm;
    block[i] = v + h;
    f->Evaluate(params, rp.data(), nullptr);
    block[i] = v - h;
    f->Evaluate(params, rm.data(), nullptr);
    block[i] = v;
    return Vec3((rp - rm) / (2 * h));
  };
  for (int i = 0; i < 7; ++i) EXPECT_LT((numeric(pose, i) - J_pose.col(i)).norm(), 1e-5 * (1 + J_pose.col(i).norm()));
  for (int i = 0; i < 9; ++i) EXPECT_LT((numeric(sb, i) - J_sb.col(i)).norm(), 1e-5 * (1 + J_sb.col(i).norm()));
  for (int i = 0; i < 4; ++i) EXPECT_LT((numeric(T_WL, i) - J_twl.col(i)).norm(), 1e-5 * (1 + J_twl.col(i).norm()));
  EXPECT_LT(J_sb.rightCols<6>().norm(), 1e-12);  // biases do not enter
}

struct Window {
  std::vector<std::array<double, 7>> pose;
  std::vector<std::array<double, 9>> sb;
  double T_WL[4] = {0, 0, 0, 0};
  WindowBlocks blocks;
  Window(const std::vector<std::int64_t>& stamps, const std::vector<bool>& keyframe)
      : pose(stamps.size(), {0, 0, 0, 0, 0, 0, 1}), sb(stamps.size(), {0, 0, 0, 0, 0, 0, 0, 0, 0}) {
    blocks.stamps_ns = stamps;
    blocks.is_keyframe = keyframe;
    for (std::size_t k = 0; k < stamps.size(); ++k) {
      blocks.pose.push_back(pose[k].data());
      blocks.speed_bias.push_back(sb[k].data());
    }
    blocks.T_WL = T_WL;
  }
};

TEST(GnssProvider, FixesAttachToTheNearestKeyframeWaitAndLeaveWithIt) {
  GnssProvider p;  // max_dt_s 0.5
  const std::int64_t s = 1'000'000'000;
  p.add_fix(1 * s + s / 10, Vec3(1, 2, 3), Eigen::Matrix3d::Identity());  // 0.1 s after keyframe 1 s
  p.add_fix(2 * s + 9 * s / 10, Vec3(1, 2, 3), Eigen::Matrix3d::Identity());  // 0.1 s before a keyframe not yet there
  p.add_fix(s / 10, Vec3(1, 2, 3), Eigen::Matrix3d::Identity());  // 0.1 s: long before the window
  Window w({1 * s, 2 * s, 2 * s + s / 2}, {true, true, false});
  std::vector<ResidualTerm> terms;
  p.add_terms(w.blocks, terms);
  EXPECT_TRUE(terms.empty());  // inactive until T_WL is set
  p.set_active(true);
  p.add_terms(w.blocks, terms);
  ASSERT_EQ(terms.size(), 1u);
  EXPECT_EQ(terms[0].blocks[0], w.blocks.pose[0]);       // on the 1 s keyframe
  EXPECT_EQ(terms[0].blocks[1], w.blocks.speed_bias[0]);
  EXPECT_EQ(terms[0].blocks[2], w.T_WL);
  EXPECT_EQ(p.counts().attached, 1u);
  EXPECT_EQ(p.counts().unmatched, 1u);  // the 0.1 s fix can never attach
  // A keyframe at 3 s arrives: the waiting fix attaches to it.
  Window w2({1 * s, 2 * s, 3 * s}, {true, true, true});
  terms.clear();
  p.add_terms(w2.blocks, terms);
  ASSERT_EQ(terms.size(), 2u);
  EXPECT_EQ(terms[1].blocks[0], w2.blocks.pose[2]);
  p.keyframe_marginalized(1 * s);
  terms.clear();
  p.add_terms(w2.blocks, terms);
  EXPECT_EQ(terms.size(), 1u);
  EXPECT_EQ(p.counts().marginalized, 1u);
}

TEST(GnssProvider, RefusesAFixWithoutAUsableCovariance) {
  GnssProvider p;
  EXPECT_THROW(p.add_fix(1, Vec3(0, 0, 0), Eigen::Matrix3d::Zero()), InputError);
  EXPECT_THROW(p.add_fix(1, Vec3(NAN, 0, 0), Eigen::Matrix3d::Identity()), InputError);
  GnssProviderConfig bad;
  bad.max_dt_s = 0;
  EXPECT_THROW(GnssProvider{bad}, InputError);
}

}  // namespace
}  // namespace twinslam::estimator

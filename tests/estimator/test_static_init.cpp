// Static initialization from rest on the real EuRoC excerpt: the gravity direction in the body frame agrees with
// the ground truth's within 1 degree, and motion is not mistaken for rest.
#include <cmath>

#include <gtest/gtest.h>

#include "twinslam/estimator/static_init.hpp"
#include "twinslam/ingest/dataset.hpp"
#include "twinslam/trajectory/io.hpp"

using namespace twinslam;

namespace {
std::vector<estimator::ImuSample> to_samples(const ingest::Dataset& ds, std::size_t begin, std::size_t end) {
  std::vector<estimator::ImuSample> out;
  for (std::size_t i = begin; i < end; ++i) out.push_back({ds.imu[i].stamp_ns, ds.imu[i].gyro_radps, ds.imu[i].accel_mps2});
  return out;
}
}  // namespace

TEST(StaticInit, EurocExcerptGravityWithinOneDegree) {
  const auto ds = ingest::load_dataset(std::string(TWINSLAM_SHARED_DIR) + "/data/euroc-v1-01-micro");
  // The first ~1.5 s (300 samples at 200 Hz), during which the MAV rests on the ground.
  const auto samples = to_samples(ds, 0, 300);
  const auto init = estimator::try_static_init(samples, {});
  ASSERT_TRUE(init.has_value());
  const auto gt = read_tum(std::string(TWINSLAM_SHARED_DIR) +
                                                   "/data/euroc-v1-01-micro/groundtruth.tum");
  // Ground-truth pose closest to the init stamp.
  const StampedPose* best = &gt.poses.front();
  for (const auto& p : gt.poses) {
    if (std::llabs(p.stamp_ns - init->stamp_ns) < std::llabs(best->stamp_ns - init->stamp_ns)) best = &p;
  }
  ASSERT_LT(std::llabs(best->stamp_ns - init->stamp_ns), 20'000'000);
  const Eigen::Vector3d up_B_gt = best->T_XB.linear().transpose() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d up_B_est = init->q_LB.toRotationMatrix().transpose() * Eigen::Vector3d::UnitZ();
  const double angle_deg = std::acos(std::clamp(up_B_gt.dot(up_B_est), -1.0, 1.0)) * 180.0 / M_PI;
  std::printf("gravity direction error vs ground truth: %.3f deg\n", angle_deg);
  EXPECT_LT(angle_deg, 1.0);
  // L has identity heading: the body x axis projects onto L's x-z plane.
  const Eigen::Vector3d x_L = init->q_LB * Eigen::Vector3d::UnitX();
  EXPECT_NEAR(x_L.y(), 0.0, 1e-9);
  EXPECT_GT(x_L.x(), 0.0);
  // Gyro bias: small (EuRoC's ADIS16448 has biases of order 1e-3..1e-2 rad/s).
  EXPECT_LT(init->bias.gyro.norm(), 0.1);
}

TEST(StaticInit, RejectsMotionAndShortHistory) {
  std::vector<estimator::ImuSample> moving;
  for (int i = 0; i < 400; ++i) {
    const double t = i * 0.005;
    moving.push_back({static_cast<std::int64_t>(t * 1e9), Eigen::Vector3d(0, 0, 0.8 * std::sin(3 * t)),
                      Eigen::Vector3d(4.0 * std::sin(4 * t), 0, 9.81)});
  }
  EXPECT_FALSE(estimator::try_static_init(moving, {}).has_value());
  std::vector<estimator::ImuSample> still(50, {0, Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 9.81)});
  for (int i = 0; i < 50; ++i) still[i].stamp_ns = i * 5'000'000LL;  // only 0.25 s
  EXPECT_FALSE(estimator::try_static_init(still, {}).has_value());
}

TEST(StaticInit, TiltedRestRecoversRollAndPitch) {
  const Eigen::Quaterniond q_true = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()) *
                                                       Eigen::AngleAxisd(-0.2, Eigen::Vector3d::UnitY()));
  const Eigen::Vector3d f_B = q_true.conjugate() * Eigen::Vector3d(0, 0, 9.81);
  std::vector<estimator::ImuSample> s;
  for (int i = 0; i < 300; ++i) s.push_back({i * 5'000'000LL, Eigen::Vector3d(0.01, -0.02, 0.003), f_B});
  const auto init = estimator::try_static_init(s, {});
  ASSERT_TRUE(init.has_value());
  const Eigen::Vector3d up_est = init->q_LB.conjugate() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d up_true = q_true.conjugate() * Eigen::Vector3d::UnitZ();
  EXPECT_LT((up_est - up_true).norm(), 1e-9);
  EXPECT_LT((init->bias.gyro - Eigen::Vector3d(0.01, -0.02, 0.003)).norm(), 1e-12);
}

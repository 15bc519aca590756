// Noise model: covariance against closed-form answers and a Monte Carlo run, and loading EuRoC's sensor.yaml.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>

#include "imu_test_utils.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/estimator/preintegration.hpp"
#include "twinslam/geometry/so3.hpp"

namespace est = twinslam::estimator;
namespace ts = twinslam::testing;
namespace tg = twinslam::geometry;

TEST(PreintegrationNoise, CovarianceOfANonRotatingUnacceleratedImuHasTheRandomWalkForm) {
  // With zero rate and zero specific force nothing couples: rotation and velocity errors are random walks
  // (variance density^2 T) and position the integrated random walk (density^2 T^3 / 3).
  std::vector<est::ImuSample> samples;
  for (std::int64_t t = 0; t <= 2'000'000'000; t += 5'000'000) {
    samples.push_back({t, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()});
  }
  for (auto method : {est::ImuIntegration::kMidpoint, est::ImuIntegration::kEuler}) {
    est::PreintegrationConfig c;
    c.integration = method;
    const est::Preintegration pre(c, {}, samples, 0, 2'000'000'000);
    const double T = 2.0, sg = c.noise.gyroscope_noise_density, sa = c.noise.accelerometer_noise_density;
    const auto& P = pre.covariance();
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(P(k, k), sg * sg * T, 1e-6 * sg * sg * T);
      EXPECT_NEAR(P(3 + k, 3 + k), sa * sa * T, 1e-6 * sa * sa * T);
      EXPECT_NEAR(P(6 + k, 6 + k), sa * sa * T * T * T / 3.0, 1e-3 * sa * sa * T * T * T / 3.0);
    }
    // Bias random walk blocks of the 15x15 factor covariance.
    const auto Q = pre.residual_covariance();
    EXPECT_NEAR(Q(9, 9), std::pow(c.noise.gyroscope_random_walk, 2) * T, 1e-20);
    EXPECT_NEAR(Q(14, 14), std::pow(c.noise.accelerometer_random_walk, 2) * T, 1e-16);
    // The whitening matrix inverts the covariance.
    const auto& S = pre.sqrt_information();
    EXPECT_LT((S * Q * S.transpose() - Eigen::Matrix<double, 15, 15>::Identity()).norm(), 1e-8);
  }
}

TEST(PreintegrationNoise, MonteCarloErrorsMatchThePropagatedCovariance) {
  // Noisy runs on the moving trajectory: the errors whitened by the predicted covariance must have the chi-square
  // mean of 9 (one per dimension), and each variance must be within 25% of its prediction.
  const ts::AnalyticTrajectory traj;
  est::PreintegrationConfig c;
  c.noise.gyroscope_noise_density = 5e-3;  // large enough that integration error is negligible in comparison
  c.noise.accelerometer_noise_density = 5e-2;
  const auto clean = ts::simulate_imu(traj, 0, 1'200'000'000, 200.0);
  const est::Preintegration reference(c, {}, clean, 300'000'000, 1'100'000'000);
  const Eigen::Matrix<double, 9, 9> P = reference.covariance();
  const Eigen::Matrix<double, 9, 9> P_inv = P.inverse();

  std::mt19937 rng(42);
  const int runs = 1000;
  Eigen::Matrix<double, 9, 9> sample_cov = Eigen::Matrix<double, 9, 9>::Zero();
  double chi2 = 0.0;
  for (int run = 0; run < runs; ++run) {
    auto noisy = clean;
    ts::add_white_noise(noisy, c.noise, 200.0, rng);
    const est::Preintegration pre(c, {}, noisy, 300'000'000, 1'100'000'000);
    Eigen::Matrix<double, 9, 1> e;
    e.segment<3>(0) = tg::so3_log(reference.delta().R.transpose() * pre.delta().R);  // dR_noisy = dR Exp(dphi)
    e.segment<3>(3) = pre.delta().v - reference.delta().v;
    e.segment<3>(6) = pre.delta().p - reference.delta().p;
    sample_cov += e * e.transpose() / runs;
    chi2 += e.dot(P_inv * e) / runs;
  }
  EXPECT_NEAR(chi2, 9.0, 0.6);  // std of the mean is sqrt(18 / 1000) = 0.13
  for (int k = 0; k < 9; ++k) EXPECT_NEAR(sample_cov(k, k) / P(k, k), 1.0, 0.25) << "dimension " << k;
}

TEST(ImuNoise, LoadsEurocSensorYaml) {
  const est::ImuNoise n =
      est::load_imu_noise(std::filesystem::path(TWINSLAM_SHARED_DIR) / "data/euroc-v1-01-micro/mav0/imu0/sensor.yaml");
  EXPECT_DOUBLE_EQ(n.gyroscope_noise_density, 1.6968e-04);
  EXPECT_DOUBLE_EQ(n.gyroscope_random_walk, 1.9393e-05);
  EXPECT_DOUBLE_EQ(n.accelerometer_noise_density, 2.0e-3);
  EXPECT_DOUBLE_EQ(n.accelerometer_random_walk, 3.0e-3);
  EXPECT_DOUBLE_EQ(n.rate_hz, 200.0);
}

namespace {

std::string load_error(const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("imu_noise_test_" + std::to_string(::getpid()) + ".yaml");
  std::ofstream(path) << text;
  std::string what = "no error";
  try {
    est::load_imu_noise(path);
  } catch (const twinslam::InputError& e) {
    what = e.what();
  }
  std::filesystem::remove(path);
  return what;
}

}  // namespace

TEST(ImuNoise, BadFilesNameTheFileAndTheProblem) {
  const std::string ok_tail = "accelerometer_noise_density: 2.0e-3\naccelerometer_random_walk: 3.0e-3\nrate_hz: 200\n";
  const std::string missing = load_error("%YAML:1.0\ngyroscope_noise_density: 1e-4\n" + ok_tail);
  EXPECT_NE(missing.find("imu_noise_test_"), std::string::npos) << missing;
  EXPECT_NE(missing.find("missing key gyroscope_random_walk"), std::string::npos) << missing;

  const std::string text =
      load_error("gyroscope_noise_density: abc\ngyroscope_random_walk: 1e-5\n" + ok_tail);
  EXPECT_NE(text.find("gyroscope_noise_density is not a number"), std::string::npos) << text;

  const std::string negative =
      load_error("gyroscope_noise_density: -1e-4\ngyroscope_random_walk: 1e-5\n" + ok_tail);
  EXPECT_NE(negative.find("gyroscope_noise_density must be finite and > 0"), std::string::npos) << negative;

  EXPECT_NE(load_error("[1, 2").find("malformed YAML"), std::string::npos);
  EXPECT_THROW(est::load_imu_noise("/nonexistent/sensor.yaml"), twinslam::InputError);
}

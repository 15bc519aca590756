#include "twinslam/estimator/static_init.hpp"

#include <cmath>

#include "twinslam/core/error.hpp"

namespace twinslam::estimator {

void StaticInitConfig::validate() const {
  auto positive = [](double v, const char* name) {
    if (!(v > 0) || !std::isfinite(v)) throw InputError(std::string("static_init.") + name + ": must be > 0");
  };
  positive(window_s, "window_s");
  positive(max_accel_std_mps2, "max_accel_std_mps2");
  positive(max_gyro_std_radps, "max_gyro_std_radps");
  positive(gravity_mps2, "gravity_mps2");
  positive(max_gravity_error_mps2, "max_gravity_error_mps2");
}

std::optional<StaticInitResult> try_static_init(const std::vector<ImuSample>& samples, const StaticInitConfig& cfg) {
  if (samples.size() < 2) return std::nullopt;
  const std::int64_t t_end = samples.back().stamp_ns;
  const std::int64_t t_begin = t_end - static_cast<std::int64_t>(cfg.window_s * 1e9);
  if (samples.front().stamp_ns > t_begin) return std::nullopt;  // not enough history yet

  Eigen::Vector3d sum_a = Eigen::Vector3d::Zero(), sum_w = Eigen::Vector3d::Zero();
  Eigen::Vector3d sum_a2 = Eigen::Vector3d::Zero(), sum_w2 = Eigen::Vector3d::Zero();
  std::size_t n = 0;
  for (auto it = samples.rbegin(); it != samples.rend() && it->stamp_ns >= t_begin; ++it, ++n) {
    sum_a += it->accel_B;
    sum_w += it->gyro_B;
    sum_a2 += it->accel_B.cwiseAbs2();
    sum_w2 += it->gyro_B.cwiseAbs2();
  }
  if (n < 10) return std::nullopt;
  const Eigen::Vector3d mean_a = sum_a / n, mean_w = sum_w / n;
  const Eigen::Vector3d std_a = (sum_a2 / n - mean_a.cwiseAbs2()).cwiseMax(0).cwiseSqrt();
  const Eigen::Vector3d std_w = (sum_w2 / n - mean_w.cwiseAbs2()).cwiseMax(0).cwiseSqrt();
  if (std_a.maxCoeff() > cfg.max_accel_std_mps2 || std_w.maxCoeff() > cfg.max_gyro_std_radps) return std::nullopt;
  if (std::abs(mean_a.norm() - cfg.gravity_mps2) > cfg.max_gravity_error_mps2) return std::nullopt;

  // At rest a_B = -R_LB^T g_L = R_LB^T e_z |g|: the rotation taking the measured "up" in B to e_z of L.
  // FromTwoVectors gives the minimal such rotation; its yaw is then removed so L has identity heading.
  const Eigen::Quaterniond q_min = Eigen::Quaterniond::FromTwoVectors(mean_a.normalized(), Eigen::Vector3d::UnitZ());
  const Eigen::Matrix3d R = q_min.toRotationMatrix();
  const double yaw = std::atan2(R(1, 0), R(0, 0));
  StaticInitResult out;
  out.stamp_ns = t_end;
  out.q_LB = (Eigen::AngleAxisd(-yaw, Eigen::Vector3d::UnitZ()) * q_min).normalized();
  out.bias.gyro = mean_w;
  return out;
}

}  // namespace twinslam::estimator

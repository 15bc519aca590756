#include "twinslam/estimator/registration_gate.hpp"

#include <cmath>
#include <cstdio>

#include <Eigen/Cholesky>

#include "twinslam/core/error.hpp"
#include "twinslam/geometry/so3.hpp"

namespace twinslam::estimator {
namespace {

constexpr double kDegToRad = 0.017453292519943295;

std::string format(const char* pattern, double a, double b) {
  char buf[200];
  std::snprintf(buf, sizeof buf, pattern, a, b);
  return buf;
}

}  // namespace

void RegistrationGateConfig::validate() const {
  const std::pair<const char*, double> nonneg[] = {{"registration_gate_max_mahalanobis_sq", max_mahalanobis_sq},
                                                   {"registration_gate_floor_m", floor_m},
                                                   {"registration_gate_floor_deg", floor_deg},
                                                   {"registration_gate_max_correction_m", max_correction_m},
                                                   {"registration_gate_max_correction_deg", max_correction_deg}};
  for (const auto& [name, v] : nonneg) {
    if (!(v >= 0.0) || !std::isfinite(v)) throw InputError(std::string("global fusion: ") + name + " must be >= 0");
  }
}

Eigen::Matrix<double, 6, 1> correction_about(const Eigen::Isometry3d& correction_W, const Eigen::Vector3d& p_WB) {
  Eigen::Matrix<double, 6, 1> xi;
  xi << geometry::so3_log(correction_W.linear()), correction_W * p_WB - p_WB;
  return xi;
}

std::string registration_refusal(const RegistrationGateConfig& config, const RegistrationGateInput& in) {
  const Eigen::Matrix<double, 6, 1> xi = correction_about(in.correction_W, in.T_WB.translation());
  if (in.declared) {
    const double moved_m = xi.tail<3>().norm(), turned_deg = xi.head<3>().norm() / kDegToRad;
    if (config.max_correction_m > 0.0 && moved_m > config.max_correction_m) {
      return format("correction moves the keyframe %.2f m > registration_gate_max_correction_m %.2f", moved_m,
                    config.max_correction_m);
    }
    if (config.max_correction_deg > 0.0 && turned_deg > config.max_correction_deg) {
      return format("correction turns the keyframe %.2f deg > registration_gate_max_correction_deg %.2f", turned_deg,
                    config.max_correction_deg);
    }
  }
  if (in.readmitted || !in.covariance || config.max_mahalanobis_sq <= 0.0) return "";
  Eigen::Matrix<double, 6, 6> S = *in.covariance;
  S.diagonal().head<3>().array() += std::pow(config.floor_deg * kDegToRad, 2);
  S.diagonal().tail<3>().array() += config.floor_m * config.floor_m;
  const Eigen::LLT<Eigen::Matrix<double, 6, 6>> llt(S);
  if (llt.info() != Eigen::Success || !S.allFinite()) return "";  // no usable covariance: test 2 only
  const double d2 = xi.dot(llt.solve(xi));
  if (d2 > config.max_mahalanobis_sq) {
    return format("correction's Mahalanobis distance^2 %.1f under the estimator's covariance > "
                  "registration_gate_max_mahalanobis_sq %.1f",
                  d2, config.max_mahalanobis_sq);
  }
  return "";
}

}  // namespace twinslam::estimator

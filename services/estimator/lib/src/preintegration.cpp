#include "twinslam/estimator/preintegration.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Cholesky>

#include "twinslam/core/error.hpp"
#include "twinslam/geometry/so3.hpp"

namespace twinslam::estimator {

namespace g = twinslam::geometry;

void PreintegrationConfig::validate() const {
  noise.validate();
  if (!(repropagate_gyro_bias > 0.0) || !std::isfinite(repropagate_gyro_bias)) {
    throw InputError("preintegration: repropagate_gyro_bias must be finite and > 0");
  }
  if (!(repropagate_accel_bias > 0.0) || !std::isfinite(repropagate_accel_bias)) {
    throw InputError("preintegration: repropagate_accel_bias must be finite and > 0");
  }
  if (!(gap_s > 0.0) || !std::isfinite(gap_s)) throw InputError("preintegration: gap_s must be finite and > 0");
  if (!(gap_gyro_sigma >= 0.0) || !std::isfinite(gap_gyro_sigma) || !(gap_accel_sigma >= 0.0) ||
      !std::isfinite(gap_accel_sigma)) {
    throw InputError("preintegration: gap_gyro_sigma and gap_accel_sigma must be finite and >= 0");
  }
}

namespace {

std::string stamp(std::int64_t t) { return std::to_string(t) + " ns"; }

}  // namespace

Preintegration::Preintegration(const PreintegrationConfig& config, const ImuBias& linearization_bias,
                               std::span<const ImuSample> samples, std::int64_t t_i_ns, std::int64_t t_j_ns)
    : config_(config), bias_bar_(linearization_bias), t_i_ns_(t_i_ns), t_j_ns_(t_j_ns) {
  config_.validate();
  if (t_j_ns <= t_i_ns) {
    throw InputError("preintegration: keyframe stamps must increase (t_i " + stamp(t_i_ns) + ", t_j " + stamp(t_j_ns) +
                     ")");
  }
  // Nodes: interpolated sample at t_i, every sample strictly inside (t_i, t_j), interpolated sample at t_j; the
  // samples are validated there (order, finite values, coverage).
  nodes_ = imu::integration_nodes(samples, t_i_ns, t_j_ns);
  propagate();
}

void Preintegration::repropagate(const ImuBias& linearization_bias) {
  bias_bar_ = linearization_bias;
  propagate();
}

bool Preintegration::repropagate_if_needed(const ImuBias& bias) {
  if ((bias.gyro - bias_bar_.gyro).norm() <= config_.repropagate_gyro_bias &&
      (bias.accel - bias_bar_.accel).norm() <= config_.repropagate_accel_bias) {
    return false;
  }
  repropagate(bias);
  return true;
}

void Preintegration::propagate() {
  delta_ = PreintegratedDelta{};
  jac_ = PreintegrationBiasJacobians{};
  cov_.setZero();
  longest_gap_s_ = 0.0;
  for (std::size_t k = 0; k + 1 < nodes_.size(); ++k) step(nodes_[k], nodes_[k + 1]);
  // Products of hundreds of rotations drift off SO(3) by round-off; project once at the end.
  delta_.R = g::so3_normalize(delta_.R);
  dt_ = 1e-9 * static_cast<double>(t_j_ns_ - t_i_ns_);

  // S = L^-1 with L L^T = Sigma gives S^T S = Sigma^-1 (the square-root information used to whiten the residual).
  const Eigen::LLT<Matrix15d> llt(residual_covariance());
  sqrt_info_ = llt.matrixL().solve(Matrix15d::Identity());
}

// One integration step from node a to node b. The error state is x = [dphi, dv, dp] with dR_true = dR Exp(dphi);
// for the step we write the mean acceleration in frame B_i as acc and its first-order perturbation as
//   d(acc) = A_phi dphi + A_bg db_g + A_ba db_a (+ the same matrices times the measurement noise),
// which gives the error-state transition F, the noise/bias input matrix G, and
//   Sigma <- F Sigma F^T + G Q G^T   (Forster App. A)
//   J_b   <- F J_b + G               (Forster App. B; the same recursion, exact for the discrete scheme, so the
//                                      first-order bias update agrees with repropagation up to O(db^2)).
// For kEuler (acc = dR a_k) these reduce to Forster's matrices: A_phi = -dR [a]x, A_bg = 0, A_ba = -dR.
void Preintegration::step(const ImuSample& a, const ImuSample& b) {
  const double h = 1e-9 * static_cast<double>(b.stamp_ns - a.stamp_ns);  // [s]
  if (h <= 0.0) return;
  const bool midpoint = config_.integration == ImuIntegration::kMidpoint;

  const Eigen::Vector3d w = (midpoint ? 0.5 * (a.gyro_B + b.gyro_B) : a.gyro_B) - bias_bar_.gyro;  // [rad/s]
  const Eigen::Vector3d a0 = a.accel_B - bias_bar_.accel;                                          // [m/s^2]
  const Eigen::Vector3d a1 = midpoint ? Eigen::Vector3d(b.accel_B - bias_bar_.accel) : a0;
  const Eigen::Matrix3d dRk = g::so3_exp(w * h);              // rotation over the step, B_k -> B_k+1
  const Eigen::Matrix3d Jr = g::so3_right_jacobian(w * h);
  const Eigen::Matrix3d& R0 = delta_.R;                       // dR_ik
  const Eigen::Matrix3d R1 = R0 * dRk;                        // dR_i,k+1

  Eigen::Vector3d acc;
  Eigen::Matrix3d A_phi, A_bg, A_ba;
  if (midpoint) {
    acc = 0.5 * (R0 * a0 + R1 * a1);
    A_phi = -0.5 * (R0 * g::skew(a0) + R1 * g::skew(a1) * dRk.transpose());
    A_bg = 0.5 * R1 * g::skew(a1) * Jr * h;
    A_ba = -0.5 * (R0 + R1);
  } else {
    acc = R0 * a0;
    A_phi = -R0 * g::skew(a0);
    A_bg.setZero();
    A_ba = -R0;
  }

  // Error-state transition F = [F_RR 0 0; F_vR I 0; F_pR hI I] and input matrix G = [G_Rg 0; G_vg G_va; G_pg G_pa].
  const Eigen::Matrix3d F_RR = dRk.transpose();
  const Eigen::Matrix3d F_vR = A_phi * h;
  const Eigen::Matrix3d F_pR = 0.5 * A_phi * h * h;
  const Eigen::Matrix3d G_g[3] = {-Jr * h, A_bg * h, 0.5 * A_bg * h * h};
  const Eigen::Matrix3d G_a[3] = {Eigen::Matrix3d::Zero(), A_ba * h, 0.5 * A_ba * h * h};

  // Sigma <- F Sigma F^T + G Q G^T with Q = diag(qg I, qa I), by 3x3 blocks: F is sparse and dense 9x9 products
  // cost several times more. Discrete white noise of the sample interval: Cov(eta_d) = sigma^2 / h (Forster Sec. IV).
  double qg = config_.noise.gyroscope_noise_density * config_.noise.gyroscope_noise_density / h;
  double qa = config_.noise.accelerometer_noise_density * config_.noise.accelerometer_noise_density / h;
  longest_gap_s_ = std::max(longest_gap_s_, h);
  if (h > config_.gap_s) {
    // A gap: the rate and acceleration inside it deviate from the interpolation by an unknown constant of the gap
    // sigmas, which enters through the same G as the white noise (variance sigma^2 instead of sigma_d^2 / h).
    qg += config_.gap_gyro_sigma * config_.gap_gyro_sigma;
    qa += config_.gap_accel_sigma * config_.gap_accel_sigma;
  }
  Eigen::Matrix3d M[3][3];  // M = F Sigma
  for (int c = 0; c < 3; ++c) {
    const Eigen::Matrix3d P0 = cov_.block<3, 3>(0, 3 * c), P1 = cov_.block<3, 3>(3, 3 * c),
                          P2 = cov_.block<3, 3>(6, 3 * c);
    M[0][c] = F_RR * P0;
    M[1][c] = F_vR * P0 + P1;
    M[2][c] = F_pR * P0 + h * P1 + P2;
  }
  for (int r = 0; r < 3; ++r) {
    // Row r of M F^T: columns F^T = [F_RR^T F_vR^T F_pR^T; 0 I hI; 0 0 I].
    const Eigen::Matrix3d out[3] = {M[r][0] * F_RR.transpose(), M[r][0] * F_vR.transpose() + M[r][1],
                                    M[r][0] * F_pR.transpose() + h * M[r][1] + M[r][2]};
    for (int c = r; c < 3; ++c) {
      Eigen::Matrix3d block = out[c] + qg * G_g[r] * G_g[c].transpose();
      if (r > 0) block += qa * G_a[r] * G_a[c].transpose();
      cov_.block<3, 3>(3 * r, 3 * c) = block;
      if (c != r) cov_.block<3, 3>(3 * c, 3 * r) = block.transpose();
    }
  }

  // Bias Jacobians: J <- F J + G, written out block by block (dphi, dv, dp rows; b_g, b_a columns).
  jac_.dp_dbg += jac_.dv_dbg * h + 0.5 * h * h * (A_phi * jac_.dR_dbg + A_bg);
  jac_.dp_dba += jac_.dv_dba * h + 0.5 * h * h * A_ba;
  jac_.dv_dbg += h * (A_phi * jac_.dR_dbg + A_bg);
  jac_.dv_dba += h * A_ba;
  jac_.dR_dbg = dRk.transpose() * jac_.dR_dbg - Jr * h;

  // Mean (Forster Sec. V-A, in iterative form).
  delta_.p += delta_.v * h + 0.5 * acc * h * h;
  delta_.v += acc * h;
  delta_.R = R1;
}

PreintegratedDelta Preintegration::corrected(const ImuBias& bias) const {
  // Forster eq. 44: first-order update of the measurements for a bias change db = b - b_bar.
  const Eigen::Vector3d dbg = bias.gyro - bias_bar_.gyro;
  const Eigen::Vector3d dba = bias.accel - bias_bar_.accel;
  PreintegratedDelta out;
  out.R = delta_.R * g::so3_exp(jac_.dR_dbg * dbg);
  out.v = delta_.v + jac_.dv_dbg * dbg + jac_.dv_dba * dba;
  out.p = delta_.p + jac_.dp_dbg * dbg + jac_.dp_dba * dba;
  return out;
}

Preintegration::Matrix15d Preintegration::residual_covariance() const {
  Matrix15d cov = Matrix15d::Zero();
  cov.topLeftCorner<9, 9>() = cov_;
  const double wg = config_.noise.gyroscope_random_walk;
  const double wa = config_.noise.accelerometer_random_walk;
  cov.block<3, 3>(9, 9) = wg * wg * dt_ * Eigen::Matrix3d::Identity();
  cov.block<3, 3>(12, 12) = wa * wa * dt_ * Eigen::Matrix3d::Identity();
  return cov;
}

}  // namespace twinslam::estimator

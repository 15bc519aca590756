#pragma once
// Shared helpers of the visual-factor tests and benchmarks: a camera mounted on the body, random poses, and
// Ridders' numeric Jacobians of any cost function for comparison with analytic ones.
#include <cmath>
#include <random>
#include <vector>

#include <ceres/ceres.h>
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "twinslam/estimator/imu_state.hpp"
#include "twinslam/geometry/quaternion.hpp"
#include "twinslam/geometry/se3.hpp"

namespace twinslam::testing {

// Camera looking along body x (forward), image x = -body y, image y = -body z, mounted a few cm off the IMU.
inline Eigen::Isometry3d forward_camera_T_BC() {
  Eigen::Matrix3d R_BC;
  R_BC << 0, 0, 1,  //
      -1, 0, 0,     //
      0, -1, 0;
  return geometry::make_pose(R_BC, Eigen::Vector3d(0.05, 0.01, -0.02));
}

inline Eigen::Vector3d random_vector(std::mt19937& rng, double sigma) {
  std::normal_distribution<double> n(0.0, sigma);
  return Eigen::Vector3d(n(rng), n(rng), n(rng));
}

inline void pack_pose(const Eigen::Isometry3d& T_LB, double* pose) {
  Eigen::Map<Eigen::Vector3d>{pose} = T_LB.translation();
  Eigen::Map<Eigen::Vector4d>{pose + 3} = Eigen::Quaterniond(T_LB.linear()).normalized().coeffs();
}

inline Eigen::Isometry3d random_pose(std::mt19937& rng, double position_sigma = 2.0) {
  return geometry::make_pose(geometry::quaternion_exp(random_vector(rng, 1.5)), random_vector(rng, position_sigma));
}

// Analytic Jacobians of `cost` at `params` (row-major blocks) as dense matrices.
inline std::vector<Eigen::MatrixXd> analytic_jacobians(const ceres::CostFunction& cost,
                                                       const std::vector<double*>& params,
                                                       Eigen::VectorXd* residual = nullptr) {
  const int m = cost.num_residuals();
  const auto& sizes = cost.parameter_block_sizes();
  std::vector<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> rm;
  std::vector<double*> ptrs;
  for (int s : sizes) rm.emplace_back(m, s);
  for (auto& J : rm) ptrs.push_back(J.data());
  Eigen::VectorXd r(m);
  cost.Evaluate(params.data(), r.data(), ptrs.data());
  if (residual != nullptr) *residual = r;
  return {rm.begin(), rm.end()};
}

// Numeric Jacobians of `cost` at `params` by the five-point central stencil
//   f'(x) ~= (-f(x + 2h) + 8 f(x + h) - 8 f(x - h) + f(x - 2h)) / (12 h),
// truncation O(h^4), as dense matrices (num_residuals x block size). Differentiates the ambient coordinates, like the
// analytic Jacobians. h = 1e-4 keeps truncation (~1e-16) and round-off (~eps |r| / h ~ 1e-11) far below 1e-6 relative.
// (Ceres' DynamicNumericDiffCostFunction with RIDDERS stopped early on some of these residuals, 1e-4 off.)
inline std::vector<Eigen::MatrixXd> numeric_jacobians(const ceres::CostFunction& cost,
                                                      const std::vector<double*>& params, double h = 1e-4) {
  const int m = cost.num_residuals();
  std::vector<Eigen::MatrixXd> out;
  auto eval = [&](std::size_t b, int k, double offset) {
    const double x = params[b][k];
    params[b][k] = x + offset;
    Eigen::VectorXd r(m);
    cost.Evaluate(params.data(), r.data(), nullptr);
    params[b][k] = x;
    return r;
  };
  for (std::size_t b = 0; b < params.size(); ++b) {
    const int size = cost.parameter_block_sizes()[b];
    Eigen::MatrixXd J(m, size);
    for (int k = 0; k < size; ++k) {
      J.col(k) = (-eval(b, k, 2 * h) + 8 * eval(b, k, h) - 8 * eval(b, k, -h) + eval(b, k, -2 * h)) / (12 * h);
    }
    out.push_back(J);
  }
  return out;
}

inline double max_relative_error(const Eigen::MatrixXd& analytic, const Eigen::MatrixXd& numeric) {
  return (analytic - numeric).cwiseAbs().maxCoeff() / numeric.cwiseAbs().maxCoeff();
}

}  // namespace twinslam::testing

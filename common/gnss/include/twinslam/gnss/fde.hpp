#pragma once
// Fault detection and exclusion on least-squares residuals (Baarda's data snooping): the global test compares the
// weighted sum of squared residuals with the chi-square quantile for the redundancy; when it fails, the observation
// with the largest standardized residual w_i = v_i / sqrt(Q_vv,ii) is the one to exclude.
#include <Eigen/Core>

namespace twinslam::gnss {

// Upper quantile of the chi-square distribution: x with P(X > x) = alpha for `dof` >= 1 degrees of freedom
// (Boost.Math).
double chi_square_quantile(int dof, double alpha);

// Standardized residuals of a weighted least-squares solution: H (n x m) the Jacobian, sigma (n) the observations'
// standard deviations, v (n) their residuals. Q_vv = diag(sigma^2) - H (H^T W H)^-1 H^T.
Eigen::VectorXd standardized_residuals(const Eigen::MatrixXd& H, const Eigen::VectorXd& sigma,
                                       const Eigen::VectorXd& v);

}  // namespace twinslam::gnss

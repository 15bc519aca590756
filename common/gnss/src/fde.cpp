#include "twinslam/gnss/fde.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>
#include <boost/math/distributions/chi_squared.hpp>

namespace twinslam::gnss {

double chi_square_quantile(int dof, double alpha) {
  const boost::math::chi_squared_distribution<double> chi2(dof);
  return boost::math::quantile(boost::math::complement(chi2, alpha));
}

Eigen::VectorXd standardized_residuals(const Eigen::MatrixXd& H, const Eigen::VectorXd& sigma,
                                       const Eigen::VectorXd& v) {
  const Eigen::VectorXd w = sigma.array().square().inverse().matrix();
  const Eigen::MatrixXd N = H.transpose() * w.asDiagonal() * H;
  const Eigen::MatrixXd N_inv = N.ldlt().solve(Eigen::MatrixXd::Identity(N.rows(), N.cols()));
  Eigen::VectorXd out(v.size());
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    // Q_vv,ii = sigma_i^2 - h_i N^-1 h_i^T; clamped because an observation with no redundancy has Q_vv,ii = 0.
    const double q = sigma[i] * sigma[i] - H.row(i) * N_inv * H.row(i).transpose();
    out[i] = v[i] / std::sqrt(std::max(q, 1e-12 * sigma[i] * sigma[i]));
  }
  return out;
}

}  // namespace twinslam::gnss

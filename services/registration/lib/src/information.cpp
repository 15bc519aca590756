// Information of a registration (see information.hpp for the 6-vector and the normalization).
#include "twinslam/registration/information.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

namespace twinslam::registration {
namespace {

// Eigen-analysis of Hn = S H_w S / n, n the summed weight (ascending); fills eigenvalues, directions, zeroed, and
// returns the information with the zeroed directions removed: S^-1 (U L' U^T) S^-1 * n, i.e. H_w itself when nothing
// is zeroed.
Matrix6d analyse(const RegistrationConfig& config, double n, Information& info) {
  Vector6d s;
  s << Eigen::Vector3d::Constant(1.0 / info.length_scale_m), Eigen::Vector3d::Ones();
  const Matrix6d Hn = s.asDiagonal() * info.H_weighted * s.asDiagonal() / n;
  const Eigen::SelfAdjointEigenSolver<Matrix6d> eig(0.5 * (Hn + Hn.transpose()));
  info.eigenvalues = eig.eigenvalues();
  Vector6d kept = info.eigenvalues;
  for (int i = 0; i < 6; ++i) {
    info.zeroed[static_cast<std::size_t>(i)] = info.eigenvalues(i) < config.degeneracy_threshold;
    if (info.zeroed[static_cast<std::size_t>(i)]) {
      kept(i) = 0.0;
      ++info.zero_directions;
    }
    info.directions.col(i) = (s.asDiagonal() * eig.eigenvectors().col(i)).normalized();
  }
  const Matrix6d Hk = eig.eigenvectors() * kept.asDiagonal() * eig.eigenvectors().transpose();
  const Vector6d s_inv = s.cwiseInverse();
  return s_inv.asDiagonal() * Hk * s_inv.asDiagonal() * n;
}

}  // namespace

Matrix6d registration_hessian(const std::vector<Correspondence>& inliers, bool weighted, bool marginalize_scale) {
  Matrix6d H = Matrix6d::Zero();
  Vector6d h_scale = Vector6d::Zero();  // cross terms with the log-scale column n . a
  double h_ss = 0.0;
  for (const Correspondence& k : inliers) {
    Vector6d A;  // eq. (9) has A_j = -[(a x n)^T, n^T]; the sign cancels in A^T A
    A << k.a.cross(k.n), k.n;
    const double w = weighted ? k.weight : 1.0;
    H.noalias() += w * A * A.transpose();
    const double scale_column = k.n.dot(k.a);
    h_scale.noalias() += w * scale_column * A;
    h_ss += w * scale_column * scale_column;
  }
  // The pose's information with the scale unknown: the Schur complement of the 7 x 7 Hessian over the scale.
  if (marginalize_scale && h_ss > 0.0) H -= h_scale * h_scale.transpose() / h_ss;
  return 0.5 * (H + H.transpose());  // Eigen's product kernel is not bit-symmetric; the factor must be
}

Information compute_information(const RegistrationConfig& config, const std::vector<Correspondence>& inliers,
                                double rmse_m, double robust_sigma_m) {
  Information info;
  if (inliers.empty()) return info;
  info.H = registration_hessian(inliers, false, config.estimate_scale);
  info.H_weighted = registration_hessian(inliers, true, config.estimate_scale);
  double radius_sq = 0.0, weight = 0.0;
  for (const Correspondence& k : inliers) {
    radius_sq += k.a.squaredNorm();
    weight += k.weight;
  }
  info.length_scale_m = std::max(1.0, std::sqrt(radius_sq / static_cast<double>(inliers.size())));
  const Matrix6d H_kept = analyse(config, std::max(weight, 1e-12), info);
  switch (config.weights) {
    case WeightMode::kPaper:
      info.sigma_sq = info.H.trace();
      info.information = config.paper_beta / info.sigma_sq * std::exp(-0.5 * rmse_m * rmse_m) * info.H;
      break;
    case WeightMode::kAdaptive: {
      const double sigma = std::max(robust_sigma_m, config.min_sigma_m);
      info.sigma_sq = sigma * sigma * config.correlation_inflation;
      info.information = H_kept / info.sigma_sq;
      break;
    }
    case WeightMode::kFixed:
      info.information.setZero();
      info.information.diagonal() << Eigen::Vector3d::Constant(config.fixed_rotation_information),
          Eigen::Vector3d::Constant(config.fixed_translation_information);
      break;
  }
  info.information = (0.5 * (info.information + info.information.transpose())).eval();  // exactly symmetric
  return info;
}

}  // namespace twinslam::registration

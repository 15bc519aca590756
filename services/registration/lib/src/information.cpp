// Information of a registration (see information.hpp for the 6-vector and the normalization).
#include "twinslam/registration/information.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

namespace twinslam::registration {
namespace {

// Eigen-analysis of Hn = S H_w S / n, n the summed weight (ascending); fills eigenvalues, directions, zeroed.
struct Analysis {
  Vector6d s;           // diag of S
  Matrix6d U;           // eigenvectors of Hn (columns)
  Vector6d kept;        // eigenvalues of Hn with the zeroed ones set to 0
  double n = 1.0;       // summed weight
  // The information with the zeroed directions removed: S^-1 (U kept U^T) S^-1 n, i.e. H_w itself when nothing is
  // zeroed.
  Matrix6d kept_information() const {
    const Vector6d s_inv = s.cwiseInverse();
    return s_inv.asDiagonal() * (U * kept.asDiagonal() * U.transpose()) * s_inv.asDiagonal() * n;
  }
};

Analysis analyse(const RegistrationConfig& config, double n, Information& info) {
  Analysis a;
  a.n = n;
  a.s << Eigen::Vector3d::Constant(1.0 / info.length_scale_m), Eigen::Vector3d::Ones();
  const Matrix6d Hn = a.s.asDiagonal() * info.H_weighted * a.s.asDiagonal() / n;
  const Eigen::SelfAdjointEigenSolver<Matrix6d> eig(0.5 * (Hn + Hn.transpose()));
  info.eigenvalues = eig.eigenvalues();
  a.U = eig.eigenvectors();
  a.kept = info.eigenvalues;
  for (int i = 0; i < 6; ++i) {
    info.zeroed[static_cast<std::size_t>(i)] = info.eigenvalues(i) < config.degeneracy_threshold;
    if (info.zeroed[static_cast<std::size_t>(i)]) {
      a.kept(i) = 0.0;
      ++info.zero_directions;
    }
    info.directions.col(i) = (a.s.asDiagonal() * a.U.col(i)).normalized();
  }
  return a;
}

// Row A_j of eq. (9) for one correspondence; eq. (9) has A_j = -[(a x n)^T, n^T]: the sign cancels in every product
// used here.
Vector6d jacobian_row(const Correspondence& k) {
  Vector6d A;
  A << k.a.cross(k.n), k.n;
  return A;
}

// The 7 x 7 Hessian's coupling of the pose with ICP's log-scale (column n . a): sum w c A_j and sum w c^2.
struct ScaleCoupling {
  Vector6d h_scale = Vector6d::Zero();
  double h_ss = 0.0;
};
ScaleCoupling scale_coupling(const std::vector<Correspondence>& inliers, bool weighted) {
  ScaleCoupling s;
  for (const Correspondence& k : inliers) {
    const double w = weighted ? k.weight : 1.0;
    const double c = k.n.dot(k.a);
    s.h_scale.noalias() += w * c * jacobian_row(k);
    s.h_ss += w * c * c;
  }
  return s;
}

// The rows A_j with the log-scale eliminated when ICP estimated it: A~_j = A_j - (h / h_ss) (n . a)_j, whose weighted
// sum of outer products is registration_hessian's Schur complement, so a change of the residuals moves the pose as
// the 7-DoF solve does.
std::vector<Vector6d> pose_rows(const std::vector<Correspondence>& inliers, bool marginalize_scale) {
  std::vector<Vector6d> rows(inliers.size());
  for (std::size_t j = 0; j < inliers.size(); ++j) rows[j] = jacobian_row(inliers[j]);
  if (!marginalize_scale) return rows;
  const ScaleCoupling s = scale_coupling(inliers, true);
  if (s.h_ss > 0.0) {
    for (std::size_t j = 0; j < inliers.size(); ++j) rows[j] -= s.h_scale * (inliers[j].n.dot(inliers[j].a) / s.h_ss);
  }
  return rows;
}

// adaptive with surface_error_m > 0 (information.hpp): on the kept directions B = S U_k (coordinates c = D^T xi,
// D = S^-1 U_k, D^T B = I) the correction's covariance is B C B^T with C = L^-1 B^T M B L^-1, L = n diag(kept), and
// the information D C^-1 D^T. With surface_error_m = 0 this is H_kept / sigma^2 exactly.
Matrix6d surface_information(const RegistrationConfig& config, const std::vector<Correspondence>& inliers,
                             const Analysis& a, double sigma_sq, Information& info) {
  std::vector<int> kept_columns;
  for (int i = 0; i < 6; ++i) {
    if (a.kept(i) > 0.0) kept_columns.push_back(i);
  }
  if (kept_columns.empty()) return Matrix6d::Zero();
  const int m = static_cast<int>(kept_columns.size());
  Eigen::Matrix<double, 6, Eigen::Dynamic> B(6, m), D(6, m);
  Eigen::VectorXd L(m);
  for (int c = 0; c < m; ++c) {
    B.col(c) = a.s.asDiagonal() * a.U.col(kept_columns[static_cast<std::size_t>(c)]);
    D.col(c) = a.s.cwiseInverse().asDiagonal() * a.U.col(kept_columns[static_cast<std::size_t>(c)]);
    L(c) = a.n * a.kept(kept_columns[static_cast<std::size_t>(c)]);
  }
  const std::vector<int> group =
      group_surfaces(inliers, config.surface_group_angle_deg, config.surface_group_offset_m);
  const std::vector<Vector6d> rows = pose_rows(inliers, config.estimate_scale);
  info.surfaces = group.empty() ? 0 : *std::max_element(group.begin(), group.end()) + 1;
  std::vector<Vector6d> G(static_cast<std::size_t>(info.surfaces), Vector6d::Zero());
  for (std::size_t j = 0; j < inliers.size(); ++j) G[static_cast<std::size_t>(group[j])] += inliers[j].weight * rows[j];
  Matrix6d M = sigma_sq * info.H_weighted;
  const double surface_var = config.surface_error_m * config.surface_error_m;
  for (const Vector6d& g : G) M.noalias() += surface_var * g * g.transpose();
  const Eigen::VectorXd L_inv = L.cwiseInverse();
  Eigen::MatrixXd C = L_inv.asDiagonal() * (B.transpose() * M * B) * L_inv.asDiagonal();
  C = (0.5 * (C + C.transpose())).eval();
  const Eigen::MatrixXd C_inv = C.ldlt().solve(Eigen::MatrixXd::Identity(m, m));
  return D * C_inv * D.transpose();
}

}  // namespace

Matrix6d registration_hessian(const std::vector<Correspondence>& inliers, bool weighted, bool marginalize_scale) {
  Matrix6d H = Matrix6d::Zero();
  for (const Correspondence& k : inliers) {
    const Vector6d A = jacobian_row(k);
    H.noalias() += (weighted ? k.weight : 1.0) * A * A.transpose();
  }
  // The pose's information with the scale unknown: the Schur complement of the 7 x 7 Hessian over the scale.
  if (marginalize_scale) {
    const ScaleCoupling s = scale_coupling(inliers, weighted);
    if (s.h_ss > 0.0) H -= s.h_scale * s.h_scale.transpose() / s.h_ss;
  }
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
  const Analysis analysis = analyse(config, std::max(weight, 1e-12), info);
  switch (config.weights) {
    case WeightMode::kPaper:
      info.sigma_sq = info.H.trace();
      info.information = config.paper_beta / info.sigma_sq * std::exp(-0.5 * rmse_m * rmse_m) * info.H;
      break;
    case WeightMode::kAdaptive: {
      const double sigma = std::max(robust_sigma_m, config.min_sigma_m);
      info.sigma_sq = sigma * sigma * config.correlation_inflation;
      info.information = config.surface_error_m > 0.0
                             ? surface_information(config, inliers, analysis, info.sigma_sq, info)
                             : Matrix6d(analysis.kept_information() / info.sigma_sq);
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

std::vector<int> group_surfaces(const std::vector<Correspondence>& inliers, double angle_deg, double offset_m) {
  const double min_cos = std::cos(angle_deg * M_PI / 180.0);
  std::vector<int> group(inliers.size(), -1);
  std::vector<std::size_t> first;  // the first member of each group
  for (std::size_t j = 0; j < inliers.size(); ++j) {
    const Correspondence& k = inliers[j];
    for (std::size_t g = 0; g < first.size() && group[j] < 0; ++g) {
      const Correspondence& f = inliers[first[g]];
      if (k.n.dot(f.n) > min_cos && std::abs(f.n.dot(k.b - f.b)) < offset_m) group[j] = static_cast<int>(g);
    }
    if (group[j] < 0) {
      group[j] = static_cast<int>(first.size());
      first.push_back(j);
    }
  }
  return group;
}

}  // namespace twinslam::registration

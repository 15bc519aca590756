// The pose graph of the loosely coupled GNSS + VIO fusion (loose_gnss_fusion.hpp): node poses T_WB in W, with
//  - odometry terms between consecutive nodes: the VIO's relative pose, sigmas growing with the distance travelled;
//  - a tilt term per node: W and the VIO frame L are both gravity-aligned (z up), so T_WL = T_WB T_LB^-1 turns about
//    z only - roll and pitch are the VIO's (gravity makes them observable there), the graph moves heading and position;
//  - GNSS terms: the antenna of a fix, reached from its node through the VIO motion between them, against the fix;
//  - a prior on the oldest node for what the nodes that left the window said.
// Residual order: translation then rotation (odometry, prior); E, N, U (GNSS). All whitened.
#include <cmath>

#include <ceres/ceres.h>

#include "twinslam/estimator/loose_gnss_fusion.hpp"

namespace twinslam::estimator {
namespace {

constexpr double kDegToRad = 0.017453292519943295;

template <typename T>
using Quat = Eigen::Quaternion<T>;
template <typename T>
using Vec3 = Eigen::Matrix<T, 3, 1>;

// VIO's relative pose i -> j must be the graph's: residual 6 = ((R_Wi^T (p_Wj - p_Wi) - dp) / s_t, 2 vec(dq^-1 q_ij) / s_r).
struct OdometryTerm {
  Eigen::Vector3d dp;
  Eigen::Quaterniond dq;
  double sigma_m, sigma_rad;
  template <typename T>
  bool operator()(const T* pi, const T* qi, const T* pj, const T* qj, T* r) const {
    const Eigen::Map<const Vec3<T>> p_i(pi), p_j(pj);
    const Eigen::Map<const Quat<T>> q_i(qi), q_j(qj);
    const Vec3<T> t = q_i.conjugate() * (p_j - p_i) - dp.cast<T>();
    const Quat<T> e = dq.cast<T>().conjugate() * (q_i.conjugate() * q_j);
    for (int k = 0; k < 3; ++k) {
      r[k] = t[k] / sigma_m;
      r[3 + k] = T(2.0) * e.vec()[k] / sigma_rad;
    }
    return true;
  }
};

// R_WL = R_WB R_LB^T turns about z only: the horizontal part of R_WL^T e_z is zero.
struct TiltTerm {
  Eigen::Quaterniond q_LB;
  double sigma_rad;
  template <typename T>
  bool operator()(const T* q, T* r) const {
    const Eigen::Map<const Quat<T>> q_WB(q);
    const Vec3<T> up_L = q_LB.cast<T>() * (q_WB.conjugate() * Vec3<T>(T(0), T(0), T(1)));
    r[0] = up_L.x() / sigma_rad;
    r[1] = up_L.y() / sigma_rad;
    return true;
  }
};

// The antenna o_B (in the node's body frame) must be at the fix: residual 3 = S (p_W + R_WB o_B - z_W), S^T S = C^-1.
struct GnssTerm {
  Eigen::Vector3d o_B, z_W;
  Eigen::Matrix3d S;
  template <typename T>
  bool operator()(const T* p, const T* q, T* r) const {
    const Eigen::Map<const Vec3<T>> p_W(p);
    const Eigen::Map<const Quat<T>> q_WB(q);
    const Vec3<T> e = S.cast<T>() * (p_W + q_WB * o_B.cast<T>() - z_W.cast<T>());
    for (int k = 0; k < 3; ++k) r[k] = e[k];
    return true;
  }
};

struct PriorTerm {
  Eigen::Vector3d p0;
  Eigen::Quaterniond q0;
  double sigma_m, sigma_rad;
  template <typename T>
  bool operator()(const T* p, const T* q, T* r) const {
    const Eigen::Map<const Vec3<T>> p_W(p);
    const Eigen::Map<const Quat<T>> q_WB(q);
    const Quat<T> e = q0.cast<T>().conjugate() * q_WB;
    for (int k = 0; k < 3; ++k) {
      r[k] = (p_W[k] - T(p0[k])) / sigma_m;
      r[3 + k] = T(2.0) * e.vec()[k] / sigma_rad;
    }
    return true;
  }
};

Eigen::Matrix3d whitening(const Eigen::Matrix3d& cov) {
  const Eigen::LLT<Eigen::Matrix3d> llt(cov.inverse());
  return llt.matrixL().transpose();  // C^-1 = L L^T -> S = L^T
}

}  // namespace

void solve_loose_graph(std::deque<LooseGnssFusion::Node>& nodes, const std::optional<Eigen::Isometry3d>& prior_T_WB,
                       const LooseGnssFusionConfig& c) {
  if (nodes.empty()) return;
  const std::size_t n = nodes.size();
  std::vector<Eigen::Vector3d> p(n);
  std::vector<Eigen::Quaterniond> q(n);
  for (std::size_t i = 0; i < n; ++i) {
    p[i] = nodes[i].T_WB.translation();
    q[i] = Eigen::Quaterniond(nodes[i].T_WB.linear()).normalized();
  }
  ceres::Problem::Options po;
  po.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  po.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  ceres::EigenQuaternionManifold quaternion;
  ceres::HuberLoss huber(c.huber_delta);
  for (std::size_t i = 0; i < n; ++i) {
    problem.AddParameterBlock(p[i].data(), 3);
    problem.AddParameterBlock(q[i].coeffs().data(), 4, &quaternion);
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<TiltTerm, 2, 4>(
                                 new TiltTerm{Eigen::Quaterniond(nodes[i].T_LB.linear()), 0.5 * kDegToRad}),
                             nullptr, q[i].coeffs().data());
    for (const auto& f : nodes[i].fixes) {
      const Eigen::Vector3d o_B = f.T_node_fix * c.lever_arm_B;
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<GnssTerm, 3, 3, 4>(new GnssTerm{o_B, f.z_W, whitening(f.cov_W)}), &huber,
          p[i].data(), q[i].coeffs().data());
    }
    if (i == 0) continue;
    const Eigen::Isometry3d d = nodes[i - 1].T_LB.inverse() * nodes[i].T_LB;
    const double dist = d.translation().norm();
    const double sigma_m = std::max(c.odometry_min_sigma_m, c.odometry_sigma_per_m * dist);
    const double sigma_rad = std::max(c.odometry_min_sigma_deg, c.odometry_deg_per_m * dist) * kDegToRad;
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<OdometryTerm, 6, 3, 4, 3, 4>(new OdometryTerm{
                                 d.translation(), Eigen::Quaterniond(d.linear()).normalized(), sigma_m, sigma_rad}),
                             nullptr, p[i - 1].data(), q[i - 1].coeffs().data(), p[i].data(), q[i].coeffs().data());
  }
  if (prior_T_WB) {
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<PriorTerm, 6, 3, 4>(
            new PriorTerm{prior_T_WB->translation(), Eigen::Quaterniond(prior_T_WB->linear()).normalized(),
                          c.prior_sigma_m, c.prior_sigma_deg * kDegToRad}),
        nullptr, p[0].data(), q[0].coeffs().data());
  }
  ceres::Solver::Options so;
  so.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;  // a chain: banded normal equations
  so.max_num_iterations = c.max_iterations;
  so.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  if (!summary.IsSolutionUsable()) return;  // keep the previous estimate
  for (std::size_t i = 0; i < n; ++i) {
    nodes[i].T_WB.translation() = p[i];
    nodes[i].T_WB.linear() = q[i].normalized().toRotationMatrix();
  }
}

}  // namespace twinslam::estimator

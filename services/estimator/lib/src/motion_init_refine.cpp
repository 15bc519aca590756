#include "motion_init_refine.hpp"

#include <cmath>
#include <limits>
#include <memory>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <ceres/autodiff_cost_function.h>
#include <ceres/loss_function.h>
#include <ceres/problem.h>
#include <ceres/solver.h>
#include <ceres/sphere_manifold.h>

namespace twinslam::estimator {
namespace {

// Residual (2) of one ray: the direction u from the camera centre to the landmark, rotated into B_k, against the
// measured f_B in a tangent basis (b1, b2) of f_B, divided by the component along f_B: for small errors its norm is
// the angle [rad]. Camera centre c_k = t v_0 + t^2/2 g + dp_0k(b) + R_0k(b_g) t_BC; R_0k(b_g) = R_0k Exp(dR_dbg b_g)
// to first order, dp_0k(b) = dp_0k + dp_dbg b_g + dp_dba b_a (Forster eq. 44).
struct RayAngleError {
  RayAngleError(const RefineFrame& frame, const Eigen::Vector3d& f_B, const Eigen::Vector3d& t_BC, double sigma_rad)
      : fr(frame), f(f_B), t_BC(t_BC), inv_sigma(1.0 / sigma_rad) {
    const Eigen::Vector3d any = std::abs(f.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    b1 = f.cross(any).normalized();
    b2 = f.cross(b1);
  }
  template <typename T>
  bool operator()(const T* v0, const T* g, const T* bg, const T* ba, const T* P, T* r) const {
    using V3 = Eigen::Matrix<T, 3, 1>;
    const Eigen::Map<const V3> v(v0), gv(g), b_g(bg), b_a(ba), p(P);
    const V3 phi = fr.dR_dbg.cast<T>() * b_g;
    const V3 Rt = fr.R_0k.cast<T>() * (t_BC.cast<T>() + phi.cross(t_BC.cast<T>()));
    const T t(fr.t_s);
    const V3 c = t * v + T(0.5) * t * t * gv + fr.dp_0k.cast<T>() + fr.dp_dbg.cast<T>() * b_g +
                 fr.dp_dba.cast<T>() * b_a + Rt;
    const V3 u_0 = fr.R_0k.transpose().cast<T>() * (p - c);
    const V3 u = u_0 - phi.cross(u_0);  // Exp(phi)^T u_0 to first order
    const T along = u.dot(f.cast<T>());
    // A landmark behind the camera gets a large constant error instead of a wrap-around of the angle.
    if (along <= T(1e-6)) {
      r[0] = T(inv_sigma);
      r[1] = T(inv_sigma);
      return true;
    }
    r[0] = u.dot(b1.cast<T>()) / along * T(inv_sigma);
    r[1] = u.dot(b2.cast<T>()) / along * T(inv_sigma);
    return true;
  }
  RefineFrame fr;
  Eigen::Vector3d f, t_BC, b1, b2;
  double inv_sigma;
};

using RayCost = ceres::AutoDiffCostFunction<RayAngleError, 2, 3, 3, 3, 3, 3>;

std::unique_ptr<RayCost> ray_cost(const RefineProblem& pb, const RefineRay& ray) {
  return std::make_unique<RayCost>(new RayAngleError(pb.frames[ray.frame], ray.f_B, pb.t_BC, pb.sigma_rad));
}

// Whitened residual of a zero-mean Gaussian prior on a 3-vector.
struct BiasPrior {
  explicit BiasPrior(double sigma) : inv_sigma(1.0 / sigma) {}
  template <typename T>
  bool operator()(const T* b, T* r) const {
    for (int i = 0; i < 3; ++i) r[i] = b[i] * T(inv_sigma);
    return true;
  }
  double inv_sigma;
};

}  // namespace

bool refine_motion_init(const RefineProblem& pb, RefineState& state, int max_iterations) {
  ceres::Problem::Options po;
  po.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  po.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  ceres::SphereManifold<3> sphere;
  ceres::HuberLoss loss(pb.huber_rad / pb.sigma_rad);  // residuals are whitened
  std::vector<double> P(3 * state.P_B0.size());
  for (std::size_t j = 0; j < state.P_B0.size(); ++j) {
    Eigen::Map<Eigen::Vector3d> P_j(&P[3 * j]);
    P_j = state.P_B0[j];
  }
  double* v0 = state.v0_B0.data();
  double* g = state.g_B0.data();
  double* bg = state.b_g.data();
  double* ba = state.b_a.data();
  for (const RefineRay& ray : pb.rays) {
    problem.AddResidualBlock(ray_cost(pb, ray).release(), &loss, v0, g, bg, ba, &P[3 * ray.landmark]);
  }
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<BiasPrior, 3, 3>(new BiasPrior(pb.gyro_bias_sigma)), nullptr, bg);
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<BiasPrior, 3, 3>(new BiasPrior(pb.accel_bias_sigma)), nullptr, ba);
  problem.SetManifold(g, &sphere);
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_SCHUR;  // the landmarks are eliminated first
  options.max_num_iterations = max_iterations;
  options.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  if (!summary.IsSolutionUsable()) return false;
  for (std::size_t j = 0; j < state.P_B0.size(); ++j) state.P_B0[j] = Eigen::Map<Eigen::Vector3d>(&P[3 * j]);
  return true;
}

Eigen::Matrix<double, 5, 5> motion_init_covariance(const RefineProblem& pb, const RefineState& state, double sigma_rad) {
  constexpr int kX = 11;  // v_0 [3], g tangent [2], b_g [3], b_a [3]
  using MatrixX = Eigen::Matrix<double, kX, kX>;
  using Matrix3X = Eigen::Matrix<double, 3, kX>;
  const Eigen::Vector3d g_hat = state.g_B0.normalized();
  const Eigen::Vector3d any = std::abs(g_hat.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  Eigen::Matrix<double, 3, 2> B;
  B.col(0) = g_hat.cross(any).normalized();
  B.col(1) = g_hat.cross(B.col(0));
  const double w = (pb.sigma_rad * pb.sigma_rad) / (sigma_rad * sigma_rad);  // residuals come whitened by pb.sigma_rad
  MatrixX H = MatrixX::Zero();
  H.block<3, 3>(5, 5).diagonal().setConstant(1.0 / (pb.gyro_bias_sigma * pb.gyro_bias_sigma));
  H.block<3, 3>(8, 8).diagonal().setConstant(1.0 / (pb.accel_bias_sigma * pb.accel_bias_sigma));
  std::vector<Eigen::Matrix3d> A(state.P_B0.size(), Eigen::Matrix3d::Zero());
  std::vector<Matrix3X> C(state.P_B0.size(), Matrix3X::Zero());
  for (const RefineRay& ray : pb.rays) {
    const auto cost = ray_cost(pb, ray);
    const double* params[5] = {state.v0_B0.data(), state.g_B0.data(), state.b_g.data(), state.b_a.data(),
                               state.P_B0[ray.landmark].data()};
    Eigen::Matrix<double, 2, 3, Eigen::RowMajor> J[5];
    double* jac[5] = {J[0].data(), J[1].data(), J[2].data(), J[3].data(), J[4].data()};
    double r[2];
    if (!cost->Evaluate(params, r, jac)) continue;
    Eigen::Matrix<double, 2, kX> J_x;
    J_x << J[0], J[1] * B, J[2], J[3];
    H += w * J_x.transpose() * J_x;
    A[ray.landmark] += w * J[4].transpose() * J[4];
    C[ray.landmark] += w * J[4].transpose() * J_x;
  }
  for (std::size_t j = 0; j < A.size(); ++j) {
    Eigen::FullPivLU<Eigen::Matrix3d> lu(A[j]);
    if (lu.rank() == 3) H -= C[j].transpose() * lu.solve(C[j]);
  }
  Eigen::FullPivLU<MatrixX> lu(H);
  if (lu.rank() < kX) return Eigen::Matrix<double, 5, 5>::Constant(std::numeric_limits<double>::infinity());
  return lu.inverse().topLeftCorner<5, 5>();
}

std::vector<double> ray_angles(const RefineProblem& pb, const RefineState& state) {
  std::vector<double> out;
  out.reserve(pb.rays.size());
  for (const RefineRay& ray : pb.rays) {
    const auto cost = ray_cost(pb, ray);
    const double* params[5] = {state.v0_B0.data(), state.g_B0.data(), state.b_g.data(), state.b_a.data(),
                               state.P_B0[ray.landmark].data()};
    double r[2] = {1.0, 1.0};
    cost->Evaluate(params, r, nullptr);
    out.push_back(std::atan(pb.sigma_rad * std::hypot(r[0], r[1])));
  }
  return out;
}

}  // namespace twinslam::estimator

#include "twinslam/eval/alignment.hpp"

#include <cmath>

#include <Eigen/SVD>

#include "twinslam/core/error.hpp"

namespace twinslam::eval {
namespace {

Eigen::Vector3d mean(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto& p : points) sum += p;
  return sum / static_cast<double>(points.size());
}

Eigen::Matrix3d rot_z(double yaw_rad) { return Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix(); }

// Yaw of a rotation matrix (z-y-x convention), i.e. the heading of its x axis projected on the horizontal plane.
double yaw_of(const Eigen::Matrix3d& R) { return std::atan2(R(1, 0), R(0, 0)); }

}  // namespace

std::string to_string(AlignMode mode) {
  switch (mode) {
    case AlignMode::None: return "none";
    case AlignMode::PosYaw: return "posyaw";
    case AlignMode::SE3: return "se3";
    case AlignMode::Sim3: return "sim3";
  }
  return "none";
}

AlignMode parse_align_mode(std::string_view text) {
  if (text == "none") return AlignMode::None;
  if (text == "posyaw") return AlignMode::PosYaw;
  if (text == "se3") return AlignMode::SE3;
  if (text == "sim3") return AlignMode::Sim3;
  throw UsageError("unknown alignment '" + std::string(text) + "' (choose none, posyaw, se3 or sim3)");
}

Eigen::Isometry3d Similarity::apply(const Eigen::Isometry3d& T_LB) const {
  Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
  T_WB.linear() = R_WL * T_LB.linear();
  T_WB.translation() = apply(Eigen::Vector3d(T_LB.translation()));
  return T_WB;
}

Similarity umeyama(const std::vector<Eigen::Vector3d>& p_L, const std::vector<Eigen::Vector3d>& p_W, bool with_scale) {
  const double n = static_cast<double>(p_L.size());
  const Eigen::Vector3d mu_L = mean(p_L), mu_W = mean(p_W);  // eqs. 34, 35
  Eigen::Matrix3d Sigma = Eigen::Matrix3d::Zero();             // eq. 38: covariance of W and L points
  double var_L = 0.0;                                          // eq. 36
  for (std::size_t i = 0; i < p_L.size(); ++i) {
    const Eigen::Vector3d x = p_L[i] - mu_L, y = p_W[i] - mu_W;
    Sigma += y * x.transpose();
    var_L += x.squaredNorm();
  }
  Sigma /= n;
  var_L /= n;
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(Sigma, Eigen::ComputeFullU | Eigen::ComputeFullV);
  // eq. 43: flip the smallest singular direction when U V^T would be a reflection.
  Eigen::Vector3d S = Eigen::Vector3d::Ones();
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0.0) S(2) = -1.0;
  Similarity out;
  out.R_WL = svd.matrixU() * S.asDiagonal() * svd.matrixV().transpose();  // eq. 40
  if (with_scale) {
    if (!(var_L > 0.0)) throw InputError("sim3 alignment: the estimate's positions do not spread (zero variance)");
    out.scale = svd.singularValues().dot(S) / var_L;  // eq. 42: tr(D S) / sigma_x^2
  }
  out.t_W = mu_W - out.scale * out.R_WL * mu_L;  // eq. 41
  return out;
}

Similarity align_posyaw(const std::vector<Eigen::Vector3d>& p_L, const std::vector<Eigen::Vector3d>& p_W) {
  const Eigen::Vector3d mu_L = mean(p_L), mu_W = mean(p_W);
  double a = 0.0, b = 0.0;  // a = sum x.y in the plane, b = sum (x cross y).z
  for (std::size_t i = 0; i < p_L.size(); ++i) {
    const Eigen::Vector3d x = p_L[i] - mu_L, y = p_W[i] - mu_W;
    a += x.x() * y.x() + x.y() * y.y();
    b += x.x() * y.y() - x.y() * y.x();
  }
  Similarity out;
  out.R_WL = rot_z(std::atan2(b, a));
  out.t_W = mu_W - out.R_WL * mu_L;
  return out;
}

Similarity align(AlignMode mode, const std::vector<Eigen::Isometry3d>& T_LB, const std::vector<Eigen::Isometry3d>& T_WB) {
  if (mode == AlignMode::None) return {};
  const std::size_t n = T_LB.size();
  const std::size_t needed = mode == AlignMode::Sim3 ? 3 : 1;
  if (n < needed) {
    throw InputError(to_string(mode) + " alignment needs at least " + std::to_string(needed) +
                     " associated poses, got " + std::to_string(n));
  }
  if (n == 1) {  // one pose: align it exactly (orientation included), as for rpg's "align on the first frame"
    Similarity out;
    out.R_WL = mode == AlignMode::PosYaw ? rot_z(yaw_of(T_WB[0].linear()) - yaw_of(T_LB[0].linear()))
                                         : Eigen::Matrix3d(T_WB[0].linear() * T_LB[0].linear().transpose());
    out.t_W = T_WB[0].translation() - out.R_WL * T_LB[0].translation();
    return out;
  }
  std::vector<Eigen::Vector3d> p_L(n), p_W(n);
  for (std::size_t i = 0; i < n; ++i) {
    p_L[i] = T_LB[i].translation();
    p_W[i] = T_WB[i].translation();
  }
  if (mode == AlignMode::PosYaw) return align_posyaw(p_L, p_W);
  return umeyama(p_L, p_W, mode == AlignMode::Sim3);
}

}  // namespace twinslam::eval

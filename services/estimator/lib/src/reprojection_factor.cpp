#include "twinslam/estimator/reprojection_factor.hpp"

#include <cmath>
#include <stdexcept>

#include "twinslam/core/error.hpp"
#include "twinslam/geometry/quaternion.hpp"
#include "twinslam/geometry/so3.hpp"

namespace twinslam::estimator {

Eigen::Matrix<double, 3, 2> tangent_basis(const Eigen::Vector3d& f_in) {
  const Eigen::Vector3d f = f_in.normalized();
  // Start from the coordinate axis least aligned with f, so the cross product is never close to zero.
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();
  if (std::abs(f.y()) < std::abs(f.x()) && std::abs(f.y()) <= std::abs(f.z())) axis = Eigen::Vector3d::UnitY();
  if (std::abs(f.z()) < std::abs(f.x()) && std::abs(f.z()) < std::abs(f.y())) axis = Eigen::Vector3d::UnitZ();
  Eigen::Matrix<double, 3, 2> B;
  B.col(0) = f.cross(axis).normalized();
  B.col(1) = f.cross(B.col(0));
  return B;
}

void ReprojectionNoise::validate() const {
  auto check = [](double v, const char* name) {
    if (!(v > 0.0) || !std::isfinite(v)) throw InputError(std::string("ReprojectionNoise: ") + name + " must be > 0");
  };
  check(focal_px, "focal_px");
  check(pixel_sigma, "pixel_sigma");
  check(huber_threshold, "huber_threshold");
}

ceres::LossFunction* new_reprojection_loss(const ReprojectionNoise& noise) {
  noise.validate();
  return new ceres::HuberLoss(noise.huber_threshold);
}

ReprojectionFactor::ReprojectionFactor(const Eigen::Vector3d& f_Ca, const Eigen::Vector3d& f_Cj,
                                       const Eigen::Isometry3d& T_BC, double sqrt_information)
    : f_Ca_(f_Ca.normalized()), f_Cj_(f_Cj.normalized()), R_BC_(T_BC.linear()), t_BC_(T_BC.translation()) {
  if (!f_Ca_.allFinite() || !f_Cj_.allFinite() || !(sqrt_information > 0.0)) {
    throw std::invalid_argument("ReprojectionFactor: bearings must be non-zero and sqrt_information > 0");
  }
  scaled_basis_T_ = sqrt_information * tangent_basis(f_Cj_).transpose();
}

namespace {

// The intermediate vectors of the prediction, named as in the header: a (anchor body, scaled by rho), w (L, scaled),
// q (observer body, scaled) and h = R_CB q.
struct Prediction {
  Eigen::Matrix3d R_a, R_j;
  Eigen::Vector3d a, w, q, h;
};

Prediction predict(const double* pose_a, const double* pose_j, double rho, const Eigen::Vector3d& f_Ca,
                   const Eigen::Matrix3d& R_BC, const Eigen::Vector3d& t_BC) {
  Prediction P;
  const Eigen::Map<const Eigen::Vector3d> p_a(pose_a), p_j(pose_j);
  P.R_a = geometry::rotation_from_quaternion(Eigen::Quaterniond(Eigen::Map<const Eigen::Quaterniond>(pose_a + 3)));
  P.R_j = geometry::rotation_from_quaternion(Eigen::Quaterniond(Eigen::Map<const Eigen::Quaterniond>(pose_j + 3)));
  P.a = R_BC * f_Ca + rho * t_BC;
  P.w = P.R_a * P.a + rho * (p_a - p_j);
  P.q = P.R_j.transpose() * P.w - rho * t_BC;
  P.h = R_BC.transpose() * P.q;
  return P;
}

}  // namespace

Eigen::Vector3d ReprojectionFactor::predicted_scaled_point(const double* pose_a, const double* pose_j, double rho,
                                                           const Eigen::Matrix3d* R_BC) const {
  return predict(pose_a, pose_j, rho, f_Ca_, R_BC != nullptr ? *R_BC : R_BC_, t_BC_).h;
}

bool ReprojectionFactor::in_front(const double* pose_a, const double* pose_j, double rho,
                                  const Eigen::Matrix3d* R_BC) const {
  return rho >= 0.0 && predicted_scaled_point(pose_a, pose_j, rho, R_BC).dot(f_Cj_) > 0.0;
}

double ReprojectionFactor::angular_error(const double* pose_a, const double* pose_j, double rho,
                                         const Eigen::Matrix3d* R_BC) const {
  const Eigen::Vector3d h = predicted_scaled_point(pose_a, pose_j, rho, R_BC);
  return std::atan2(h.cross(f_Cj_).norm(), h.dot(f_Cj_));
}

bool ReprojectionFactor::Evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
  return evaluate_with(R_BC_, parameters, residuals, jacobians, nullptr);
}

bool ReprojectionFactor::evaluate_with(const Eigen::Matrix3d& R_BC, double const* const* parameters,
                                       double* residuals, double** jacobians, double* dr_dphi) const {
  return evaluate_impl({R_BC, f_Ca_, nullptr}, parameters, residuals, jacobians, dr_dphi, nullptr);
}

bool ReprojectionFactor::evaluate_bearings(const Eigen::Vector3d& f_Ca, const Eigen::Vector3d& f_obs,
                                           double const* const* parameters, double* residuals, double** jacobians,
                                           double* dr_dfa, double* dr_dfo) const {
  if (dr_dfo != nullptr) Eigen::Map<Eigen::Matrix<double, 2, 3, Eigen::RowMajor>>{dr_dfo} = -scaled_basis_T_;
  return evaluate_impl({R_BC_, f_Ca, &f_obs}, parameters, residuals, jacobians, nullptr, dr_dfa);
}

bool ReprojectionFactor::evaluate_impl(const Inputs& in, double const* const* parameters, double* residuals,
                                       double** jacobians, double* dr_dphi, double* dr_dfa) const {
  const Eigen::Matrix3d& R_BC = in.R_BC;
  const double rho = parameters[2][0];
  const Prediction P = predict(parameters[0], parameters[1], rho, in.f_Ca, R_BC, t_BC_);
  const double n = P.h.norm();
  if (!(n > 0.0) || !std::isfinite(n)) return false;
  const Eigen::Vector3d b = P.h / n;
  // [t1 t2]^T f_Cj = 0, so the residual s [t1 t2]^T (b - f_Cj) is s [t1 t2]^T b.
  Eigen::Map<Eigen::Vector2d> r{residuals};
  r = scaled_basis_T_ * b;
  if (in.f_obs != nullptr) r -= scaled_basis_T_ * *in.f_obs;
  if (jacobians == nullptr && dr_dphi == nullptr && dr_dfa == nullptr) return true;

  // Chain rule through the normalization: d(h/|h|)/dh = (I - b b^T) / |h|.
  const Eigen::Matrix<double, 2, 3> dr_dh = scaled_basis_T_ * (Eigen::Matrix3d::Identity() - b * b.transpose()) / n;
  const Eigen::Matrix<double, 2, 3> dr_dq = dr_dh * R_BC.transpose();
  const Eigen::Matrix<double, 2, 3> dr_dw = dr_dq * P.R_j.transpose();
  if (dr_dphi != nullptr) {
    // R_BC Exp(phi) enters twice: a = R_BC Exp(phi) f_Ca + ... gives -R_BC [f_Ca]x phi, and
    // h = Exp(-phi) R_BC^T q gives [h]x phi.
    Eigen::Map<Eigen::Matrix<double, 2, 3, Eigen::RowMajor>>{dr_dphi} =
        dr_dh * geometry::skew(P.h) - dr_dw * P.R_a * R_BC * geometry::skew(in.f_Ca);
  }
  // a = R_BC f_Ca + rho t_BC, w = R_a a + ...
  if (dr_dfa != nullptr) Eigen::Map<Eigen::Matrix<double, 2, 3, Eigen::RowMajor>>{dr_dfa} = dr_dw * P.R_a * R_BC;
  if (jacobians == nullptr) return true;
  using PoseJacobian = Eigen::Matrix<double, 2, kPoseSize, Eigen::RowMajor>;
  // Pose blocks: p_L + dp enters w linearly; R_LB Exp(dtheta) gives d(R_a a) = -R_a [a]x dtheta for the anchor and
  // d(R_j^T w) = [R_j^T w]x dtheta for the observer.
  if (jacobians[0] != nullptr) {
    Eigen::Map<PoseJacobian> J(jacobians[0]);
    const Eigen::Quaterniond q_a(Eigen::Map<const Eigen::Quaterniond>(parameters[0] + 3));
    J.leftCols<3>() = rho * dr_dw;
    J.rightCols<4>() = (-dr_dw * P.R_a * geometry::skew(P.a)) * geometry::right_perturbation_jacobian(q_a);
  }
  if (jacobians[1] != nullptr) {
    Eigen::Map<PoseJacobian> J(jacobians[1]);
    const Eigen::Quaterniond q_j(Eigen::Map<const Eigen::Quaterniond>(parameters[1] + 3));
    J.leftCols<3>() = -rho * dr_dw;
    J.rightCols<4>() = (dr_dq * geometry::skew(P.R_j.transpose() * P.w)) * geometry::right_perturbation_jacobian(q_j);
  }
  if (jacobians[2] != nullptr) {
    // dh/drho = R_CB (R_LBj^T (R_LBa t_BC + p_La - p_Lj) - t_BC).
    const Eigen::Map<const Eigen::Vector3d> p_a(parameters[0]), p_j(parameters[1]);
    const Eigen::Vector3d dq_drho = P.R_j.transpose() * (P.R_a * t_BC_ + p_a - p_j) - t_BC_;
    Eigen::Map<Eigen::Vector2d>{jacobians[2]} = dr_dq * dq_drho;
  }
  return true;
}

}  // namespace twinslam::estimator

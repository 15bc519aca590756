#include "twinslam/estimator/triangulation.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "twinslam/core/error.hpp"
#include "twinslam/estimator/reprojection_factor.hpp"

namespace twinslam::estimator {

namespace {

constexpr double kRadToDeg = 57.29577951308232;

double angle_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));  // accurate at small angles, unlike acos
}

}  // namespace

void TriangulationConfig::validate() const {
  auto positive = [](double v, const char* name) {
    if (!(v > 0.0) || !std::isfinite(v)) throw InputError(std::string("TriangulationConfig: ") + name + " must be > 0");
  };
  positive(min_parallax_deg, "min_parallax_deg");
  positive(max_error_px, "max_error_px");
  positive(focal_px, "focal_px");
  positive(min_depth_m, "min_depth_m");
  positive(max_depth_m, "max_depth_m");
  if (max_depth_m <= min_depth_m) throw InputError("TriangulationConfig: max_depth_m must exceed min_depth_m");
  if (max_iterations < 0) throw InputError("TriangulationConfig: max_iterations must be >= 0");
}

std::string_view to_string(TriangulationStatus status) {
  switch (status) {
    case TriangulationStatus::kOk: return "ok";
    case TriangulationStatus::kTooFewViews: return "too few views";
    case TriangulationStatus::kLowParallax: return "low parallax";
    case TriangulationStatus::kBehindCamera: return "behind camera";
    case TriangulationStatus::kDepthOutOfRange: return "depth out of range";
    case TriangulationStatus::kLargeError: return "large reprojection error";
  }
  return "unknown";
}

TriangulationResult triangulate(const TriangulationConfig& config, std::span<const BearingObservation> observations,
                                const Eigen::Isometry3d& T_BC, std::size_t anchor) {
  TriangulationResult out;
  if (observations.size() < 2 || anchor >= observations.size()) return out;

  // Camera poses T_LC, their centres c_i and rays d_i in L.
  const std::size_t n = observations.size();
  std::vector<Eigen::Isometry3d> T_LC(n);
  std::vector<Eigen::Vector3d> d(n);
  for (std::size_t i = 0; i < n; ++i) {
    T_LC[i] = observations[i].T_LB * T_BC;
    d[i] = T_LC[i].linear() * observations[i].f_C.normalized();
  }
  const Eigen::Vector3d c_a = T_LC[anchor].translation();

  double parallax = 0.0;
  for (std::size_t i = 0; i < n; ++i) parallax = std::max(parallax, angle_between(d[anchor], d[i]));
  out.parallax_deg = parallax * kRadToDeg;
  if (out.parallax_deg < config.min_parallax_deg) {
    out.status = TriangulationStatus::kLowParallax;
    return out;
  }

  // 1. Multi-view midpoint.
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - d[i] * d[i].transpose();
    A += P;
    b += P * T_LC[i].translation();
  }
  const Eigen::Vector3d x_L = A.ldlt().solve(b);
  const double depth0 = d[anchor].dot(x_L - c_a);
  if (!(depth0 > 0.0) || !std::isfinite(depth0)) {
    out.status = TriangulationStatus::kBehindCamera;
    return out;
  }
  double rho = 1.0 / depth0;

  // 2. Gauss-Newton on rho: r_i = B_i^T h_i / |h_i| with h_i = u_i + rho v_i (header), dr_i/drho = B_i^T (I - b b^T)
  // v_i / |h_i|.
  std::vector<Eigen::Vector3d> u(n), v(n);
  std::vector<Eigen::Matrix<double, 3, 2>> B(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Matrix3d R_CiL = T_LC[i].linear().transpose();
    u[i] = R_CiL * d[anchor];
    v[i] = R_CiL * (c_a - T_LC[i].translation());
    B[i] = tangent_basis(observations[i].f_C);
  }
  for (int it = 0; it < config.max_iterations; ++it) {
    double JtJ = 0.0, Jtr = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      if (i == anchor) continue;
      const Eigen::Vector3d h = u[i] + rho * v[i];
      const double norm = h.norm();
      const Eigen::Vector3d bearing = h / norm;
      const Eigen::Vector2d r = B[i].transpose() * bearing;
      const Eigen::Vector2d J = B[i].transpose() * (v[i] - bearing * bearing.dot(v[i])) / norm;
      JtJ += J.squaredNorm();
      Jtr += J.dot(r);
    }
    if (!(JtJ > 0.0)) break;
    const double step = -Jtr / JtJ;
    rho += step;
    if (std::abs(step) <= 1e-15 * std::max(1.0, std::abs(rho))) break;
  }
  out.rho = rho;

  // 3. Checks.
  if (!(rho > 0.0) || !std::isfinite(rho)) {
    out.status = TriangulationStatus::kBehindCamera;
    return out;
  }
  out.p_L = c_a + d[anchor] / rho;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d h = u[i] + rho * v[i];  // rho p_Ci
    const Eigen::Vector3d f = observations[i].f_C.normalized();
    if (!(h.dot(f) > 0.0)) {
      out.status = TriangulationStatus::kBehindCamera;
      return out;
    }
    out.max_error_px = std::max(out.max_error_px, angle_between(h, f) * config.focal_px);
  }
  const double depth = 1.0 / rho;
  if (depth < config.min_depth_m || depth > config.max_depth_m) {
    out.status = TriangulationStatus::kDepthOutOfRange;
    return out;
  }
  out.status =
      out.max_error_px <= config.max_error_px ? TriangulationStatus::kOk : TriangulationStatus::kLargeError;
  return out;
}

}  // namespace twinslam::estimator

#include "twinslam/sim/bspline.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace twinslam::sim {

namespace {

double binomial(int n, int k) {
  double r = 1;
  for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
  return r;
}

// Blending matrix of the uniform B-spline of order k = degree + 1 (Qin 2000, Eq. 3):
// m_ij = 1/(k-1)! C(k-1, i) sum_{s=j}^{k-1} (-1)^(s-j) C(k, s-j) (k-s-1)^(k-1-i); row i multiplies u^i.
Eigen::Matrix<double, 6, 6> blending_matrix() {
  constexpr int k = QuinticBSpline::kDegree + 1;
  double factorial = 1;
  for (int i = 2; i < k; ++i) factorial *= i;
  Eigen::Matrix<double, 6, 6> M;
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      double sum = 0;
      for (int s = j; s < k; ++s)
        sum += ((s - j) % 2 ? -1.0 : 1.0) * binomial(k, s - j) * std::pow(k - s - 1.0, k - 1 - i);
      M(i, j) = binomial(k - 1, i) * sum / factorial;
    }
  return M;
}

}  // namespace

QuinticBSpline::QuinticBSpline(std::vector<Eigen::Vector4d> control_points, double dt)
    : control_points_(std::move(control_points)), dt_(dt) {
  if (control_points_.size() < kDegree + 1) throw std::invalid_argument("QuinticBSpline: needs >= 6 control points");
  if (!(dt > 0)) throw std::invalid_argument("QuinticBSpline: knot spacing must be > 0");
}

std::array<Eigen::Vector4d, 5> QuinticBSpline::derivatives(double t) const {
  static const Eigen::Matrix<double, 6, 6> M = blending_matrix();
  const double x = std::clamp(t / dt_, 0.0, static_cast<double>(segments()));
  const auto i = std::min(static_cast<std::size_t>(x), segments() - 1);
  const double u = x - static_cast<double>(i);

  Eigen::Matrix<double, 6, 4> C;
  for (int j = 0; j < 6; ++j) C.row(j) = control_points_[i + static_cast<std::size_t>(j)].transpose();
  const Eigen::Matrix<double, 6, 4> MC = M * C;

  std::array<Eigen::Vector4d, 5> out;
  double scale = 1;  // (1/dt)^order: chain rule from u to t
  for (int order = 0; order < 5; ++order) {
    // d^order/du^order of u^p = p!/(p-order)! u^(p-order)
    Eigen::Matrix<double, 1, 6> U = Eigen::Matrix<double, 1, 6>::Zero();
    for (int p = order; p < 6; ++p) {
      double f = 1;
      for (int q = p - order + 1; q <= p; ++q) f *= q;
      U(p) = f * std::pow(u, p - order);
    }
    out[static_cast<std::size_t>(order)] = scale * (U * MC).transpose();
    scale /= dt_;
  }
  return out;
}

}  // namespace twinslam::sim

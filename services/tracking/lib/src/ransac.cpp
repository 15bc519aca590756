#include "twinslam/tracking/ransac.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/SVD>

#include "twinslam/geometry/so3.hpp"

namespace twinslam::tracking {
namespace {

// Draws k distinct indices in [0, n) (k << n, so rejection is cheap).
void sample(std::mt19937& rng, int n, int k, int* out) {
  std::uniform_int_distribution<int> pick(0, n - 1);
  for (int i = 0; i < k; ++i) {
    bool fresh = false;
    while (!fresh) {
      out[i] = pick(rng);
      fresh = std::find(out, out + i, out[i]) == out + i;
    }
  }
}

// Iterations that draw at least one all-inlier sample of size s with probability p when a fraction w are inliers
// (Fischler & Bolles 1981; Hartley & Zisserman eq. 4.18).
int needed_iterations(double p, double w, int s, int cap) {
  const double all_inliers = std::pow(w, s);
  if (all_inliers >= 1.0 - 1e-12) return 1;
  if (all_inliers <= 1e-12) return cap;
  const double n = std::log(1.0 - p) / std::log(1.0 - all_inliers);
  return static_cast<int>(std::min<double>(cap, std::ceil(n)));
}

// Scores a model: inliers under the threshold. Ties (e.g. pure rotation, where every translation fits) go to the
// smaller sum of squared inlier residuals (MSAC-style), which prefers models that fit the inliers tightly.
struct Score {
  int inliers = -1;
  double cost = 0.0;
  bool better_than(const Score& o) const { return inliers > o.inliers || (inliers == o.inliers && cost < o.cost); }
};

Score score(const Eigen::Matrix3d& E, const std::vector<Eigen::Vector3d>& f_prev,
            const std::vector<Eigen::Vector3d>& f_curr, double threshold) {
  Score s{0, 0.0};
  for (std::size_t i = 0; i < f_prev.size(); ++i) {
    const double e = epipolar_angle(E, f_prev[i], f_curr[i]);
    if (e < threshold) {
      ++s.inliers;
      s.cost += e * e;
    }
  }
  return s;
}

RansacResult finish(const Eigen::Matrix3d& E, const std::vector<Eigen::Vector3d>& f_prev,
                    const std::vector<Eigen::Vector3d>& f_curr, double threshold, int iterations) {
  RansacResult r;
  r.E_curr_prev = E;
  r.iterations = iterations;
  r.inlier.resize(f_prev.size());
  for (std::size_t i = 0; i < f_prev.size(); ++i) {
    r.inlier[i] = epipolar_angle(E, f_prev[i], f_curr[i]) < threshold;
    r.num_inliers += r.inlier[i] ? 1 : 0;
  }
  return r;
}

RansacResult all_inliers(std::size_t n) {
  RansacResult r;
  r.inlier.assign(n, true);
  r.num_inliers = static_cast<int>(n);
  return r;
}

// Linear 8-point on bearings, projected onto the essential manifold (singular values 1, 1, 0; H&Z Sec. 11.1-11.3).
Eigen::Matrix3d essential_from_8(const std::vector<Eigen::Vector3d>& f_prev, const std::vector<Eigen::Vector3d>& f_curr,
                                 const int* idx) {
  Eigen::Matrix<double, 8, 9> A;
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d& a = f_curr[idx[k]];
    const Eigen::Vector3d& b = f_prev[idx[k]];
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) A(k, 3 * i + j) = a(i) * b(j);  // f_curr^T E f_prev = sum E_ij a_i b_j
    }
  }
  const Eigen::JacobiSVD<Eigen::Matrix<double, 8, 9>> svd_a(A, Eigen::ComputeFullV);
  const Eigen::Matrix<double, 9, 1> e = svd_a.matrixV().col(8);
  Eigen::Matrix3d E;
  E << e(0), e(1), e(2), e(3), e(4), e(5), e(6), e(7), e(8);
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(E, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return svd.matrixU() * Eigen::Vector3d(1.0, 1.0, 0.0).asDiagonal() * svd.matrixV().transpose();
}

}  // namespace

double epipolar_angle(const Eigen::Matrix3d& E, const Eigen::Vector3d& f_prev, const Eigen::Vector3d& f_curr) {
  const Eigen::Vector3d l_curr = E * f_prev;               // normal of the epipolar plane of f_prev, in curr
  const Eigen::Vector3d l_prev = E.transpose() * f_curr;   // normal of the epipolar plane of f_curr, in prev
  const double den = std::min(l_curr.norm(), l_prev.norm());
  // A bearing on the epipole (den ~ 0) carries no epipolar information: it fits any match.
  if (den < 1e-12) return 0.0;
  return std::abs(f_curr.dot(l_curr)) / den;
}

RansacResult ransac_known_rotation(const std::vector<Eigen::Vector3d>& f_prev,
                                   const std::vector<Eigen::Vector3d>& f_curr, const Eigen::Matrix3d& R_prev_curr_C,
                                   const RansacOptions& options) {
  const int n = static_cast<int>(f_prev.size());
  if (n < 2) return all_inliers(f_prev.size());
  const Eigen::Matrix3d R_curr_prev = R_prev_curr_C.transpose();
  // n_i = (R_curr_prev f_prev) x f_curr: the translation direction t_curr is orthogonal to every n_i.
  std::vector<Eigen::Vector3d> normals(n);
  for (int i = 0; i < n; ++i) normals[i] = (R_curr_prev * f_prev[i]).cross(f_curr[i]);

  std::mt19937 rng(options.seed);
  Score best;
  Eigen::Matrix3d best_E = geometry::skew(Eigen::Vector3d::UnitZ()) * R_curr_prev;
  int needed = options.max_iterations, it = 0;
  for (; it < needed; ++it) {
    int idx[2];
    sample(rng, n, 2, idx);
    const Eigen::Vector3d t = normals[idx[0]].cross(normals[idx[1]]);
    if (t.norm() < 1e-15) continue;  // parallel normals (or both ~0): no direction defined
    const Eigen::Matrix3d E = geometry::skew(t.normalized()) * R_curr_prev;
    const Score s = score(E, f_prev, f_curr, options.threshold_rad);
    if (s.better_than(best)) {
      best = s;
      best_E = E;
      const double inlier_ratio = static_cast<double>(s.inliers) / n;
      needed = std::max(it + 1, needed_iterations(options.confidence, inlier_ratio, 2, options.max_iterations));
    }
  }
  return finish(best_E, f_prev, f_curr, options.threshold_rad, it);
}

RansacResult ransac_essential(const std::vector<Eigen::Vector3d>& f_prev, const std::vector<Eigen::Vector3d>& f_curr,
                              const RansacOptions& options) {
  const int n = static_cast<int>(f_prev.size());
  if (n < 8) return all_inliers(f_prev.size());
  std::mt19937 rng(options.seed);
  Score best;
  Eigen::Matrix3d best_E = Eigen::Matrix3d::Zero();
  int needed = options.max_iterations, it = 0;
  for (; it < needed; ++it) {
    int idx[8];
    sample(rng, n, 8, idx);
    const Eigen::Matrix3d E = essential_from_8(f_prev, f_curr, idx);
    const Score s = score(E, f_prev, f_curr, options.threshold_rad);
    if (s.better_than(best)) {
      best = s;
      best_E = E;
      const double inlier_ratio = static_cast<double>(s.inliers) / n;
      needed = std::max(it + 1, needed_iterations(options.confidence, inlier_ratio, 8, options.max_iterations));
    }
  }
  return finish(best_E, f_prev, f_curr, options.threshold_rad, it);
}

}  // namespace twinslam::tracking

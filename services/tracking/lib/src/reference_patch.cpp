#include "reference_patch.hpp"

#include <cmath>
#include <cstdint>

#include <Eigen/Dense>
#include <opencv2/imgproc.hpp>

namespace twinslam::tracking {
namespace {

constexpr int kMaxIterations = 8;
constexpr double kConvergedPx = 0.03;  // stop when the centre moves less than this [px]
constexpr double kSettledPx = 0.2;     // after kMaxIterations, a last step above this means Gauss-Newton oscillates

// Zero-mean, unit-norm copy (false if the patch is flat): the comparison then ignores gain and offset, which change
// with exposure and, in the simulator, with the distance-dependent fading of fine texture.
bool normalize(Eigen::VectorXf* v) {
  v->array() -= v->mean();
  const float norm = v->norm();
  if (!(norm > 1e-3f)) return false;
  *v /= norm;
  return true;
}

}  // namespace

ReferencePatch::ReferencePatch(const cv::Mat& mono8, const cv::Point2f& px, int half_px)
    : half_(half_px), n_((2 * half_px + 1) * (2 * half_px + 1)), ref_(n_), sd_(n_, 6) {
  // One pixel of margin for the central differences; getRectSubPix replicates the border if px is near the edge.
  const int side = 2 * half_ + 3;
  cv::Mat1f patch;
  cv::getRectSubPix(mono8, cv::Size(side, side), px, patch, CV_32F);
  for (int y = -half_, i = 0; y <= half_; ++y) {
    for (int x = -half_; x <= half_; ++x, ++i) ref_[i] = patch(y + half_ + 1, x + half_ + 1);
  }
  const float mean = ref_.mean();
  ok_ = normalize(&ref_);
  if (!ok_) return;
  // Gradients of the normalized reference (the same affine map of intensities as ref_).
  Eigen::VectorXf raw(n_);
  for (int y = -half_, i = 0; y <= half_; ++y) {
    for (int x = -half_; x <= half_; ++x, ++i) raw[i] = patch(y + half_ + 1, x + half_ + 1) - mean;
  }
  const float to_unit = 1.0f / raw.norm();
  for (int y = -half_, i = 0; y <= half_; ++y) {
    for (int x = -half_; x <= half_; ++x, ++i) {
      const int r = y + half_ + 1, c = x + half_ + 1;
      const float gx = 0.5f * (patch(r, c + 1) - patch(r, c - 1)) * to_unit;
      const float gy = 0.5f * (patch(r + 1, c) - patch(r - 1, c)) * to_unit;
      sd_.row(i) << gx * x, gy * x, gx * y, gy * y, gx, gy;
    }
  }
  const Eigen::Matrix<double, 6, 6> h = (sd_.transpose() * sd_).cast<double>();
  const Eigen::FullPivLU<Eigen::Matrix<double, 6, 6>> lu(h);
  ok_ = lu.isInvertible();
  if (ok_) h_inv_ = lu.inverse();
}

bool ReferencePatch::align(const cv::Mat& mono8, double min_zncc, Warp* warp) const {
  if (!ok_) return false;
  Warp w = *warp;
  Eigen::VectorXf cur(n_);
  bool converged = false;
  double step = 0;
  for (int it = 0; it <= kMaxIterations; ++it) {
    // Bilinear samples of the current image under the warp, stepping along each patch row; a patch that leaves the
    // image is lost.
    const float a00 = static_cast<float>(w.A(0, 0)), a01 = static_cast<float>(w.A(0, 1));
    const float a10 = static_cast<float>(w.A(1, 0)), a11 = static_cast<float>(w.A(1, 1));
    const float max_u = static_cast<float>(mono8.cols - 1), max_v = static_cast<float>(mono8.rows - 1);
    float* out = cur.data();
    for (int y = -half_; y <= half_; ++y) {
      float u = static_cast<float>(w.t.x()) + a01 * y - a00 * half_;
      float v = static_cast<float>(w.t.y()) + a11 * y - a10 * half_;
      for (int x = -half_; x <= half_; ++x, u += a00, v += a10) {
        if (!(u >= 0.0f && v >= 0.0f && u < max_u && v < max_v)) return false;
        const int u0 = static_cast<int>(u), v0 = static_cast<int>(v);
        const float a = u - u0, b = v - v0;
        const std::uint8_t* r0 = mono8.ptr<std::uint8_t>(v0) + u0;
        const std::uint8_t* r1 = r0 + mono8.step[0];
        *out++ = (1 - b) * (r0[0] + a * (r0[1] - r0[0])) + b * (r1[0] + a * (r1[1] - r1[0]));
      }
    }
    if (!normalize(&cur)) return false;
    if (converged || it == kMaxIterations) break;  // the last pass only samples, for the final score
    const Eigen::Matrix<double, 6, 1> dp = h_inv_ * (sd_.transpose() * (cur - ref_)).cast<double>();
    // Inverse composition: W <- W o W(dp)^-1, with W(dp) = [1 + p0, p2, p4; p1, 1 + p3, p5].
    Eigen::Matrix2d D;
    D << 1 + dp[0], dp[2], dp[1], 1 + dp[3];
    if (std::abs(D.determinant()) < 1e-6) return false;
    const Eigen::Matrix2d D_inv = D.inverse();
    w.t -= w.A * (D_inv * Eigen::Vector2d(dp[4], dp[5]));
    w.A = w.A * D_inv;
    step = dp.tail<2>().norm();
    converged = step < kConvergedPx;
  }
  if (!converged && step > kSettledPx) return false;
  // The linear part: a patch seen from a third of the way or three times as far is no longer the same surface.
  const Eigen::JacobiSVD<Eigen::Matrix2d> svd(w.A);
  const Eigen::Vector2d s = svd.singularValues();
  if (!(s[0] < 3.0 && s[1] > 1.0 / 3.0)) return false;
  if (cur.dot(ref_) < min_zncc) return false;
  *warp = w;
  return true;
}

}  // namespace twinslam::tracking

#pragma once
// The silhouette corner of a box against the sky, measured in a rendered image (test_render, test_imperfect_camera).
#include <cmath>
#include <cstdint>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>
#include <opencv2/core.hpp>

namespace twinslam::sim::testing {

// Least-squares line x = a + b y through (y, x) samples.
inline Eigen::Vector2d fit(const std::vector<Eigen::Vector2d>& yx) {
  Eigen::MatrixXd A(yx.size(), 2);
  Eigen::VectorXd x(yx.size());
  for (std::size_t i = 0; i < yx.size(); ++i) {
    A(i, 0) = 1;
    A(i, 1) = yx[i][0];
    x[i] = yx[i][1];
  }
  return A.colPivHouseholderQr().solve(x);
}

// The silhouette corner measured in the image: the box's left edge (first dark pixel scanning right, rows below
// the corner) and top edge (first dark pixel scanning down, columns right of the corner), each a line fitted over
// 28 px, intersected. Single-sample rendering quantizes each edge to a pixel boundary; the fit averages that out
// only if the edge crosses several pixel columns/rows, so the cameras are rolled (see rolled()).
inline Eigen::Vector2d measured_corner(const cv::Mat& image, const Eigen::Vector2d& guess) {
  constexpr int kDark = 195;  // sky >= 205, surfaces <= 184 (+ noise)
  const int u0 = static_cast<int>(std::lround(guess.x())), v0 = static_cast<int>(std::lround(guess.y()));
  std::vector<Eigen::Vector2d> left, top;  // (v, u_edge) and (u, v_edge)
  for (int k = 3; k <= 30; ++k) {
    for (int u = u0 - 20; u <= u0 + 20; ++u)
      if (image.at<std::uint8_t>(v0 + k, u) < kDark) {
        left.emplace_back(v0 + k, u - 0.5);
        break;
      }
    for (int v = v0 - 20; v <= v0 + 20; ++v)
      if (image.at<std::uint8_t>(v, u0 + k) < kDark) {
        top.emplace_back(u0 + k, v - 0.5);
        break;
      }
  }
  EXPECT_EQ(left.size(), 28u);
  EXPECT_EQ(top.size(), 28u);
  const Eigen::Vector2d l = fit(left), t = fit(top);  // u = l0 + l1 v, v = t0 + t1 u
  const double u = (l[0] + l[1] * t[0]) / (1 - l[1] * t[1]);
  return {u, t[0] + t[1] * u};
}

}  // namespace twinslam::sim::testing

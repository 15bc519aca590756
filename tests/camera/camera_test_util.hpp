#pragma once
// Shared helpers for the camera tests: the models under test and central-difference Jacobians.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <functional>
#include <ostream>

#include "twinslam/camera/camera_model.hpp"

namespace twinslam::test {

// EuRoC V1_01 cam0 (MT9M034), from mav0/cam0/sensor.yaml.
inline CameraIntrinsics euroc_cam0() {
  CameraIntrinsics in;
  in.distortion = DistortionModel::kRadialTangential;
  in.width = 752;
  in.height = 480;
  in.fu = 458.654;
  in.fv = 457.296;
  in.cu = 367.215;
  in.cv = 248.375;
  in.coefficients = {-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05};
  return in;
}

}  // namespace twinslam::test

namespace twinslam {
// Short gtest names for parameterized tests (instead of a byte dump).
inline void PrintTo(const CameraIntrinsics& in, std::ostream* os) {
  *os << to_string(in.distortion) << " " << in.width << "x" << in.height << " f=" << in.fu;
}
}  // namespace twinslam

namespace twinslam::test {

// Central differences of f: R^n -> R^m at x, step h per coordinate.
template <int M, int N>
Eigen::Matrix<double, M, N> numeric_jacobian(const std::function<Eigen::Matrix<double, M, 1>(
                                                 const Eigen::Matrix<double, N, 1>&)>& f,
                                             const Eigen::Matrix<double, N, 1>& x, double h) {
  Eigen::Matrix<double, M, N> J;
  for (int i = 0; i < N; ++i) {
    Eigen::Matrix<double, N, 1> xp = x, xm = x;
    xp(i) += h;
    xm(i) -= h;
    J.col(i) = (f(xp) - f(xm)) / (2.0 * h);
  }
  return J;
}

// Relative error ||A - B|| / ||B|| (Frobenius).
template <typename A, typename B>
double relative_error(const A& a, const B& b) {
  return (a - b).norm() / b.norm();
}

// Calls fn(uv) for every pixel centre of the image plus the outer edges of the border pixels (-0.5 and size-0.5).
inline void for_each_pixel(const CameraModel& cam, const std::function<void(const Eigen::Vector2d&)>& fn) {
  auto coords = [](int n) {
    std::vector<double> c{-0.5};
    for (int i = 0; i < n; ++i) c.push_back(i);
    c.push_back(n - 0.5);
    return c;
  };
  const auto us = coords(cam.width()), vs = coords(cam.height());
  for (double v : vs) {
    for (double u : us) fn(Eigen::Vector2d(u, v));
  }
}

}  // namespace twinslam::test

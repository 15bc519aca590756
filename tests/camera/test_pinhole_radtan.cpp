// Pinhole + radial-tangential: round trips across the whole EuRoC image, analytic vs numeric Jacobians, agreement
// with OpenCV's projectPoints (the convention EuRoC calibrations are made in) and the fold-over domain.
#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <random>
#include <string>

#include "camera_test_util.hpp"
#include "twinslam/camera/pinhole_radtan.hpp"
#include "twinslam/core/error.hpp"

namespace twinslam {
namespace {

using test::euroc_cam0;

// A stronger lens than EuRoC's (a wide-angle action camera), still one-to-one over its image.
CameraIntrinsics strong_radtan() {
  CameraIntrinsics in = euroc_cam0();
  in.width = 640;
  in.height = 400;
  in.fu = 300.0;
  in.fv = 305.0;
  in.cu = 321.3;
  in.cv = 197.8;
  in.coefficients = {-0.38, 0.12, 1.5e-3, -2.0e-3};
  return in;
}

class PinholeRadtanRoundTrip : public ::testing::TestWithParam<CameraIntrinsics> {};

TEST_P(PinholeRadtanRoundTrip, EveryPixelUnprojectsAndProjectsBackWithin1e9Px) {
  const PinholeRadtan cam(GetParam());
  double worst = 0.0;
  int n = 0;
  test::for_each_pixel(cam, [&](const Eigen::Vector2d& uv) {
    Eigen::Vector3d f_C;
    ASSERT_TRUE(cam.unproject(uv, &f_C)) << "pixel " << uv.transpose();
    ASSERT_NEAR(f_C.norm(), 1.0, 1e-12);
    Eigen::Vector2d uv2;
    ASSERT_EQ(cam.project(f_C, &uv2), ProjectionStatus::kOk);
    worst = std::max(worst, (uv2 - uv).norm());
    ++n;
  });
  EXPECT_LT(worst, 1e-9) << "over " << n << " pixels";
}

TEST_P(PinholeRadtanRoundTrip, BearingsThatLandInTheImageUnprojectBackWithin1e9) {
  const PinholeRadtan cam(GetParam());
  // A grid of undistorted normalized coordinates wider than the image; keep the rays that land inside it.
  double worst = 0.0;
  int tested = 0;
  for (double y = -1.2; y <= 1.2; y += 0.01) {
    for (double x = -1.6; x <= 1.6; x += 0.01) {
      const Eigen::Vector3d f_C = Eigen::Vector3d(x, y, 1.0).normalized();
      Eigen::Vector2d uv;
      if (cam.project(f_C, &uv) != ProjectionStatus::kOk || !cam.in_image(uv)) continue;
      Eigen::Vector3d f2;
      ASSERT_TRUE(cam.unproject(uv, &f2)) << "pixel " << uv.transpose();
      worst = std::max(worst, (f2 - f_C).norm());
      ++tested;
    }
  }
  EXPECT_GT(tested, 10000);
  EXPECT_LT(worst, 1e-9);
}

// Named by index: both lenses print as "radial-tangential", and CTest needs distinct names to run each.
INSTANTIATE_TEST_SUITE_P(Lenses, PinholeRadtanRoundTrip, ::testing::Values(euroc_cam0(), strong_radtan()),
                         [](const ::testing::TestParamInfo<CameraIntrinsics>& info) {
                           return info.index == 0 ? std::string("EurocCam0") : std::string("StrongWideAngle");
                         });

TEST(PinholeRadtan, ProjectionJacobianMatchesCentralDifferences) {
  for (const auto& in : {euroc_cam0(), strong_radtan()}) {
    const PinholeRadtan cam(in);
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> xy(-0.8, 0.8), depth(0.3, 20.0);
    int checked = 0;
    for (int i = 0; i < 500; ++i) {
      const double z = depth(rng);
      const Eigen::Vector3d p_C(xy(rng) * z, xy(rng) * z, z);
      Eigen::Vector2d uv;
      Matrix23d J;
      ASSERT_EQ(cam.project(p_C, &uv, &J), ProjectionStatus::kOk);
      const auto f = [&](const Eigen::Vector3d& p) {
        Eigen::Vector2d out;
        cam.project(p, &out);
        return out;
      };
      const Matrix23d J_num = test::numeric_jacobian<2, 3>(f, p_C, 1e-6 * p_C.norm());
      EXPECT_LT(test::relative_error(J, J_num), 1e-6) << "p_C " << p_C.transpose();
      ++checked;
    }
    EXPECT_EQ(checked, 500);
  }
}

TEST(PinholeRadtan, DistortionAndIntrinsicsJacobiansMatchCentralDifferences) {
  const CameraIntrinsics in = strong_radtan();
  const PinholeRadtan cam(in);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> xy(-0.9, 0.9);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector2d m(xy(rng), xy(rng));
    Eigen::Vector2d m_d;
    Eigen::Matrix2d J;
    ASSERT_TRUE(cam.distort(m, &m_d, &J));
    const auto f = [&](const Eigen::Vector2d& q) {
      Eigen::Vector2d out;
      cam.distort(q, &out);
      return out;
    };
    EXPECT_LT(test::relative_error(J, test::numeric_jacobian<2, 2>(f, m, 1e-6)), 1e-6) << m.transpose();

    const Eigen::Vector3d p_C(m.x() * 3.0, m.y() * 3.0, 3.0);
    Matrix28d J_k;
    ASSERT_TRUE(cam.jacobian_wrt_intrinsics(p_C, &J_k));
    const auto g = [&](const Eigen::Matrix<double, 8, 1>& k) {
      CameraIntrinsics c = in;
      c.fu = k[0], c.fv = k[1], c.cu = k[2], c.cv = k[3];
      for (int j = 0; j < 4; ++j) c.coefficients[j] = k[4 + j];
      Eigen::Vector2d out;
      PinholeRadtan(c).project(p_C, &out);
      return out;
    };
    Eigen::Matrix<double, 8, 1> k0;
    k0 << in.fu, in.fv, in.cu, in.cv, in.coefficients[0], in.coefficients[1], in.coefficients[2],
        in.coefficients[3];
    EXPECT_LT(test::relative_error(J_k, test::numeric_jacobian<2, 8>(g, k0, 1e-4)), 1e-6);
  }
}

TEST(PinholeRadtan, AgreesWithOpenCvProjectPoints) {
  const CameraIntrinsics in = euroc_cam0();
  const PinholeRadtan cam(in);
  const cv::Matx33d K(in.fu, 0, in.cu, 0, in.fv, in.cv, 0, 0, 1);
  const std::vector<double> dist(in.coefficients.begin(), in.coefficients.end());
  std::vector<cv::Point3d> pts;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> xy(-0.9, 0.9);
  for (int i = 0; i < 100; ++i) pts.emplace_back(xy(rng) * 2.0, xy(rng) * 2.0, 2.0);
  std::vector<cv::Point2d> cv_uv;
  cv::projectPoints(pts, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, dist, cv_uv);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    Eigen::Vector2d uv;
    ASSERT_EQ(cam.project(Eigen::Vector3d(pts[i].x, pts[i].y, pts[i].z), &uv), ProjectionStatus::kOk);
    EXPECT_NEAR(uv.x(), cv_uv[i].x, 1e-9);
    EXPECT_NEAR(uv.y(), cv_uv[i].y, 1e-9);
  }
}

TEST(PinholeRadtan, WithoutDistortionIsThePlainPinhole) {
  CameraIntrinsics in = euroc_cam0();
  in.coefficients = {0, 0, 0, 0};
  const PinholeRadtan cam(in);
  Eigen::Vector2d uv;
  ASSERT_EQ(cam.project(Eigen::Vector3d(1.0, -0.5, 2.0), &uv), ProjectionStatus::kOk);
  EXPECT_NEAR(uv.x(), 458.654 * 0.5 + 367.215, 1e-12);
  EXPECT_NEAR(uv.y(), 457.296 * -0.25 + 248.375, 1e-12);
}

TEST(PinholeRadtan, PointsBehindTheCameraAreRejected) {
  const PinholeRadtan cam(euroc_cam0());
  Eigen::Vector2d uv;
  EXPECT_EQ(cam.project(Eigen::Vector3d(0.1, 0.2, -1.0), &uv), ProjectionStatus::kBehindCamera);
  EXPECT_EQ(cam.project(Eigen::Vector3d(0.1, 0.2, 0.0), &uv), ProjectionStatus::kBehindCamera);
  EXPECT_FALSE(cam.jacobian_wrt_intrinsics(Eigen::Vector3d(0, 0, -1), nullptr));
}

TEST(PinholeRadtan, RaysBeyondTheLensFoldAreOutsideTheDomain) {
  // k1 < 0, k2 = 0: r (1 + k1 r^2) peaks at r^2 = -1 / (3 k1) = 1 / 0.9; beyond it two rays share one pixel.
  CameraIntrinsics in = euroc_cam0();
  in.coefficients = {-0.3, 0.0, 0.0, 0.0};
  const PinholeRadtan cam(in);
  EXPECT_NEAR(cam.max_r2(), 1.0 / 0.9, 1e-12);
  Eigen::Vector2d uv;
  EXPECT_EQ(cam.project(Eigen::Vector3d(1.0, 0.0, 1.0), &uv), ProjectionStatus::kOk);
  EXPECT_EQ(cam.project(Eigen::Vector3d(1.1, 0.0, 1.0), &uv), ProjectionStatus::kOutsideDomain);
  // The largest distorted radius is r_max (1 + k1 r_max^2) = 0.7027; a pixel further out has no ray.
  Eigen::Vector3d f_C;
  EXPECT_FALSE(cam.unproject(Eigen::Vector2d(in.cu + in.fu * 0.75, in.cv), &f_C));
  EXPECT_TRUE(cam.unproject(Eigen::Vector2d(in.cu + in.fu * 0.70, in.cv), &f_C));
  EXPECT_LT(f_C.x() / f_C.z(), std::sqrt(cam.max_r2()));
}

TEST(PinholeRadtan, RejectsInvalidIntrinsics) {
  CameraIntrinsics in = euroc_cam0();
  in.fu = -1.0;
  EXPECT_THROW(PinholeRadtan{in}, InputError);
  in = euroc_cam0();
  in.distortion = DistortionModel::kEquidistant;
  EXPECT_THROW(PinholeRadtan{in}, InputError);
}

}  // namespace
}  // namespace twinslam

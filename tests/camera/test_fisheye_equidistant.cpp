// Fisheye equidistant (Kannala-Brandt): round trips across the whole image at 120 and 190 degrees field of view
// (rays behind the image plane included), analytic vs numeric Jacobians, agreement with OpenCV's fisheye model.
#include <gtest/gtest.h>

#include <numbers>
#include <opencv2/calib3d.hpp>
#include <random>

#include "camera_test_util.hpp"
#include "twinslam/camera/fisheye_equidistant.hpp"
#include "twinslam/core/error.hpp"

namespace twinslam {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// 640 x 400 fisheye whose horizontal field of view is fov_deg: the left/right image edges (u = -0.5, 639.5) see rays
// at fov/2 from the axis. Distortion like a real Kalibr equidistant calibration.
CameraIntrinsics fisheye(double fov_deg) {
  CameraIntrinsics in;
  in.distortion = DistortionModel::kEquidistant;
  in.width = 640;
  in.height = 400;
  in.coefficients = {0.012, -0.0048, 0.0011, -1.2e-4};
  const double t = 0.5 * fov_deg * kDeg;
  const double td = t * (1 + t * t * (0.012 + t * t * (-0.0048 + t * t * (0.0011 + t * t * -1.2e-4))));
  in.fu = in.fv = 320.0 / td;
  in.cu = 319.5;
  in.cv = 199.5;
  return in;
}

class FisheyeRoundTrip : public ::testing::TestWithParam<double> {};

TEST_P(FisheyeRoundTrip, EveryPixelUnprojectsAndProjectsBackWithin1e9Px) {
  const FisheyeEquidistant cam(fisheye(GetParam()));
  double worst = 0.0, widest = 0.0;
  test::for_each_pixel(cam, [&](const Eigen::Vector2d& uv) {
    Eigen::Vector3d f_C;
    ASSERT_TRUE(cam.unproject(uv, &f_C)) << "pixel " << uv.transpose();
    ASSERT_NEAR(f_C.norm(), 1.0, 1e-12);
    Eigen::Vector2d uv2;
    ASSERT_EQ(cam.project(f_C, &uv2), ProjectionStatus::kOk);
    worst = std::max(worst, (uv2 - uv).norm());
    widest = std::max(widest, std::acos(f_C.z()));
  });
  EXPECT_LT(worst, 1e-9);
  // The image really spans the field of view (its corners see even wider than the horizontal edges).
  EXPECT_GT(widest, 0.5 * GetParam() * kDeg);
}

TEST_P(FisheyeRoundTrip, BearingsOverTheFieldOfViewUnprojectBackWithin1e9) {
  const FisheyeEquidistant cam(fisheye(GetParam()));
  const double half_fov = 0.5 * GetParam() * kDeg;
  double worst = 0.0;
  int tested = 0, behind = 0;
  for (double theta = 0.0; theta <= half_fov; theta += half_fov / 200.0) {
    for (double phi = 0.0; phi < 2.0 * std::numbers::pi; phi += 0.01) {
      const Eigen::Vector3d f_C(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
      Eigen::Vector2d uv;
      ASSERT_EQ(cam.project(f_C, &uv), ProjectionStatus::kOk) << "theta " << theta;
      Eigen::Vector3d f2;
      ASSERT_TRUE(cam.unproject(uv, &f2));
      worst = std::max(worst, (f2 - f_C).norm());
      ++tested;
      behind += f_C.z() < 0.0;
    }
  }
  EXPECT_LT(worst, 1e-9) << "over " << tested << " bearings";
  if (GetParam() > 180.0) {
    EXPECT_GT(behind, 1000) << "the wide lens must be tested behind the image plane";
  }
}

INSTANTIATE_TEST_SUITE_P(FieldsOfView, FisheyeRoundTrip, ::testing::Values(120.0, 190.0));

TEST(FisheyeEquidistant, ProjectionJacobianMatchesCentralDifferences) {
  for (double fov : {120.0, 190.0}) {
    const FisheyeEquidistant cam(fisheye(fov));
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int i = 0; i < 500; ++i) {
      // Uniform over the directions within the field of view, at depths 0.3..20 m.
      const double theta = std::acos(1.0 - unit(rng) * (1.0 - std::cos(0.5 * fov * kDeg)));
      const double phi = 2.0 * std::numbers::pi * unit(rng), range = 0.3 + 19.7 * unit(rng);
      const Eigen::Vector3d p_C =
          range * Eigen::Vector3d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
      Eigen::Vector2d uv;
      Matrix23d J;
      ASSERT_EQ(cam.project(p_C, &uv, &J), ProjectionStatus::kOk);
      const auto f = [&](const Eigen::Vector3d& p) {
        Eigen::Vector2d out;
        cam.project(p, &out);
        return out;
      };
      EXPECT_LT(test::relative_error(J, test::numeric_jacobian<2, 3>(f, p_C, 1e-6 * range)), 1e-6)
          << "fov " << fov << " p_C " << p_C.transpose();
    }
  }
}

TEST(FisheyeEquidistant, JacobianOnTheOpticalAxisIsTheLimit) {
  const FisheyeEquidistant cam(fisheye(120.0));
  const double f = cam.intrinsics().fu, z = 2.5;
  Eigen::Vector2d uv;
  Matrix23d J;
  ASSERT_EQ(cam.project(Eigen::Vector3d(0, 0, z), &uv, &J), ProjectionStatus::kOk);
  Matrix23d expected;  // on the axis the lens is locally a pinhole with focal f
  expected << f / z, 0, 0, 0, f / z, 0;
  EXPECT_LT((J - expected).norm(), 1e-12 * f);
}

TEST(FisheyeEquidistant, DistortionAndIntrinsicsJacobiansMatchCentralDifferences) {
  const CameraIntrinsics in = fisheye(190.0);
  const FisheyeEquidistant cam(in);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> xy(-2.0, 2.0);
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

    // Intrinsics Jacobian, also behind the image plane (z < 0).
    const Eigen::Vector3d p_C(m.x(), m.y(), i % 2 == 0 && m.norm() > 0.5 ? -0.05 : 1.0);
    Matrix28d J_k;
    ASSERT_TRUE(cam.jacobian_wrt_intrinsics(p_C, &J_k));
    const auto g = [&](const Eigen::Matrix<double, 8, 1>& k) {
      CameraIntrinsics c = in;
      c.fu = k[0], c.fv = k[1], c.cu = k[2], c.cv = k[3];
      for (int j = 0; j < 4; ++j) c.coefficients[j] = k[4 + j];
      Eigen::Vector2d out;
      FisheyeEquidistant(c).project(p_C, &out);
      return out;
    };
    Eigen::Matrix<double, 8, 1> k0;
    k0 << in.fu, in.fv, in.cu, in.cv, in.coefficients[0], in.coefficients[1], in.coefficients[2],
        in.coefficients[3];
    EXPECT_LT(test::relative_error(J_k, test::numeric_jacobian<2, 8>(g, k0, 1e-4)), 1e-6);
  }
}

TEST(FisheyeEquidistant, AgreesWithOpenCvFisheyeProjectPoints) {
  const CameraIntrinsics in = fisheye(120.0);
  const FisheyeEquidistant cam(in);
  const cv::Matx33d K(in.fu, 0, in.cu, 0, in.fv, in.cv, 0, 0, 1);
  const cv::Vec4d D(in.coefficients[0], in.coefficients[1], in.coefficients[2], in.coefficients[3]);
  std::vector<cv::Point3d> pts;
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> xy(-1.5, 1.5);
  for (int i = 0; i < 100; ++i) pts.emplace_back(xy(rng), xy(rng), 1.0);
  std::vector<cv::Point2d> cv_uv;
  cv::fisheye::projectPoints(pts, cv_uv, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, D);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    Eigen::Vector2d uv;
    ASSERT_EQ(cam.project(Eigen::Vector3d(pts[i].x, pts[i].y, pts[i].z), &uv), ProjectionStatus::kOk);
    EXPECT_NEAR(uv.x(), cv_uv[i].x, 1e-9);
    EXPECT_NEAR(uv.y(), cv_uv[i].y, 1e-9);
  }
}

TEST(FisheyeEquidistant, ARaySidewaysLandsAtThetaDOfNinetyDegrees) {
  CameraIntrinsics in = fisheye(190.0);
  in.coefficients = {0, 0, 0, 0};  // ideal equidistant: radius = f * theta
  const FisheyeEquidistant cam(in);
  Eigen::Vector2d uv;
  ASSERT_EQ(cam.project(Eigen::Vector3d(3.0, 0.0, 0.0), &uv), ProjectionStatus::kOk);
  EXPECT_NEAR(uv.x(), in.cu + in.fu * std::numbers::pi / 2.0, 1e-9);
  EXPECT_NEAR(uv.y(), in.cv, 1e-12);
  ASSERT_EQ(cam.project(Eigen::Vector3d(0.0, -1.0, -1.0), &uv), ProjectionStatus::kOk);  // 135 degrees off axis
  EXPECT_NEAR(uv.y(), in.cv - in.fv * 0.75 * std::numbers::pi, 1e-9);
}

TEST(FisheyeEquidistant, RaysBeyondTheMonotonicRangeAreOutsideTheDomain) {
  CameraIntrinsics in = fisheye(120.0);
  in.coefficients = {-0.1, 0.0, 0.0, 0.0};  // theta_d' = 1 - 0.3 theta^2 vanishes at theta = sqrt(1/0.3)
  const FisheyeEquidistant cam(in);
  EXPECT_NEAR(cam.max_theta(), std::sqrt(1.0 / 0.3), 1e-12);
  Eigen::Vector2d uv;
  const double t_in = cam.max_theta() - 0.01, t_out = cam.max_theta() + 0.01;
  EXPECT_EQ(cam.project(Eigen::Vector3d(std::sin(t_in), 0, std::cos(t_in)), &uv), ProjectionStatus::kOk);
  EXPECT_EQ(cam.project(Eigen::Vector3d(std::sin(t_out), 0, std::cos(t_out)), &uv),
            ProjectionStatus::kOutsideDomain);
  EXPECT_EQ(cam.project(Eigen::Vector3d(0, 0, -1), &uv), ProjectionStatus::kOutsideDomain);
  EXPECT_EQ(cam.project(Eigen::Vector3d(0, 0, 0), &uv), ProjectionStatus::kOutsideDomain);
  Eigen::Vector3d f_C;
  const double td_max = cam.theta_d(cam.max_theta());
  EXPECT_FALSE(cam.unproject(Eigen::Vector2d(in.cu + in.fu * (td_max + 0.01), in.cv), &f_C));
  ASSERT_TRUE(cam.unproject(Eigen::Vector2d(in.cu + in.fu * (td_max - 0.01), in.cv), &f_C));
  EXPECT_LT(std::acos(f_C.z()), cam.max_theta());
}

TEST(FisheyeEquidistant, RejectsInvalidIntrinsics) {
  CameraIntrinsics in = fisheye(120.0);
  in.coefficients[2] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(FisheyeEquidistant{in}, InputError);
  in = fisheye(120.0);
  in.distortion = DistortionModel::kRadialTangential;
  EXPECT_THROW(FisheyeEquidistant{in}, InputError);
}

}  // namespace
}  // namespace twinslam

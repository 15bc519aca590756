// Renderer: bit-identical images per seed (any thread count), world corners land where the camera model projects
// them (both models), ray casts and visibility give known answers, and a city frame has enough corners for KLT.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "corner_measure.hpp"
#include "sim_world_test_utils.hpp"
#include "twinslam/sim/world/city.hpp"
#include "twinslam/sim/world/renderer.hpp"
#include "twinslam/sim/world/top_down.hpp"

namespace twinslam::sim {
namespace {

using testing::fisheye_120;
using testing::look_at;
using testing::measured_corner;
using testing::pinhole_90;

const City& city() {
  static const City c = build_city(CityConfig{}, 7);
  return c;
}

// A view like the loops trajectory: 10 m up, 45 m from the tower, looking at it.
Eigen::Isometry3d loops_view() { return look_at({45, 0, 10}, {0, 0, 25}); }

TEST(SimWorldRender, SameSeedSameImageAnyThreadCount) {
  RenderConfig one;
  one.threads = 1;
  const Renderer a(city().mesh), b(build_city(CityConfig{}, 7).mesh, one);
  const auto cam = fisheye_120();
  const cv::Mat ia = a.render(loops_view(), *cam, 42), ib = b.render(loops_view(), *cam, 42);
  ASSERT_EQ(ia.type(), CV_8UC1);
  ASSERT_EQ(ia.cols, 640);
  ASSERT_EQ(ia.rows, 400);
  EXPECT_EQ(cv::norm(ia, ib, cv::NORM_INF), 0.0);
}

TEST(SimWorldRender, DifferentSeedsDiffer) {
  const Renderer r(city().mesh);
  const auto cam = fisheye_120();
  const cv::Mat base = r.render(loops_view(), *cam, 1);
  // Another noise seed: small differences in most pixels.
  const cv::Mat noise = r.render(loops_view(), *cam, 2);
  cv::Mat diff;
  cv::absdiff(base, noise, diff);
  EXPECT_GT(cv::countNonZero(diff), base.total() / 2);
  EXPECT_LT(cv::mean(diff)[0], 4.0);
  // Another city: a different picture.
  const Renderer other(build_city(CityConfig{}, 8).mesh);
  cv::absdiff(base, other.render(loops_view(), *cam, 1), diff);
  EXPECT_GT(cv::mean(diff)[0], 10.0);
}

// One box against the sky; the camera sits inside the box's x and z extent, so only its front face (y = 25) is seen
// and the face's top-left corner is a silhouette corner.
TriMesh single_box() {
  TriMesh m;
  add_box(&m, {-4, 25, -3}, {6, 35, 8}, SurfaceKind::kFacade, SurfaceKind::kRoof, 0, true);
  return m;
}

// A 40 m x 40 m ground square with one 10 m box on it.
TriMesh single_box_for_top_down() {
  TriMesh m;
  m.add_quad({-20, -20, 0}, {20, -20, 0}, {20, 20, 0}, {-20, 20, 0}, SurfaceKind::kGround, kNoBuilding);
  add_box(&m, {-4, 5, 0}, {6, 15, 10}, SurfaceKind::kFacade, SurfaceKind::kRoof, 0);
  return m;
}

// The camera rolled about its optical axis by roll_deg, so the box edges are slanted in the image.
Eigen::Isometry3d rolled(const Eigen::Isometry3d& T_WC, double roll_deg) {
  return T_WC * Eigen::AngleAxisd(roll_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ());
}

void expect_corner_within_1px(const CameraModel& cam, const Eigen::Isometry3d& T_WC) {
  const Renderer r(single_box());
  const cv::Mat image = r.render(T_WC, cam, 3);
  const Eigen::Vector3d corner_W(-4, 25, 8);
  Eigen::Vector2d projected;
  ASSERT_EQ(cam.project(T_WC.inverse() * corner_W, &projected), ProjectionStatus::kOk);
  ASSERT_TRUE(cam.in_image(projected, 40));
  const Eigen::Vector2d measured = measured_corner(image, projected);
  ::testing::Test::RecordProperty("corner_error_px", std::to_string((measured - projected).norm()));
  // Issue 3 asks for 1 px; measured <= 0.15 px, and 0.5 px also catches a half-pixel convention slip.
  EXPECT_LT((measured - projected).norm(), 0.5) << "projected " << projected.transpose() << " measured "
                                                << measured.transpose();
}

TEST(SimWorldRender, ProjectedCornerLandsOnRenderedCornerFisheye) {
  const auto cam = fisheye_120();
  expect_corner_within_1px(*cam, rolled(look_at({0.5, 0, 0.5}, {3, 25, 1}), 12));   // corner ~40 deg off-axis
  expect_corner_within_1px(*cam, rolled(look_at({1, 0, 2}, {-2, 25, 6}), -9));     // corner near the centre
}

TEST(SimWorldRender, ProjectedCornerLandsOnRenderedCornerPinhole) {
  const auto cam = pinhole_90();
  expect_corner_within_1px(*cam, rolled(look_at({0.5, 0, 0.5}, {2, 25, 3}), 12));
  expect_corner_within_1px(*cam, rolled(look_at({1, 0, 2}, {-2, 25, 6}), -9));
}

TEST(SimWorldRender, RaycastAndVisibilityHaveKnownAnswers) {
  const Renderer r(single_box());
  const auto t = r.raycast({0, 0, 0}, {0, 2, 0});  // direction need not be unit
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(*t, 25.0, 1e-4);
  EXPECT_FALSE(r.raycast({0, 0, 0}, {0, -1, 0}).has_value());
  const Eigen::Vector3d c_W(0, 0, 0);
  EXPECT_TRUE(r.visible({1, 25, 1}, c_W));    // on the front face
  EXPECT_FALSE(r.visible({1, 35, 1}, c_W));   // on the back face, behind the front
  EXPECT_TRUE(r.visible({1, 20, 1}, c_W));    // free space in front
}

TEST(SimWorldRender, EmptyWorldIsAllSky) {
  RenderConfig config;
  config.noise_sigma = 0;
  const Renderer r(TriMesh{}, config);
  const auto cam = pinhole_90();
  const cv::Mat image = r.render(look_at({0, 0, 0}, {0, 10, 8}), *cam, 1);  // 39 deg up: all rays above the horizon
  double lo, hi;
  cv::minMaxLoc(image, &lo, &hi);
  EXPECT_GE(lo, 205);
  EXPECT_LE(hi, 240);
  EXPECT_FALSE(r.raycast({0, 0, 0}, {0, 0, -1}).has_value());
}

TEST(SimWorldRender, CityFrameHasEnoughShiTomasiCorners) {
  const Renderer r(city().mesh);
  const auto cam = fisheye_120();
  for (const Eigen::Isometry3d& T_WC : {loops_view(), look_at({-80, -60, 10}, {-40, -20, 0})}) {
    const cv::Mat image = r.render(T_WC, *cam, 9);
    std::vector<cv::Point2f> corners;
    cv::goodFeaturesToTrack(image, corners, 1000, 0.01, 8);
    EXPECT_GE(corners.size(), 150u);
  }
}

}  // namespace
}  // namespace twinslam::sim

namespace twinslam::sim {
namespace {

TEST(SimWorldRender, TopDownPreviewMapsWorldToPixels) {
  const Renderer r(single_box_for_top_down());
  const TopDownImage map = render_top_down(r, 0.5);
  // Ground 40 x 40 m at 0.5 m/px; the 10 m tall box over [-4, 6] x [5, 15] is brighter than the ground.
  ASSERT_EQ(map.image.cols, 80);
  ASSERT_EQ(map.image.rows, 80);
  const cv::Point2d on_box = map.pixel(1, 10), on_ground = map.pixel(-15, -15);
  EXPECT_NEAR(on_box.x, 41.5, 1e-9);   // (1 - (-20)) / 0.5 - 0.5
  EXPECT_NEAR(on_box.y, 19.5, 1e-9);   // (20 - 10) / 0.5 - 0.5
  const int box = map.image.at<std::uint8_t>(static_cast<int>(on_box.y), static_cast<int>(on_box.x));
  const int ground = map.image.at<std::uint8_t>(static_cast<int>(on_ground.y), static_cast<int>(on_ground.x));
  EXPECT_GT(box, ground + 40);
}

}  // namespace
}  // namespace twinslam::sim

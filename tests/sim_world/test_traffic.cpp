// Moving cars (issue 13, item 6): on the street centrelines at their speed and out of the tower's ring, in the images
// where their geometry says and moving between frames, never in the world mesh nor the twin, hiding the landmarks
// behind them and carrying landmarks of their own in the ideal tracks.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "frame_tracks.hpp"
#include "sim_world_test_utils.hpp"
#include "twinslam/sim/feature_tracks.hpp"
#include "twinslam/sim/flight_trajectory.hpp"
#include "twinslam/sim/scenario_io.hpp"
#include "twinslam/sim/world/city.hpp"
#include "twinslam/sim/world/embree_scene.hpp"
#include "twinslam/sim/world/renderer.hpp"
#include "twinslam/sim/world/traffic.hpp"
#include "twinslam/sim/world/twin.hpp"

namespace twinslam::sim {
namespace {

using testing::look_at;
using testing::tracks_of;
using testing::pinhole_90;

const City& city() {
  static const City c = build_city(CityConfig{}, 7);
  return c;
}

const Traffic& traffic() {
  static const Traffic t(city().hints, TrafficSimConfig{60, 8.0}, 120, 7);
  return t;
}

Eigen::Vector2d xy(const Eigen::Isometry3d& T) { return T.translation().head<2>(); }

TEST(SimTraffic, CarsDriveOneWayOnTheStreetCentrelinesAtTheirSpeed) {
  const Traffic& cars = traffic();
  ASSERT_EQ(cars.size(), 60u);
  const StreetGrid& g = city().hints.streets;
  const double half = 0.5 * g.width_m, dt = 0.25, speed = 8.0;
  double closest_to_tower = 1e9;
  for (std::size_t k = 0; k < cars.size(); ++k) {
    for (double t = 0; t < 120; t += dt) {
      const Eigen::Isometry3d T = cars.T_WV(k, t), T2 = cars.T_WV(k, t + dt);
      const Eigen::Vector2d p = xy(T);
      double de = 1e9, dn = 1e9;
      for (const double e : g.east_m) de = std::min(de, std::abs(p.x() - e));
      for (const double n : g.north_m) dn = std::min(dn, std::abs(p.y() - n));
      // On a centreline, or turning inside an intersection.
      ASSERT_TRUE(std::min(de, dn) < 1e-6 || (de <= half + 1e-6 && dn <= half + 1e-6)) << k << " " << t;
      EXPECT_NEAR(T.translation().z(), 0.0, 1e-12);
      const double step = (xy(T2) - p).norm();
      EXPECT_LE(step, speed * dt + 1e-9);
      EXPECT_GE(step, 0.97 * speed * dt) << k << " " << t;  // chords of the turns are barely shorter
      // Facing where it goes.
      EXPECT_GT(T.linear().col(0).head<2>().dot(xy(cars.T_WV(k, t + 0.01)) - p), 0.0);
      closest_to_tower = std::min(closest_to_tower, (p - city().hints.tall_building_center_W).norm());
    }
  }
  // The ring the loops flight circles over stays free of traffic: the nearest a car comes to the tower is well outside
  // the city-loops circle.
  const LoopsGeometry loops = loops_geometry(builtin_scenario("city-loops"), city().hints);
  ::testing::Test::RecordProperty("closest_to_tower_m", std::to_string(closest_to_tower));
  EXPECT_GT(closest_to_tower, loops.radius_m + 5) << "loops radius " << loops.radius_m;
  // Seeded: the same seed the same traffic, another seed another.
  const Traffic again(city().hints, TrafficSimConfig{60, 8.0}, 120, 7), other(city().hints, {60, 8.0}, 120, 8);
  EXPECT_TRUE(again.T_WV(3, 17.0).isApprox(cars.T_WV(3, 17.0), 0.0));
  EXPECT_GT((xy(other.T_WV(3, 17.0)) - xy(cars.T_WV(3, 17.0))).norm(), 1.0);
  // 0 cars, or no street grid: none.
  EXPECT_TRUE(Traffic(city().hints, TrafficSimConfig{0, 8.0}, 120, 7).empty());
  EXPECT_TRUE(Traffic(SceneHints{}, TrafficSimConfig{60, 8.0}, 120, 7).empty());
}

// A car on a straight piece with nothing else near it for half a second, and a camera 9 m behind and 11 m above where
// it is at the middle of that half second, looking at it along the street (trees and parked cars stand aside).
struct CarView {
  std::size_t car = 0;
  double t = 0;
  Eigen::Isometry3d T_WC;
};
const CarView& car_view() {
  static const CarView view = [] {
    const Traffic& cars = traffic();
    for (double t = 10; t < 100; t += 0.5) {
      for (std::size_t k = 0; k < cars.size(); ++k) {
        const Eigen::Isometry3d a = cars.T_WV(k, t), b = cars.T_WV(k, t + 0.5);
        if (!a.linear().isApprox(b.linear(), 1e-12)) continue;  // turning
        bool alone = true;
        for (std::size_t j = 0; j < cars.size() && alone; ++j)
          alone = j == k || ((xy(cars.T_WV(j, t)) - xy(a)).norm() > 40 &&
                             (xy(cars.T_WV(j, t + 0.5)) - xy(b)).norm() > 40);
        if (!alone) continue;
        const Eigen::Isometry3d mid = cars.T_WV(k, t + 0.25);
        return CarView{k, t, look_at(mid * Eigen::Vector3d(-9, 0, 11), mid * Eigen::Vector3d(0, 0, 0.75))};
      }
    }
    ADD_FAILURE() << "no lonely car on a straight street";
    return CarView{};
  }();
  return view;
}

// The car's silhouette as its geometry projects: every triangle filled (their union is the outline).
cv::Mat predicted_mask(const Traffic& cars, std::size_t k, double t, const CameraModel& cam,
                       const Eigen::Isometry3d& T_WC) {
  cv::Mat mask(cam.height(), cam.width(), CV_8UC1, cv::Scalar(0));
  const TriMesh& m = cars.mesh_V(k);
  const Eigen::Isometry3d T_CV = T_WC.inverse() * cars.T_WV(k, t);
  for (const auto& tri : m.triangles) {
    std::vector<cv::Point> poly;
    for (int c = 0; c < 3; ++c) {
      Eigen::Vector2d uv;
      EXPECT_EQ(cam.project(T_CV * m.p_W[tri[c]], &uv), ProjectionStatus::kOk);
      // Pixel centres at integers; 4 fractional bits.
      poly.emplace_back(static_cast<int>(std::lround(uv.x() * 16)), static_cast<int>(std::lround(uv.y() * 16)));
    }
    cv::fillConvexPoly(mask, poly, cv::Scalar(255), cv::LINE_8, 4);
  }
  return mask;
}

double iou(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat both, either;
  cv::bitwise_and(a, b, both);
  cv::bitwise_or(a, b, either);
  return static_cast<double>(cv::countNonZero(both)) / std::max(1, cv::countNonZero(either));
}

Eigen::Vector2d centroid(const cv::Mat& mask) {
  const cv::Moments m = cv::moments(mask, true);
  return {m.m10 / m.m00, m.m01 / m.m00};
}

TEST(SimTraffic, ACarAppearsWhereItsGeometrySaysAndMovesBetweenFrames) {
  const CarView& view = car_view();
  const auto cam = pinhole_90();
  RenderConfig cfg;
  cfg.shadows = false;  // the silhouette alone (a car's shadow on the road changes pixels too)
  const Renderer r(city().mesh, cfg);
  const cv::Mat empty_street = r.render(view.T_WC, *cam, 5);
  std::vector<cv::Mat> masks;
  for (const double t : {view.t, view.t + 0.5}) {
    FrameCapture frame;
    frame.t_s = t;
    frame.T_WC = [&view](double) { return view.T_WC; };
    frame.traffic = &traffic();
    cv::Mat diff, mask;
    cv::absdiff(r.render(frame, *cam, 5), empty_street, diff);  // same noise: exactly 0 off the car
    cv::threshold(diff, mask, 0, 255, cv::THRESH_BINARY);
    const cv::Mat expected = predicted_mask(traffic(), view.car, t, *cam, view.T_WC);
    const double overlap = iou(mask, expected);
    const Eigen::Vector2d off = centroid(mask) - centroid(expected);
    ::testing::Test::RecordProperty("car_iou", std::to_string(overlap));
    EXPECT_GT(cv::countNonZero(expected), 2000);
    EXPECT_GT(overlap, 0.9) << "t " << t;
    EXPECT_LT(off.norm(), 1.0) << off.transpose();
    masks.push_back(mask);
  }
  // It moved: 4 m along the street, far more than its own length in the image... at least clearly apart.
  const Eigen::Vector2d moved = centroid(masks[1]) - centroid(masks[0]);
  Eigen::Vector2d a, b;
  cam->project(view.T_WC.inverse() * (traffic().T_WV(view.car, view.t) * Eigen::Vector3d(0, 0, 0.75)), &a);
  cam->project(view.T_WC.inverse() * (traffic().T_WV(view.car, view.t + 0.5) * Eigen::Vector3d(0, 0, 0.75)), &b);
  EXPECT_GT(moved.norm(), 30.0);
  EXPECT_LT((moved - (b - a)).norm(), 0.1 * (b - a).norm());
  EXPECT_LT(iou(masks[0], masks[1]), 0.5);
}

TEST(SimTraffic, CarsAreNeitherInTheWorldNorInTheTwin) {
  const CarView& view = car_view();
  const Twin twin = derive_twin(city(), TwinConfig{}, 7, {});
  const EmbreeScene world_scene(city().mesh), twin_scene(twin.mesh);
  const auto snapshot = traffic().snapshot(view.t, view.t);
  const Eigen::Isometry3d T_WV = traffic().T_WV(view.car, view.t);
  for (const Eigen::Vector3d& p_V :
       {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1.5, 0.5, 0), Eigen::Vector3d(-1.5, -0.5, 0)}) {
    const Eigen::Vector3d top = T_WV * p_V + Eigen::Vector3d(0, 0, 20), down(0, 0, -1);
    CarHit car;
    ASSERT_TRUE(snapshot->intersect(top, down, view.t, 100, &car));
    EXPECT_GT(20 - car.t_m, 0.9);  // the car's roof or bonnet
    RayHit world, twin_hit;
    ASSERT_TRUE(world_scene.intersect(top, down, 0, 100, &world));
    ASSERT_TRUE(twin_scene.intersect(top, down, 0, 100, &twin_hit));
    EXPECT_NEAR(world.t_m, 20, 1e-3);      // the street
    EXPECT_NEAR(twin_hit.t_m, 20, 1.0);    // the twin's street (its surfaces are noisy)
  }
}

// The rows of features.csv: id -> (u, v).

TEST(SimTraffic, TracksLoseWhatACarHidesAndFollowTheCarsOwnLandmarks) {
  const CarView& view = car_view();
  const auto cam = pinhole_90();
  RenderConfig cfg;
  cfg.shadows = false;
  const Renderer r(city().mesh, cfg);
  const Eigen::Vector3d under_car = traffic().T_WV(view.car, view.t) * Eigen::Vector3d(0.3, 0.2, 0);  // on the road
  FrameCapture frame;
  frame.t_s = view.t;
  frame.T_WC = [&view](double) { return view.T_WC; };
  FeatureTrackConfig config;
  config.landmarks_per_car = 30;  // (6 by default) enough that several face the camera
  const std::size_t per_car = 30;
  const auto without = tracks_of({under_car}, frame, *cam, r, nullptr, config);
  EXPECT_EQ(without.count(0), 1u);  // seen on the empty street
  frame.traffic = &traffic();
  const auto with = tracks_of({under_car}, frame, *cam, r, nullptr, config);
  EXPECT_EQ(with.count(0), 0u);  // hidden by the car
  // The car's own landmarks (ids 1 + car * 30 + j): those seen lie on the car in the image, and the next frame finds
  // them where the car has taken them.
  cv::Mat diff, mask;
  cv::absdiff(r.render(frame, *cam, 5), r.render(view.T_WC, *cam, 5), diff);
  cv::threshold(diff, mask, 0, 255, cv::THRESH_BINARY);
  cv::dilate(mask, mask, cv::Mat::ones(3, 3, CV_8UC1));
  FrameCapture later = frame;
  later.t_s = view.t + 0.1;
  const auto next = tracks_of({under_car}, later, *cam, r, nullptr, config);
  int on_car = 0;
  for (std::size_t j = 0; j < per_car; ++j) {
    const std::size_t id = 1 + view.car * per_car + j;
    if (!with.count(id)) continue;
    ++on_car;
    const Eigen::Vector2d uv = with.at(id);
    EXPECT_GT(mask.at<std::uint8_t>(static_cast<int>(std::lround(uv.y())), static_cast<int>(std::lround(uv.x()))), 0)
        << "landmark " << id << " at " << uv.transpose();
    ASSERT_EQ(next.count(id), 1u);
    EXPECT_GT((next.at(id) - uv).norm(), 3.0);  // 0.8 m along the street
  }
  EXPECT_GE(on_car, 5);
  for (const auto& row : with) EXPECT_LT(row.first, 1 + 60 * per_car);  // one static landmark, then the cars' own
}

// With everything on (rolling shutter, blur of a turning camera, cars in view), the image does not depend on the thread
// count, and tracing cars only in the blocks where their bounding spheres may be seen changes nothing.
TEST(SimTraffic, ImagesWithCarsAreTheSameForAnyThreadsAndWithoutCulling) {
  const CarView& view = car_view();
  const auto cam = testing::fisheye_120();
  RenderConfig fast, plain;
  plain.threads = 1;
  plain.cull_cars = false;
  const Renderer a(city().mesh, fast), b(city().mesh, plain);
  FrameCapture frame;
  frame.t_s = view.t;
  frame.shutter = {30e-6, 8e-3};
  frame.traffic = &traffic();
  frame.T_WC = [&view](double t) {
    Eigen::Isometry3d T = view.T_WC;
    T.linear() = Eigen::AngleAxisd(0.8 * (t - view.t), Eigen::Vector3d::UnitZ()) * T.linear();
    T.translation() += Eigen::Vector3d(3, 0, 0) * (t - view.t);
    return T;
  };
  RenderInfo info;
  const cv::Mat image = a.render(frame, *cam, 11, &info);
  EXPECT_GT(info.subexposures, 1);
  EXPECT_EQ(cv::norm(image, b.render(frame, *cam, 11), cv::NORM_INF), 0.0);
  FrameCapture no_cars = frame;
  no_cars.traffic = nullptr;
  EXPECT_GT(cv::norm(image, a.render(no_cars, *cam, 11), cv::NORM_L1), 1e4);  // the cars are in it
}

}  // namespace
}  // namespace twinslam::sim

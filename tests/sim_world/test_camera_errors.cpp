// Imperfect camera (issue 13): the camera-IMU time offset, the extrinsic and intrinsic calibration errors and
// auto-exposure each show in a simulated dataset as configured, and each key set to 0 gives the ideal output.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include <opencv2/imgcodecs.hpp>
#include <unistd.h>

#include "twinslam/camera/sensor_yaml.hpp"
#include "twinslam/sim/auto_exposure.hpp"
#include "twinslam/sim/camera_calibration.hpp"
#include "twinslam/sim/clock.hpp"
#include "twinslam/sim/flight_trajectory.hpp"
#include "twinslam/sim/scenario_io.hpp"
#include "twinslam/sim/sim_camera.hpp"
#include "twinslam/sim/simulate.hpp"
#include "twinslam/sim/world/city.hpp"
#include "twinslam/sim/world/surface_distance.hpp"

namespace twinslam::sim {
namespace {

namespace fs = std::filesystem;

double angle_deg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle() * 180.0 / M_PI;
}

std::string slurp(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(SimCameraErrors, CalibratedExtrinsicsDifferByExactlyTheConfiguredError) {
  Scenario s = builtin_scenario("city-loops");
  const Eigen::Isometry3d T_true = camera_T_BC(s);
  Eigen::Vector3d first_axis = Eigen::Vector3d::Zero();
  for (const std::uint64_t seed : {1u, 7u, 99u}) {
    for (const double deg : {0.1, 0.5, 3.0}) {
      for (const double m : {0.002, 0.01, 0.2}) {
        s.seed = seed;
        s.camera.extrinsic_error_deg = deg;
        s.camera.extrinsic_error_m = m;
        const Eigen::Isometry3d T = calibrated_T_BC(s);
        EXPECT_NEAR(angle_deg(T_true.linear(), T.linear()), deg, 1e-9);
        EXPECT_NEAR((T.translation() - T_true.translation()).norm(), m, 1e-12);
        EXPECT_NEAR((T.linear().transpose() * T.linear() - Eigen::Matrix3d::Identity()).norm(), 0, 1e-12);
        const Eigen::Vector3d axis = Eigen::AngleAxisd(T.linear() * T_true.linear().transpose()).axis();
        if (seed == 1 && deg == 0.1 && m == 0.002) first_axis = axis;
        if (seed != 1) {
          EXPECT_GT((axis - first_axis).norm(), 1e-3);  // seeded: another seed, another direction
        }
      }
    }
  }
  // The defaults (0.5 deg, 1 cm) in every scenario but tiny, and 0 keeps the true extrinsics bit for bit.
  s = builtin_scenario("city-loops");
  EXPECT_NEAR(angle_deg(camera_T_BC(s).linear(), calibrated_T_BC(s).linear()), 0.5, 1e-9);
  EXPECT_NEAR((calibrated_T_BC(s).translation() - camera_T_BC(s).translation()).norm(), 0.01, 1e-12);
  s.camera.extrinsic_error_deg = 0;
  EXPECT_EQ(calibrated_T_BC(s).linear(), camera_T_BC(s).linear());
  EXPECT_NE(calibrated_T_BC(s).translation(), camera_T_BC(s).translation());
  s.camera.extrinsic_error_m = 0;
  EXPECT_EQ(calibrated_T_BC(s).matrix(), camera_T_BC(s).matrix());
  const Scenario tiny = builtin_scenario("tiny");
  EXPECT_EQ(calibrated_T_BC(tiny).matrix(), camera_T_BC(tiny).matrix());
}

TEST(SimCameraErrors, CalibratedIntrinsicsDifferByExactlyTheConfiguredError) {
  Scenario s = builtin_scenario("city-loops");
  std::set<int> focal_signs, k1_signs;
  std::vector<Eigen::Vector2d> directions;
  for (const std::uint64_t seed : {1u, 2u, 3u, 7u, 99u}) {
    for (const double focal : {0.001, 0.01}) {
      s.seed = seed;
      s.camera.intrinsic_error_focal = focal;
      s.camera.intrinsic_error_px = 2.5;
      s.camera.intrinsic_error_k1 = 0.004;
      const CameraIntrinsicErrors e = camera_intrinsic_errors(s);
      EXPECT_NEAR(std::abs(e.focal_scale - 1.0), focal, 1e-15);
      EXPECT_NEAR(e.principal_point_shift_px.norm(), 2.5, 1e-12);
      EXPECT_NEAR(std::abs(e.k1_offset), 0.004, 1e-15);
      focal_signs.insert(e.focal_scale > 1 ? 1 : -1);
      k1_signs.insert(e.k1_offset > 0 ? 1 : -1);
      EXPECT_EQ(e.focal_scale > 1, e.k1_offset > 0);  // one sign: the radial errors add off-axis
      if (focal == 0.01) directions.push_back(e.principal_point_shift_px.normalized());
      // The stated calibration: the true intrinsics changed by exactly these errors, the stated extrinsics.
      const CameraIntrinsics truth = sim_camera_config(s).intrinsics;
      const CameraConfig stated = calibrated_sim_camera_config(s);
      EXPECT_NEAR(stated.intrinsics.fu / truth.fu, e.focal_scale, 1e-14);
      EXPECT_NEAR(stated.intrinsics.fv / truth.fv, e.focal_scale, 1e-14);
      EXPECT_NEAR(stated.intrinsics.cu - truth.cu, e.principal_point_shift_px.x(), 1e-12);
      EXPECT_NEAR(stated.intrinsics.cv - truth.cv, e.principal_point_shift_px.y(), 1e-12);
      EXPECT_NEAR(stated.intrinsics.coefficients[0] - truth.coefficients[0], e.k1_offset, 1e-15);
      EXPECT_EQ(stated.T_BC.matrix(), calibrated_T_BC(s).matrix());
    }
  }
  EXPECT_EQ(focal_signs.size(), 2u);  // seeded: both signs and several directions occur
  EXPECT_EQ(k1_signs.size(), 2u);
  EXPECT_GT((directions.front() - directions.back()).norm(), 1e-3);
  // The defaults in every scenario but tiny; a key at 0 changes no other draw; all 0: the true intrinsics exactly.
  s = builtin_scenario("city-loops");
  const CameraIntrinsicErrors d = camera_intrinsic_errors(s);
  EXPECT_NEAR(std::abs(d.focal_scale - 1), 0.003, 1e-15);
  EXPECT_NEAR(d.principal_point_shift_px.norm(), 1.0, 1e-12);
  EXPECT_NEAR(std::abs(d.k1_offset), 0.002, 1e-15);
  s.camera.intrinsic_error_focal = 0;
  EXPECT_EQ(camera_intrinsic_errors(s).focal_scale, 1.0);
  EXPECT_EQ(camera_intrinsic_errors(s).principal_point_shift_px, d.principal_point_shift_px);
  EXPECT_EQ(camera_intrinsic_errors(s).k1_offset, d.k1_offset);
  s.camera.intrinsic_error_px = s.camera.intrinsic_error_k1 = 0;
  const CameraIntrinsics truth = sim_camera_config(s).intrinsics, stated = calibrated_sim_camera_config(s).intrinsics;
  EXPECT_TRUE(truth.fu == stated.fu && truth.fv == stated.fv && truth.cu == stated.cu && truth.cv == stated.cv &&
              truth.coefficients == stated.coefficients);
  const CameraIntrinsicErrors none = camera_intrinsic_errors(builtin_scenario("tiny"));
  EXPECT_TRUE(none.focal_scale == 1.0 && none.principal_point_shift_px.isZero(0) && none.k1_offset == 0.0);
}

// Auto-exposure on uniform frames: the scene steps from 100 to 50 grey levels. The frame after the step is as dark as
// the scene (the loop cannot know), then the gain returns to target / scene as exp(-t / tau).
TEST(SimCameraErrors, AutoExposureFollowsABrightnessStepWithItsTimeConstant) {
  AutoExposureConfig c;
  c.tau_s = 0.3;
  c.frame_period_s = 0.05;
  AutoExposure ae(c);
  const cv::Mat bright(40, 60, CV_8UC1, cv::Scalar(100)), dark(40, 60, CV_8UC1, cv::Scalar(50));
  for (int k = 0; k < 5; ++k) {
    const cv::Mat out = ae.apply(bright);
    EXPECT_NEAR(cv::mean(out)[0], c.target_mean, 0.5) << "settled before the step, frame " << k;
    EXPECT_NEAR(ae.gain(), c.target_mean / 100.0, 1e-3);
  }
  const double g_before = ae.gain(), g_after = c.target_mean / 50.0;
  const cv::Mat first = ae.apply(dark);
  EXPECT_NEAR(cv::mean(first)[0], 50 * g_before, 0.5);  // the step shows in the frame: 59 instead of 118
  EXPECT_LT(cv::mean(first)[0], 0.6 * c.target_mean);
  double mean_at_tau = 0;
  for (int k = 1; k <= 40; ++k) {
    const cv::Mat out = ae.apply(dark);
    // log(g / g*) decays by exp(-frame_period / tau) per frame; the rounding of the 8-bit output adds up to 0.5 / 50.
    const double expected = std::log(g_before / g_after) * std::exp(-k * c.frame_period_s / c.tau_s);
    EXPECT_NEAR(std::log(ae.gain() / g_after), expected, 0.012) << "frame " << k;
    if (k == 6) mean_at_tau = cv::mean(out)[0];  // t = tau after the step
  }
  // After one time constant 1 - 1/e of the log-brightness error is gone.
  const double left = std::log(c.target_mean / mean_at_tau) / std::log(c.target_mean / (50 * g_before));
  std::printf("auto-exposure step 100 -> 50: frame after the step %.1f, after tau %.1f (error left %.3f, "
              "e^-1 = %.3f)\n",
              cv::mean(first)[0], mean_at_tau, left, std::exp(-1.0));
  EXPECT_NEAR(left, std::exp(-1.0), 0.03);
  EXPECT_NEAR(cv::mean(ae.apply(dark))[0], c.target_mean, 1.0);  // converged after 2 s

  // Clipping: a frame with sky at 240 and a dark facade at 20 metered to 118 saturates the sky at 255.
  AutoExposure clip(c);
  cv::Mat scene(40, 60, CV_8UC1, cv::Scalar(20));
  scene.rowRange(0, 10).setTo(240);
  for (int k = 0; k < 60; ++k) clip.apply(scene);
  const cv::Mat out = clip.apply(scene);
  EXPECT_EQ(out.at<std::uint8_t>(0, 0), 255);
  EXPECT_NEAR(cv::mean(out)[0], c.target_mean, 3.0);

  // tau 0: the rendered frame itself.
  c.tau_s = 0;
  AutoExposure off(c);
  const cv::Mat same = off.apply(dark);
  EXPECT_EQ(same.data, dark.data);
  EXPECT_EQ(off.gain(), 1.0);
}

// One small simulated dataset (the tiny city, 10 s, 2 frames per second, features and images).
struct SmallRun {
  Scenario scenario;
  fs::path dir;
};

struct CameraErrors {
  double time_offset_s = 0, deg = 0, m = 0, tau_s = 0, focal = 0, px = 0, k1 = 0;
};

SmallRun simulate_small(const std::string& name, const CameraErrors& e) {
  SmallRun r{builtin_scenario("tiny"), fs::temp_directory_path() /
                                           ("twinslam_camera_errors_" + std::to_string(::getpid()) + "_" + name)};
  r.scenario.trajectory.duration_s = 10;
  r.scenario.camera.rate_hz = 2;
  r.scenario.gnss.model = "gaussian";
  r.scenario.camera.time_offset_s = e.time_offset_s;
  r.scenario.camera.extrinsic_error_deg = e.deg;
  r.scenario.camera.extrinsic_error_m = e.m;
  r.scenario.camera.auto_exposure_tau_s = e.tau_s;
  r.scenario.camera.intrinsic_error_focal = e.focal;
  r.scenario.camera.intrinsic_error_px = e.px;
  r.scenario.camera.intrinsic_error_k1 = e.k1;
  fs::remove_all(r.dir);
  SimOptions o;
  o.out = r.dir;
  o.features = true;
  o.feature_config.landmarks = 4000;
  o.progress = false;
  simulate(r.scenario, o);
  return r;
}

struct TrackRow {
  std::int64_t stamp;
  std::size_t id;
  Eigen::Vector2d uv;
};

std::vector<TrackRow> read_tracks(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  std::vector<TrackRow> rows;
  while (std::getline(in, line)) {
    TrackRow r{};
    long long stamp = 0;
    double u = 0, v = 0;
    if (std::sscanf(line.c_str(), "%lld,%zu,%lf,%lf", &stamp, &r.id, &u, &v) != 4) continue;
    r.stamp = stamp;
    r.uv = Eigen::Vector2d(u, v);
    rows.push_back(r);
  }
  return rows;
}

class SimCameraDataset : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // The camera's imperfections at sizes a test resolves: 50 ms is 15 cm of flight at 3 m/s; 1 % of the focal
    // length is 3 px at the image's edge.
    imperfect_ = new SmallRun(simulate_small("imperfect", {0.05, 2.0, 0.05, 0.3, 0.01, 3.0, 0.01}));
    ideal_ = new SmallRun(simulate_small("ideal", {}));
  }
  static void TearDownTestSuite() {
    for (SmallRun* r : {imperfect_, ideal_}) {
      fs::remove_all(r->dir);
      delete r;
    }
  }
  static SmallRun* imperfect_;
  static SmallRun* ideal_;
};
SmallRun* SimCameraDataset::imperfect_ = nullptr;
SmallRun* SimCameraDataset::ideal_ = nullptr;

// Pixel error of the dataset's ideal tracks against the projection of each landmark from the camera at stamp -
// shift_s with extrinsics T_BC and the given intrinsics (default: the true ones): the median over every row (within
// centre_radius_px of the image centre, if given).
double track_error_px(const SmallRun& r, double shift_s, const Eigen::Isometry3d& T_BC,
                      const std::optional<CameraIntrinsics>& intrinsics = std::nullopt,
                      double centre_radius_px = 1e9) {
  const City city = build_city(r.scenario.city, r.scenario.seed);
  const FlightTrajectory flight = make_flight_trajectory(r.scenario, city.hints);
  std::vector<Eigen::Vector3d> landmarks;
  for (const auto& s : sample_surface(city.mesh, 4000, r.scenario.seed)) landmarks.push_back(s.p_W);
  const auto camera = make_camera(intrinsics.value_or(sim_camera_config(r.scenario).intrinsics));
  std::vector<double> errors;
  const CameraIntrinsics truth = sim_camera_config(r.scenario).intrinsics;
  for (const TrackRow& row : read_tracks(r.dir / "mav0/cam0/features.csv")) {
    if ((row.uv - Eigen::Vector2d(truth.cu, truth.cv)).norm() > centre_radius_px) continue;
    const Eigen::Isometry3d T_WC = flight.at(time_s(row.stamp) - shift_s).T_WB() * T_BC;
    Eigen::Vector2d uv;
    if (camera->project(T_WC.inverse() * landmarks.at(row.id), &uv) != ProjectionStatus::kOk) {
      errors.push_back(1e9);
      continue;
    }
    errors.push_back((uv - row.uv).norm());
  }
  EXPECT_GT(errors.size(), centre_radius_px < 1e9 ? 10u : 200u);
  std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
  return errors[errors.size() / 2];
}

TEST_F(SimCameraDataset, TracksAtStampTShowThePoseAtTMinusTheOffsetAndTheTrueExtrinsics) {
  const Scenario& s = imperfect_->scenario;
  const double at_offset = track_error_px(*imperfect_, s.camera.time_offset_s, camera_T_BC(s));
  const double at_stamp = track_error_px(*imperfect_, 0, camera_T_BC(s));
  const double stated = track_error_px(*imperfect_, s.camera.time_offset_s, calibrated_T_BC(s));
  std::printf("tracks (offset 50 ms, extrinsic error 2 deg / 5 cm), median px error against the pose at t - offset: "
              "%.5f, at t: %.2f; with the stated T_BC: %.2f\n", at_offset, at_stamp, stated);
  EXPECT_LT(at_offset, 1e-3);  // the file's 4 decimals
  EXPECT_GT(at_stamp, 0.3);
  EXPECT_GT(stated, 3.0);
  // The stated intrinsics (focal 1 %, principal point 3 px, k1 0.01 off) with the true pose and extrinsics: the
  // tracks are the true camera's, so the calibration's own error shows - near the image centre as the principal
  // point's shift (the focal and k1 errors grow with the distance from it: 0.2 px at 20 px).
  const CameraIntrinsics stated_k = calibrated_sim_camera_config(s).intrinsics;
  const double everywhere = track_error_px(*imperfect_, s.camera.time_offset_s, camera_T_BC(s), stated_k);
  const double centre = track_error_px(*imperfect_, s.camera.time_offset_s, camera_T_BC(s), stated_k, 20.0);
  std::printf("tracks against the stated intrinsics (focal 1 %%, 3 px, k1 0.01): median %.2f px, %.2f px within 20 px "
              "of the centre\n", everywhere, centre);
  EXPECT_GT(everywhere, 1.0);
  EXPECT_NEAR(centre, 3.0, 0.3);
  // Offset 0: the pose at the stamp.
  EXPECT_LT(track_error_px(*ideal_, 0, camera_T_BC(ideal_->scenario)), 1e-3);
}

TEST_F(SimCameraDataset, SensorYamlStatesTheCalibratedExtrinsicsGroundTruthStaysOnTheImuClock) {
  const CameraConfig stated = read_camera_sensor_yaml(imperfect_->dir / "mav0/cam0/sensor.yaml");
  const Eigen::Isometry3d T_true = camera_T_BC(imperfect_->scenario);
  EXPECT_NEAR(angle_deg(stated.T_BC.linear(), T_true.linear()), 2.0, 1e-9);
  EXPECT_NEAR((stated.T_BC.translation() - T_true.translation()).norm(), 0.05, 1e-12);
  EXPECT_TRUE(stated.T_BC.isApprox(calibrated_T_BC(imperfect_->scenario), 1e-15));
  const CameraIntrinsics want = calibrated_sim_camera_config(imperfect_->scenario).intrinsics;
  EXPECT_NEAR(stated.intrinsics.fu, want.fu, 1e-9);
  EXPECT_NEAR(stated.intrinsics.fv, want.fv, 1e-9);
  EXPECT_NEAR(stated.intrinsics.cu, want.cu, 1e-9);
  EXPECT_NEAR(stated.intrinsics.cv, want.cv, 1e-9);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(stated.intrinsics.coefficients[i], want.coefficients[i], 1e-12);
  EXPECT_NEAR(std::abs(stated.intrinsics.fu / sim_camera_config(imperfect_->scenario).intrinsics.fu - 1), 0.01, 1e-12);
  const CameraConfig ideal = read_camera_sensor_yaml(ideal_->dir / "mav0/cam0/sensor.yaml");
  EXPECT_EQ(ideal.T_BC.matrix(), camera_T_BC(ideal_->scenario).matrix());
  const CameraIntrinsics truth = sim_camera_config(ideal_->scenario).intrinsics;
  EXPECT_TRUE(ideal.intrinsics.fu == truth.fu && ideal.intrinsics.cu == truth.cu && ideal.intrinsics.cv == truth.cv &&
              ideal.intrinsics.coefficients == truth.coefficients);
  // The camera's errors leave the IMU, the ground truth and the frame stamps alone.
  for (const char* f : {"mav0/imu0/data.csv", "groundtruth.tum", "mav0/state_groundtruth_estimate0/data.csv",
                        "mav0/cam0/data.csv"})
    EXPECT_EQ(slurp(imperfect_->dir / f), slurp(ideal_->dir / f)) << f;
  // dataset.yaml records the truth for evaluation.
  const std::string yaml = slurp(imperfect_->dir / "dataset.yaml");
  EXPECT_NE(yaml.find("camera_time_offset_s: 0.05"), std::string::npos);
  EXPECT_NE(yaml.find("T_BC_calibrated: ["), std::string::npos);
  EXPECT_TRUE(yaml.find("camera_focal_scale: 1.01") != std::string::npos ||
              yaml.find("camera_focal_scale: 0.99") != std::string::npos);
  EXPECT_NE(yaml.find("camera_principal_point_shift_px: ["), std::string::npos);
  EXPECT_TRUE(yaml.find("camera_k1_offset: 0.01") != std::string::npos ||
              yaml.find("camera_k1_offset: -0.01") != std::string::npos);
}

// The images: frame k is the render of the true camera at stamp - offset (bit for bit with auto-exposure off);
// auto-exposure changes each frame's brightness toward its target.
TEST_F(SimCameraDataset, ImagesAreExposedAtStampMinusOffsetWithTheTrueExtrinsics) {
  for (SmallRun* r : {imperfect_, ideal_}) {
    const Scenario& s = r->scenario;
    const City city = build_city(s.city, s.seed);
    const FlightTrajectory flight = make_flight_trajectory(s, city.hints);
    const auto camera = make_camera(sim_camera_config(s).intrinsics);
    const Renderer renderer(city.mesh);
    const auto stamps = sample_stamps(s.camera.rate_hz, flight.duration());
    ASSERT_EQ(stamps.size(), 21u);
    AutoExposure exposure(auto_exposure_config(s));
    int brighter = 0, darker = 0;
    for (std::size_t k = 0; k < stamps.size(); ++k) {
      const cv::Mat image =
          cv::imread((r->dir / "mav0/cam0/data" / (std::to_string(stamps[k]) + ".png")).string(), cv::IMREAD_UNCHANGED);
      ASSERT_FALSE(image.empty());
      const std::uint64_t seed = s.seed * 1000003ULL + k;
      const double t = time_s(stamps[k]);
      const cv::Mat rendered =
          renderer.render(flight.at(t - s.camera.time_offset_s).T_WB() * camera_T_BC(s), *camera, seed);
      EXPECT_EQ(cv::norm(exposure.apply(rendered), image, cv::NORM_INF), 0) << "frame " << k;
      if (s.camera.auto_exposure_tau_s > 0) {
        const double delta = cv::mean(image)[0] - cv::mean(rendered)[0];
        brighter += delta > 2;
        darker += delta < -2;
      } else {
        EXPECT_EQ(cv::norm(rendered, image, cv::NORM_INF), 0) << "frame " << k;
      }
      if (s.camera.time_offset_s > 0 && k >= 2 && k <= 17) {  // in flight (it ends at rest)
        const cv::Mat at_stamp = renderer.render(flight.at(t).T_WB() * camera_T_BC(s), *camera, seed);
        EXPECT_GT(cv::norm(rendered, at_stamp, cv::NORM_L1) / rendered.total(), 1.0) << "frame " << k;
      }
    }
    if (s.camera.auto_exposure_tau_s > 0) {
      std::printf("auto-exposure: %d of 21 frames brighter, %d darker than rendered\n", brighter, darker);
      EXPECT_GT(brighter + darker, 10);
    }
  }
}

}  // namespace
}  // namespace twinslam::sim

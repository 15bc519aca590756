// Imperfect camera (issue 13, item 6): a rolling shutter puts each row at its own time (image and ideal tracks agree
// with the line time x rate geometry), an exposure blurs an edge by the pixel motion during it, every imperfection at
// 0 gives the ideal image and tracks bit for bit, and the scenario keys parse, validate and echo.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "corner_measure.hpp"
#include "frame_tracks.hpp"
#include "sim_world_test_utils.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/sim/feature_tracks.hpp"
#include "twinslam/sim/scenario_io.hpp"
#include "twinslam/sim/world/renderer.hpp"
#include "twinslam/sim/world/traffic.hpp"

namespace twinslam::sim {
namespace {

using testing::look_at;
using testing::tracks_of;
using testing::measured_corner;
using testing::pinhole_90;

// One box against the sky (as in test_render): its front face y = 25 and the top-left silhouette corner (-4, 25, 8).
TriMesh single_box() {
  TriMesh m;
  add_box(&m, {-4, 25, -3}, {6, 35, 8}, SurfaceKind::kFacade, SurfaceKind::kRoof, 0, true);
  return m;
}
const Eigen::Vector3d kCorner_W(-4, 25, 8);

// A camera at a fixed place turning about the vertical (yaw) at rate_radps: T_WC(t) = Rz(rate t) T0.
FrameCapture yawing(const Eigen::Isometry3d& T0, double rate_radps, Shutter shutter, double t_s = 0) {
  FrameCapture f;
  f.t_s = t_s;
  f.shutter = shutter;
  f.T_WC = [T0, rate_radps](double t) {
    Eigen::Isometry3d T = T0;
    T.linear() = Eigen::AngleAxisd(rate_radps * t, Eigen::Vector3d::UnitZ()).toRotationMatrix() * T0.linear();
    return T;
  };
  return f;
}

// Where a rolling-shutter camera images p_W: the pixel at the time of its own row (fixed point on the row, with the
// exact pose, no interpolation).
Eigen::Vector2d rolling_projection(const FrameCapture& f, const CameraModel& cam, const Eigen::Vector3d& p_W,
                                   double* row_time = nullptr) {
  double v = 0.5 * (cam.height() - 1), t = f.t_s;
  Eigen::Vector2d uv;
  for (int it = 0; it < 50; ++it) {
    t = f.t_s + f.shutter.row_offset_s(v, cam.height());
    EXPECT_EQ(cam.project(f.T_WC(t).inverse() * p_W, &uv), ProjectionStatus::kOk);
    if (std::abs(uv.y() - v) < 1e-9) break;
    v = uv.y();
  }
  if (row_time) *row_time = t;
  return uv;
}


// A camera 120 rows above whose middle row the corner appears, rolled so the edges slant (see test_render).
Eigen::Isometry3d corner_view() {
  return look_at({0.5, 0, 0.5}, {2, 25, -1}) * Eigen::AngleAxisd(12 * M_PI / 180, Eigen::Vector3d::UnitZ());
}

TEST(SimImperfectCamera, RollingShutterShiftsTheCornerByLineTimeTimesRate) {
  const auto cam = pinhole_90();
  RenderConfig cfg;
  cfg.noise_sigma = 0;
  const Renderer r(single_box(), cfg);
  const double rate = 2.0, line_time = 100e-6;  // [rad/s], [s]: 120 rows = 12 ms = 24 mrad = about 8 px
  const FrameCapture global = yawing(corner_view(), rate, {});
  const FrameCapture rolling = yawing(corner_view(), rate, {line_time, 0});

  Eigen::Vector2d gs;
  ASSERT_EQ(cam->project(corner_view().inverse() * kCorner_W, &gs), ProjectionStatus::kOk);
  ASSERT_LT(gs.y(), 110);  // well above the middle row (199.5)
  ASSERT_TRUE(cam->in_image(gs, 40));
  double t_row = 0;
  const Eigen::Vector2d rs = rolling_projection(rolling, *cam, kCorner_W, &t_row);
  // The geometry: the corner's row is read (v - 199.5) x line_time before the stamp, and in that time the camera has
  // turned by rate x that; to first order the pixel moves by its image velocity times the time.
  const double dt = (rs.y() - 199.5) * line_time;
  EXPECT_NEAR(t_row, dt, 1e-12);
  Eigen::Vector2d ahead, behind;
  cam->project(global.T_WC(1e-4).inverse() * kCorner_W, &ahead);
  cam->project(global.T_WC(-1e-4).inverse() * kCorner_W, &behind);
  const Eigen::Vector2d velocity = (ahead - behind) / 2e-4;  // [px/s]
  const Eigen::Vector2d predicted = velocity * dt;
  EXPECT_GT(predicted.norm(), 6.0);
  EXPECT_LT((rs - gs - predicted).norm(), 0.05 * predicted.norm()) << (rs - gs).transpose() << " vs "
                                                                       << predicted.transpose();

  // In the image: the measured corner moves from the global-shutter corner by the same offset.
  const cv::Mat gs_image = r.render(global, *cam, 3), rs_image = r.render(rolling, *cam, 3);
  EXPECT_EQ(cv::norm(gs_image, r.render(corner_view(), *cam, 3), cv::NORM_INF), 0.0);
  const Eigen::Vector2d gs_measured = measured_corner(gs_image, gs), rs_measured = measured_corner(rs_image, rs);
  EXPECT_LT((gs_measured - gs).norm(), 0.3);
  EXPECT_LT((rs_measured - rs).norm(), 0.3) << "measured " << rs_measured.transpose() << " predicted "
                                            << rs.transpose();
  EXPECT_LT(((rs_measured - gs_measured) - predicted).norm(), 0.5);
  ::testing::Test::RecordProperty("rs_offset_px", std::to_string((rs_measured - gs_measured).norm()));
  ::testing::Test::RecordProperty("rs_offset_predicted_px", std::to_string(predicted.norm()));
  ::testing::Test::RecordProperty("rs_offset_error_px",
                                  std::to_string(((rs_measured - gs_measured) - predicted).norm()));

  // In the ideal tracks: the corner as a landmark is at its rolling-shutter pixel.
  const auto g = tracks_of({kCorner_W}, global, *cam, r), s = tracks_of({kCorner_W}, rolling, *cam, r);
  ASSERT_EQ(g.count(0), 1u);
  ASSERT_EQ(s.count(0), 1u);
  EXPECT_LT((g.at(0) - gs).norm(), 1e-3);
  EXPECT_LT((s.at(0) - rs).norm(), 2e-3) << s.at(0).transpose() << " vs " << rs.transpose();
}

// A dark far wall with a slanted left edge against the sky: so far that its texture has faded to its mean (one flat
// grey), the edge slanted so its position against the pixel grid changes from row to row.
TriMesh far_wall() {
  TriMesh m;
  m.add_quad({0, 600, -300}, {2000, 600, -300}, {2000, 600, 300}, {30, 600, 300}, SurfaceKind::kFacade, 0);
  return m;
}

// Edge width along the rows: 6 x the sum of f (1 - f) over the row, f the fraction of the way from sky to wall (a
// linear ramp of width M gives M; a step gives 0), averaged over the rows.
double edge_width(const cv::Mat& image, const CameraModel& cam) {
  double total = 0;
  int rows = 0;
  for (int v = 120; v < 280; ++v) {
    // The edge in this row: the first pixel darker than halfway between the sky (left) and the wall (right).
    int u_edge = -1;
    for (int u = 1; u < cam.width(); ++u)
      if (image.at<std::uint8_t>(v, u) < 0.5 * (image.at<std::uint8_t>(v, 5) + image.at<std::uint8_t>(v, 620))) {
        u_edge = u;
        break;
      }
    if (u_edge < 30 || u_edge > cam.width() - 30) continue;
    const double sky = image.at<std::uint8_t>(v, u_edge - 20), wall = image.at<std::uint8_t>(v, u_edge + 20);
    double sum = 0;
    for (int u = u_edge - 15; u <= u_edge + 15; ++u) {
      const double f = std::clamp((sky - image.at<std::uint8_t>(v, u)) / (sky - wall), 0.0, 1.0);
      sum += f * (1 - f);
    }
    total += 6 * sum;
    ++rows;
  }
  EXPECT_GT(rows, 100);
  return rows ? total / rows : 0;
}

TEST(SimImperfectCamera, BlurWidensASharpEdgeByThePixelMotion) {
  const auto cam = pinhole_90();
  RenderConfig cfg;
  cfg.noise_sigma = 0;
  const Renderer r(far_wall(), cfg);
  const Eigen::Isometry3d T0 = look_at({0, 0, 0}, {0, 600, 0});
  const double rate = 2.0, exposure = 0.01;  // 20 mrad during the exposure: about 6.4 px
  // The expected blur: how far the edge's middle moves in the image during the exposure.
  const FrameCapture sharp = yawing(T0, rate, {}), blurred = yawing(T0, rate, {0, exposure});
  const Eigen::Vector3d edge_W(15, 600, 0);
  Eigen::Vector2d start, end;
  cam->project(sharp.T_WC(-exposure / 2).inverse() * edge_W, &start);
  cam->project(sharp.T_WC(exposure / 2).inverse() * edge_W, &end);
  const double motion = (end - start).norm();
  EXPECT_NEAR(motion, 320 * rate * exposure, 0.3);

  RenderInfo info;
  const cv::Mat a = r.render(sharp, *cam, 1), b = r.render(blurred, *cam, 1, &info);
  // The renderer's probes find the largest motion in the frame: at the image's sides, 1 + x^2 times the centre's.
  EXPECT_GT(info.motion_px, 1.5 * motion);
  EXPECT_LT(info.motion_px, 2 * motion);
  EXPECT_EQ(info.subexposures, 8);  // ceil(motion / 0.5 px), at most 8
  const double width_sharp = edge_width(a, *cam), width_blurred = edge_width(b, *cam);
  // K sub-exposures make a staircase of K levels, whose f (1 - f) sums to M (1 - 1/K^2).
  const double expected = motion * (1 - 1.0 / (info.subexposures * info.subexposures));
  ::testing::Test::RecordProperty("edge_width_px", std::to_string(width_blurred));
  ::testing::Test::RecordProperty("edge_width_expected_px", std::to_string(expected));
  EXPECT_LT(width_sharp, 0.3);
  EXPECT_NEAR(width_blurred, expected, 0.1 * expected) << "motion " << motion << " px";

  // A short exposure (pixel motion below 0.5 px everywhere) costs nothing: one pass, the sharp image.
  RenderInfo short_info;
  const cv::Mat c = r.render(yawing(T0, rate, {0, 0.0004}), *cam, 1, &short_info);
  EXPECT_LT(short_info.motion_px, 0.5);
  EXPECT_GT(short_info.motion_px, 0.3);
  EXPECT_EQ(short_info.subexposures, 1);
  EXPECT_EQ(cv::norm(a, c, cv::NORM_INF), 0.0);
}

// Every imperfection at 0 gives today's image and tracks, bit for bit; so does a still camera with a rolling shutter
// and an exposure; and the result does not depend on the thread count with everything on.
TEST(SimImperfectCamera, ImperfectionsOffReproduceTheIdealOutput) {
  const auto cam = pinhole_90();
  const Renderer r(single_box());
  RenderConfig one;
  one.threads = 1;
  const Renderer r1(single_box(), one);
  const Eigen::Isometry3d T0 = corner_view();
  const cv::Mat ideal = r.render(T0, *cam, 9);
  SceneHints no_streets;
  const Traffic no_cars(no_streets, TrafficSimConfig{}, 10, 7);  // no street grid: no cars
  EXPECT_TRUE(no_cars.empty());
  FrameCapture off = yawing(T0, 2.0, {});
  off.traffic = &no_cars;
  EXPECT_EQ(cv::norm(ideal, r.render(off, *cam, 9), cv::NORM_INF), 0.0);
  FrameCapture still = yawing(T0, 0.0, {30e-6, 0.005});
  EXPECT_EQ(cv::norm(ideal, r.render(still, *cam, 9), cv::NORM_INF), 0.0);
  const FrameCapture on = yawing(T0, 2.0, {30e-6, 0.005});
  const cv::Mat moving = r.render(on, *cam, 9);
  EXPECT_GT(cv::norm(ideal, moving, cv::NORM_INF), 50.0);
  EXPECT_EQ(cv::norm(moving, r1.render(on, *cam, 9), cv::NORM_INF), 0.0);

  std::vector<Eigen::Vector3d> landmarks;
  for (double x = -3.5; x < 6; x += 0.5)
    for (double z = -2.5; z < 8; z += 0.5) landmarks.emplace_back(x, 25, z);
  std::string b;
  const auto file = std::filesystem::temp_directory_path() / ("twinslam_ideal_" + std::to_string(::getpid()) + ".csv");
  {
    FeatureTrackWriter writer(file, landmarks, {}, 5);
    writer.add_frame(1000, T0, *cam, r);
  }
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  std::filesystem::remove(file);
  tracks_of(landmarks, off, *cam, r, &b);
  EXPECT_EQ(text.str(), b);
  EXPECT_GT(std::count(b.begin(), b.end(), '\n'), 100);
}

std::string error_of(const std::string& yaml) {
  try {
    parse_scenario_yaml(yaml, "s.yaml", Scenario{});
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SimImperfectCamera, ScenarioKeysParseValidateAndEcho) {
  const Scenario s = parse_scenario_yaml(
      "camera: {line_time_us: 20, exposure_ms: 3}\ntraffic: {cars: 12, speed_mps: 6.5}\n", "s.yaml", Scenario{});
  EXPECT_EQ(s.camera.line_time_us, 20);
  EXPECT_EQ(s.camera.exposure_ms, 3);
  EXPECT_EQ(s.traffic.cars, 12);
  EXPECT_EQ(s.traffic.speed_mps, 6.5);
  const Scenario back = parse_scenario_yaml(scenario_to_yaml(s), "echo.yaml", Scenario{});
  EXPECT_EQ(back.camera.line_time_us, 20);
  EXPECT_EQ(back.camera.exposure_ms, 3);
  EXPECT_EQ(back.traffic.cars, 12);
  EXPECT_EQ(back.traffic.speed_mps, 6.5);
  for (const std::string key : {"camera.line_time_us", "camera.exposure_ms", "traffic.speed_mps"}) {
    const std::string section = key.substr(0, key.find('.')), name = key.substr(key.find('.') + 1);
    for (const std::string bad : {"-1", "nan", ".nan"})
      EXPECT_NE(error_of(section + ": {" + name + ": " + bad + "}\n").find(key), std::string::npos) << key << bad;
  }
  EXPECT_NE(error_of("traffic: {cars: -3}\n").find("traffic.cars"), std::string::npos);
  EXPECT_NE(error_of("traffic: {cars: 2.5}\n").find("traffic.cars"), std::string::npos);
  EXPECT_NE(error_of("traffic: {lorries: 2}\n").find("traffic.lorries"), std::string::npos);
  // A readout or an exposure longer than the frame period (20 Hz: 50 ms; 400 rows).
  EXPECT_NE(error_of("camera: {line_time_us: 200}\n").find("camera.line_time_us"), std::string::npos);
  EXPECT_NE(error_of("camera: {exposure_ms: 60}\n").find("camera.exposure_ms"), std::string::npos);
  // Off in tiny, realistic elsewhere.
  const Scenario tiny = builtin_scenario("tiny");
  EXPECT_EQ(tiny.camera.line_time_us, 0);
  EXPECT_EQ(tiny.camera.exposure_ms, 0);
  EXPECT_EQ(tiny.traffic.cars, 0);
  for (const std::string name : {"city-loops", "city-survey", "city-long"}) {
    const Scenario c = builtin_scenario(name);
    EXPECT_GT(c.camera.line_time_us, 0) << name;
    EXPECT_GT(c.camera.exposure_ms, 0) << name;
    EXPECT_GT(c.traffic.cars, 0) << name;
    EXPECT_GT(c.traffic.speed_mps, 0) << name;
  }
}

}  // namespace
}  // namespace twinslam::sim

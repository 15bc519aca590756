// Measures the tracking frontend on rendered city-loops images against the simulator's truth (the issue 6
// acceptance figures): each track's first pixel is cast into the world to its true 3D point, which is projected
// into every later frame; a tracked pixel more than 2 px from that projection is a wrong track.
// Usage: bench_tracking_sim [t0_s] [frames]; NOISE=<grey levels> sets the sensor noise (default 2).
// Not a test: it prints the figures.
#include <algorithm>
#include <cstdlib>
#include <cstdio>
#include <map>

#include "twinslam/sim/flight_trajectory.hpp"
#include "twinslam/sim/scenario_io.hpp"
#include "twinslam/sim/sim_camera.hpp"
#include "twinslam/sim/world/city.hpp"
#include "twinslam/sim/world/renderer.hpp"
#include "twinslam/tracking/frontend.hpp"

using namespace twinslam;


int main(int argc, char** argv) {
  const sim::Scenario scenario = sim::builtin_scenario("city-loops");
  const sim::City city = sim::build_city(scenario.city, scenario.seed);
  const sim::FlightTrajectory flight = sim::make_flight_trajectory(scenario, city.hints);
  const CameraConfig cam_cfg = sim::sim_camera_config(scenario);
  const std::shared_ptr<const CameraModel> camera(make_camera(cam_cfg.intrinsics));
  sim::RenderConfig rcfg;
  if (const char* n = std::getenv("NOISE")) rcfg.noise_sigma = std::atof(n);
  const sim::Renderer renderer(city.mesh, rcfg);
  tracking::Frontend frontend(camera);

  struct Track {
    Eigen::Vector3d p_W;
    bool has_truth = false;
  };
  std::map<std::uint64_t, Track> truth;
  std::vector<std::size_t> per_frame;
  std::vector<std::uint32_t> lengths;
  std::size_t checked = 0, wrong = 0;
  const double t0 = argc > 1 ? std::atof(argv[1]) : 60.0, dt = 1.0 / scenario.camera.rate_hz;
  const int frames = argc > 2 ? std::atoi(argv[2]) : 80;
  Eigen::Isometry3d T_WC_prev = Eigen::Isometry3d::Identity();
  for (int k = 0; k < frames; ++k) {
    const double t = t0 + k * dt;
    const Eigen::Isometry3d T_WC = flight.at(t).T_WB() * cam_cfg.T_BC;
    const cv::Mat image = renderer.render(T_WC, *camera, 1000 + k);
    // The gyro's rotation since the previous frame, here exact (the frontend's prediction input).
    const Eigen::Matrix3d R_prev_curr = T_WC_prev.linear().transpose() * T_WC.linear();
    const auto result = frontend.track(static_cast<std::int64_t>(t * 1e9), image, k > 0 ? &R_prev_curr : nullptr);
    T_WC_prev = T_WC;
    per_frame.push_back(result.features.size());
    for (const auto& f : result.features) {
      auto& tr = truth[f.id];
      if (f.track_length == 1) {
        const Eigen::Vector3d dir_W = T_WC.linear() * f.bearing_C;
        if (const auto range = renderer.raycast(T_WC.translation(), dir_W)) {
          tr.p_W = T_WC.translation() + *range * dir_W;
          tr.has_truth = true;
        }
        continue;
      }
      if (!tr.has_truth) continue;
      Eigen::Vector2d uv;
      if (camera->project(T_WC.inverse() * tr.p_W, &uv) != ProjectionStatus::kOk) continue;
      ++checked;
      if ((uv - f.uv).norm() > 2.0) ++wrong;
    }
    if (k >= frames / 2) {
      for (const auto& f : result.features) lengths.push_back(f.track_length);
    }
  }
  std::vector<std::size_t> sorted = per_frame;
  std::sort(sorted.begin(), sorted.end());
  std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
  const std::size_t median_features = sorted[sorted.size() / 2];
  const std::uint32_t median_length = lengths[lengths.size() / 2];
  const double wrong_pct = 100.0 * wrong / std::max<std::size_t>(1, checked);
  std::printf("city-loops t=%.0f..%.0f s: median %zu features/frame, %zu of %zu tracked observations wrong (%.3f %%), "
              "median track length %u frames\n",
              t0, t0 + frames * dt, median_features, wrong, checked, wrong_pct, median_length);
  std::printf("targets (issue 6): median >= 120 features/frame, < 1 %% wrong, median track length >= 10\n");
  return 0;
}

#include "twinslam/sim/simulate.hpp"

#include <cstdio>
#include <fstream>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "progress.hpp"
#include "twinslam/camera/sensor_yaml.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/sim/clock.hpp"
#include "twinslam/sim/dataset_writer.hpp"
#include "twinslam/sim/flight_surroundings.hpp"
#include "twinslam/sim/gnss_raytrace.hpp"
#include "twinslam/sim/scenario_io.hpp"
#include "twinslam/sim/sim_camera.hpp"
#include "twinslam/sim/world/city.hpp"
#include "twinslam/sim/world/ply.hpp"
#include "twinslam/sim/world/surface_distance.hpp"
#include "twinslam/sim/world/top_down.hpp"
#include "twinslam/sim/world/twin.hpp"

namespace twinslam::sim {
namespace fs = std::filesystem;

namespace {
void write_preview(const fs::path& dir, const Renderer& world, const FlightTrajectory& trajectory,
                   const std::vector<cv::Mat>& frames) {
  fs::create_directories(dir);
  const auto extent = world.scene().mesh();
  Eigen::Vector3d lo, hi;
  extent.bounds(&lo, &hi);
  // About 1000 px across, whatever the city size.
  const double mpp = std::max(0.25, std::max(hi.x() - lo.x(), hi.y() - lo.y()) / 1000.0);
  const TopDownImage map = render_top_down(world, mpp);
  cv::Mat bgr;
  cv::cvtColor(map.image, bgr, cv::COLOR_GRAY2BGR);
  std::vector<cv::Point> line;
  for (double t = 0; t <= trajectory.duration(); t += 0.2) {
    const Eigen::Vector3d p = trajectory.at(t).p_W;
    line.push_back(map.pixel(p.x(), p.y()));
  }
  cv::polylines(bgr, line, false, cv::Scalar(0, 0, 255), 2, cv::LINE_AA);
  if (!line.empty()) cv::circle(bgr, line.front(), 6, cv::Scalar(0, 200, 0), -1, cv::LINE_AA);
  cv::putText(bgr, "start", line.empty() ? cv::Point(10, 20) : line.front() + cv::Point(8, -8),
              cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(0, 200, 0), 2);
  cv::imwrite((dir / "top_down.png").string(), bgr);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    cv::imwrite((dir / ("frame_" + std::to_string(i) + ".png")).string(), frames[i]);
  }
}

// The GNSS model the scenario names: `raytrace` needs the world, so it is built here and handed to the sensor writer;
// `gaussian` is the writer's own; `learned` is refused rather than silently replaced.
// Refuses a model that does not exist yet, before anything is built or written.
void require_gnss_model(const Scenario& scenario) {
  if (scenario.gnss.model == "gaussian" || scenario.gnss.model == "raytrace") return;
  throw InputError("gnss.model: '" + scenario.gnss.model +
                   "' is not implemented yet (the learned model of issue 13); use 'raytrace' or 'gaussian'");
}

GnssModelFn gnss_model(const Scenario& scenario, const City& city, const fs::path& dir) {
  if (scenario.gnss.model == "gaussian") return {};
  return [&scenario, &city, dir](const FlightTrajectory& trajectory) {
    const std::vector<std::int64_t> stamps = sample_stamps(scenario.gnss.rate_hz, trajectory.duration());
    std::vector<Eigen::Vector3d> p_W;
    for (const std::int64_t s : stamps) p_W.push_back(trajectory.at(time_s(s)).p_W);
    const EmbreeScene world(city.mesh);
    RaytraceGnss g = simulate_gnss_raytrace(stamps, p_W, scenario.origin, world, scenario.seed);
    write_pseudoranges(dir, g.pseudoranges);
    return std::move(g.fixes);
  };
}
}  // namespace

SimSummary simulate(const Scenario& scenario, const SimOptions& options) {
  require_gnss_model(scenario);
  const auto wall0 = std::chrono::steady_clock::now();
  const fs::path dir = options.out;
  fs::create_directories(dir / "mav0/cam0/data");
  fs::create_directories(dir / "twin");
  SimSummary summary;

  // World (reality) and twin (what the map says), from the same seed.
  if (scenario.city.source != "procedural") {
    throw InputError("city.source: '" + scenario.city.source +
                     "' needs the twin-format loaders (not available yet); use 'procedural'");
  }
  // The twin's changes hit the buildings a streets flight passes, so the flight is planned first.
  const City city = build_city(scenario.city, scenario.seed);
  const std::vector<int> seen =
      twin_change_candidates(scenario, city.hints, make_flight_trajectory(scenario, city.hints));
  const Twin twin = derive_twin(city, scenario.twin, scenario.seed, seen);
  write_ply((dir / "twin/twin.ply").string(), twin.mesh, scenario.origin);
  summary.world_triangles = city.mesh.num_triangles();
  summary.twin_triangles = twin.mesh.num_triangles();

  // Trajectory, IMU, GNSS, ground truth, dataset.yaml.
  const TwinReference twin_ref{"twin/twin.ply", "ENU@origin", twin.missing_building_ids, twin.added_building_ids,
                               twin.shifted_building_ids, twin.shifted_building_offsets_W};
  const SensorData sensors = write_sensor_dataset(dir, scenario, city.hints, twin_ref, gnss_model(scenario, city, dir));
  summary.imu = sensors.imu.size();
  summary.gnss = sensors.gnss.size();
  summary.duration_s = sensors.trajectory.duration();

  // Camera: calibration file, then one rendered image per frame.
  const CameraConfig camera_cfg = sim_camera_config(scenario);
  write_camera_sensor_yaml(dir / "mav0/cam0/sensor.yaml", camera_cfg);
  const auto camera = make_camera(camera_cfg.intrinsics);
  RenderConfig render_cfg;
  render_cfg.threads = options.render_threads;
  const Renderer renderer(city.mesh, render_cfg);

  std::unique_ptr<FeatureTrackWriter> tracks;
  if (options.features) {
    std::vector<Eigen::Vector3d> landmarks;
    for (const auto& s : sample_surface(city.mesh, options.feature_config.landmarks, scenario.seed)) {
      landmarks.push_back(s.p_W);
    }
    tracks = std::make_unique<FeatureTrackWriter>(dir / "mav0/cam0/features.csv", std::move(landmarks),
                                                  options.feature_config, scenario.seed);
  }

  const auto stamps = sample_stamps(scenario.camera.rate_hz, sensors.trajectory.duration());
  std::ofstream index(dir / "mav0/cam0/data.csv");
  if (!index) throw InputError((dir / "mav0/cam0/data.csv").string() + ": cannot write");
  index << "#timestamp [ns],filename\n";
  Progress progress("rendering", stamps.size(), options.progress);
  std::vector<cv::Mat> preview_frames;
  const std::vector<int> png{cv::IMWRITE_PNG_COMPRESSION, 1};
  Eigen::Vector3d previous_p = sensors.trajectory.at(0).p_W;
  for (std::size_t k = 0; k < stamps.size(); ++k) {
    const double t = time_s(stamps[k]);
    const FlightState state = sensors.trajectory.at(t);
    summary.path_length_m += (state.p_W - previous_p).norm();
    previous_p = state.p_W;
    const Eigen::Isometry3d T_WC = state.T_WB() * camera_cfg.T_BC;
    if (tracks) summary.feature_rows += tracks->add_frame(stamps[k], T_WC, *camera, renderer);
    if (!options.images) {
      progress.update(k + 1);
      continue;
    }
    const cv::Mat image = renderer.render(T_WC, *camera, scenario.seed * 1000003ULL + k);
    const std::string name = std::to_string(stamps[k]) + ".png";
    if (!cv::imwrite((dir / "mav0/cam0/data" / name).string(), image, png)) {
      throw InputError((dir / "mav0/cam0/data" / name).string() + ": cannot write");
    }
    index << stamps[k] << ',' << name << '\n';
    if (options.preview && (k == stamps.size() / 4 || k == stamps.size() / 2 || k == 3 * stamps.size() / 4)) {
      preview_frames.push_back(image.clone());
    }
    progress.update(k + 1);
  }
  summary.frames = stamps.size();
  if (options.preview) write_preview(dir / "preview", renderer, sensors.trajectory, preview_frames);
  summary.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return summary;
}

}  // namespace twinslam::sim

#include "twinslam/sim/simulate.hpp"

#include <cstdio>
#include <fstream>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "twinslam/core/progress.hpp"
#include "twinslam/camera/sensor_yaml.hpp"
#include "twinslam/sim/auto_exposure.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/sim/clock.hpp"
#include "twinslam/sim/dataset_writer.hpp"
#include "twinslam/sim/flight_clearance.hpp"
#include "twinslam/sim/flight_surroundings.hpp"
#include "twinslam/sim/gnss_learned.hpp"
#include "twinslam/sim/gnss_raytrace.hpp"
#include "twinslam/sim/scenario_io.hpp"
#include "twinslam/sim/sim_camera.hpp"
#include "twinslam/sim/world/city.hpp"
#include "twinslam/sim/world/ply.hpp"
#include "twinslam/sim/world/real_city.hpp"
#include "twinslam/sim/world/surface_distance.hpp"
#include "twinslam/sim/world/top_down.hpp"
#include "twinslam/sim/world/traffic.hpp"
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

// The GNSS model the scenario names: `raytrace` and `learned` need the world, so they are built here and handed to
// the sensor writer; `gaussian` is the writer's own.
void require_gnss_model(const Scenario& scenario) {
  if (scenario.gnss.model == "gaussian" || scenario.gnss.model == "raytrace" || scenario.gnss.model == "learned") {
    return;
  }
  throw InputError("gnss.model: '" + scenario.gnss.model + "' is not a GNSS model; use raytrace, learned or gaussian");
}

GnssModelFn gnss_model(const Scenario& scenario, const City& city, const fs::path& dir) {
  if (scenario.gnss.model == "gaussian") return {};
  return [&scenario, &city, dir](const FlightTrajectory& trajectory) {
    const std::vector<std::int64_t> stamps = sample_stamps(scenario.gnss.rate_hz, trajectory.duration());
    std::vector<Eigen::Vector3d> p_W;
    for (const std::int64_t s : stamps) p_W.push_back(trajectory.at(time_s(s)).p_W);
    const EmbreeScene world(city.mesh);
    if (scenario.gnss.model == "learned") {
      return run_learned_gnss(dir, stamps, p_W, city.hints, scenario.origin, world, scenario.seed).fixes;
    }
    RaytraceGnss g = simulate_gnss_raytrace(stamps, p_W, scenario.origin, world, scenario.seed);
    write_pseudoranges(dir, g.pseudoranges);
    return std::move(g.fixes);
  };
}

// The twin's changes are drawn first among what the flight passes (within kSeenWithin_m), so it meets them. The draw
// of missing buildings shares its random stream with the faces' noise: it gets candidates only where it always had
// them (streets flights) or where a building is missing, so a twin without changes keeps its faces byte for byte.
TwinCandidates twin_candidates(const Scenario& scenario, const City& city, const FlightTrajectory& flight) {
  TwinCandidates c;
  c.shifted_ids = buildings_along_flight(flight, city.hints.buildings, kSeenWithin_m);
  if (scenario.trajectory.type == "streets" || scenario.twin.missing_buildings > 0) c.missing_ids = c.shifted_ids;
  c.lot_ids = lots_along_flight(flight, city.empty_lots_W, kSeenWithin_m);
  return c;
}

}  // namespace

SimSummary simulate(const Scenario& scenario, const SimOptions& options) {
  require_gnss_model(scenario);
  // A real city without `origin:` is placed at its model's centre at ground level; W and dataset.yaml follow.
  if (scenario.city.source != "procedural" && !scenario.origin_given) {
    Scenario placed = scenario;
    placed.origin = real_city_origin(scenario);
    placed.origin_given = true;
    return simulate(placed, options);
  }
  const auto wall0 = std::chrono::steady_clock::now();
  const fs::path dir = options.out;
  fs::create_directories(dir / "mav0/cam0/data");
  fs::create_directories(dir / "twin");
  SimSummary summary;

  // World (reality) and twin (what the map says), from the same seed: the procedural city or a real city model
  // (real_city.hpp). The twin's changes hit the buildings a streets flight passes, so the flight is planned first,
  // and it must keep clear of the world.
  const City city = build_world_city(scenario);
  const FlightTrajectory flight = make_flight_trajectory(scenario, city.hints);
  require_flight_clearance(scenario, city, flight);
  const Twin twin = derive_twin(city, scenario.twin, scenario.seed, twin_candidates(scenario, city, flight));
  write_ply((dir / "twin/twin.ply").string(), twin.mesh, scenario.origin);
  summary.world_triangles = city.mesh.num_triangles();
  summary.twin_triangles = twin.mesh.num_triangles();

  // Trajectory, IMU, GNSS, ground truth, dataset.yaml.
  TwinReference twin_ref{"twin/twin.ply", "ENU@origin", twin.missing_building_ids, twin.added_building_ids,
                         twin.shifted_building_ids, twin.shifted_building_offsets_W};
  for (const int id : twin.missing_building_ids) twin_ref.change_footprints.push_back({"missing", id, city.buildings[id].outline_W});
  for (const int id : twin.shifted_building_ids) twin_ref.change_footprints.push_back({"shifted", id, city.buildings[id].outline_W});
  for (std::size_t k = 0; k < twin.added_building_ids.size(); ++k) {
    twin_ref.change_footprints.push_back({"added", twin.added_building_ids[k], twin.added_outlines_W[k]});
  }
  const SensorData sensors = write_sensor_dataset(dir, scenario, city.hints, twin_ref, gnss_model(scenario, city, dir));
  summary.imu = sensors.imu.size();
  summary.gnss = sensors.gnss.size();
  summary.duration_s = sensors.trajectory.duration();

  // Camera: calibration file, then one rendered image per frame.
  const CameraConfig camera_cfg = sim_camera_config(scenario);  // the true camera: images and tracks
  // The calibration it states: camera.extrinsic_error_*, camera.intrinsic_error_*.
  write_camera_sensor_yaml(dir / "mav0/cam0/sensor.yaml", calibrated_sim_camera_config(scenario));
  const auto camera = make_camera(camera_cfg.intrinsics);
  RenderConfig render_cfg;
  render_cfg.threads = options.render_threads;
  const Renderer renderer(city.mesh, render_cfg);
  // traffic.*: cars on the street grid, in the images and the tracks only (not in city.mesh, so not in the twin or GNSS).
  const Traffic traffic(city.hints, scenario.traffic, sensors.trajectory.duration(), scenario.seed);

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
  AutoExposure exposure(auto_exposure_config(scenario));
  for (std::size_t k = 0; k < stamps.size(); ++k) {
    // camera.time_offset_s: the frame stamped stamps[k] was exposed at t on the IMU clock (the trajectory's time).
    const double t = time_s(stamps[k]) - scenario.camera.time_offset_s;
    const FlightState state = sensors.trajectory.at(t);
    summary.path_length_m += (state.p_W - previous_p).norm();
    previous_p = state.p_W;
    // The frame as the camera takes it: each row at its own time (camera.line_time_us), blurred over
    // camera.exposure_ms, with the cars where they are then.
    FrameCapture frame;
    frame.t_s = t;
    frame.T_WC = [&](double t_row) { return sensors.trajectory.at(t_row).T_WB() * camera_cfg.T_BC; };
    frame.shutter = {scenario.camera.line_time_us * 1e-6, scenario.camera.exposure_ms * 1e-3};
    frame.traffic = &traffic;
    if (tracks) summary.feature_rows += tracks->add_frame(stamps[k], frame, *camera, renderer);
    if (!options.images) {
      progress.update(k + 1);
      continue;
    }
    const cv::Mat image = exposure.apply(renderer.render(frame, *camera, scenario.seed * 1000003ULL + k));
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

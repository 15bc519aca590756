// twinslam-estimator: sliding-window visual-inertial estimator (features + IMU in, odometry and local maps out).
#include <cmath>
#include <sstream>

#include <spdlog/spdlog.h>

#include "estimator_config.hpp"
#include "estimator_node.hpp"
#include "twinslam/camera/sensor_yaml.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/dds/service_main.hpp"
#include "twinslam/estimator/sliding_window_config_yaml.hpp"

int main(int argc, char** argv) {
  namespace est = twinslam::estimator;
  CLI::App app{"twinslam estimator service: sliding-window visual-inertial estimator (features + IMU in, odometry and "
               "local maps out)"};
  twinslam::dds::ServiceOptions service;
  twinslam::dds::add_service_options(app, service);
  std::string camera_file, imu_file, config_file;
  int window = 0;
  app.add_option("--camera", camera_file, "Camera calibration (EuRoC cam0/sensor.yaml: T_BS and fu are used)")
      ->required();
  app.add_option("--imu", imu_file, "IMU noise (EuRoC imu0/sensor.yaml)")->required();
  app.add_option("--config", config_file, "Estimator config YAML (deploy/config/estimator.yaml lists every key)");
  app.add_option("--window", window, "Keyframes in the sliding window (default 8; wins over --config)");
  // Global inputs (paper Sec. III-C/D). Without these the estimator is plain VIO and only counts them.
  bool fuse_registrations = false, align_gnss = false, fuse_gnss = false, fuse_gnss_loose = false,
       await_registration = false;
  std::string origin, initial_pose, checkpoint;
  app.add_flag("--fuse-registrations", fuse_registrations, "Fuse accepted map registrations (eq. 7 through T_WL)");
  app.add_flag("--align-gnss", align_gnss, "Find the initial alignment T_WL from GNSS fixes (eq. 11; needs --origin)");
  app.add_flag("--fuse-gnss", fuse_gnss, "Fuse GNSS fixes as window terms through T_WL once aligned (needs --origin)");
  app.add_flag("--fuse-gnss-loose", fuse_gnss_loose,
               "GNSS fixes in a pose graph apart from the VIO, which it leaves untouched (needs --align-gnss)");
  app.add_option("--origin", origin, "W's origin LAT,LON,ALT (deg, deg, m): GNSS fixes are converted to W with it");
  app.add_option("--initial-pose", initial_pose, "\"E N U YAW_DEG\": body pose in W at the first estimate (no GNSS)");
  app.add_option("--checkpoint", checkpoint,
                 "State file: written every node.checkpoint_every_s once aligned, resumed from at start if fresh");
  app.add_flag("--await-registration", await_registration,
               "Lockstep: hold the next frame until the registration answering each LocalMap arrives");
  return twinslam::dds::service_main("estimator", app, service, argc, argv, [&] {
    est::EstimatorServiceConfig config;
    if (!config_file.empty()) {
      config = est::load_estimator_service_config(config_file);
      spdlog::info("config {}: {}", config_file, est::changed_from_defaults(config));
    }
    const twinslam::CameraConfig camera = twinslam::read_camera_sensor_yaml(camera_file);
    config.options.estimator.T_BC = camera.T_BC;
    config.options.estimator.focal_px = camera.intrinsics.fu;
    config.options.estimator.imu = est::load_imu_noise(imu_file);
    if (window > 0) config.options.estimator.window_keyframes = window;
    // Lockstep replay (--max): node.lockstep_max_solver_time_s replaces the wall-clock cap (see estimator_config.hpp).
    est::EstimatorNodeOptions options = config.for_replay(!service.realtime);
    options.fusion.fuse_registrations = options.fusion.fuse_registrations || fuse_registrations;
    options.fusion.align_from_gnss = options.fusion.align_from_gnss || align_gnss;
    options.fusion.fuse_gnss = options.fusion.fuse_gnss || fuse_gnss;
    options.fusion.fuse_gnss_loose = options.fusion.fuse_gnss_loose || fuse_gnss_loose;
    options.await_registration = await_registration && !service.realtime;
    if (!checkpoint.empty()) options.checkpoint_path = checkpoint;
    if (!origin.empty()) options.origin = twinslam::twin::parse_origin(origin);
    if ((options.fusion.align_from_gnss || options.fusion.fuse_gnss || options.fusion.fuse_gnss_loose) &&
        !options.origin) {
      throw twinslam::UsageError("--align-gnss, --fuse-gnss and --fuse-gnss-loose need --origin LAT,LON,ALT (W's origin)");
    }
    try {
      options.fusion.validate();  // flags and config together (e.g. --fuse-gnss-loose without --align-gnss)
    } catch (const twinslam::InputError& e) {
      throw twinslam::UsageError(e.what());
    }
    if (!initial_pose.empty()) {
      est::InitialPose p;
      std::istringstream in(initial_pose);
      if (!(in >> p.p_W.x() >> p.p_W.y() >> p.p_W.z() >> p.yaw_deg) || !p.p_W.allFinite() || !std::isfinite(p.yaw_deg)) {
        throw twinslam::UsageError("--initial-pose '" + initial_pose + "': expected \"E N U YAW_DEG\" (4 numbers)");
      }
      options.initial_pose = p;
    }
    est::validate_estimator_config(options.estimator, config_file.empty() ? "command line" : config_file);
    twinslam::dds::Node node(service.node);
    twinslam::dds::Counters counters;
    twinslam::dds::HeartbeatPublisher heartbeat(node, counters);
    est::EstimatorNode estimator(node, counters, options);
    if (options.await_registration && !estimator.wait_for_registration_link(options.registration_link_wait)) {
      spdlog::warn("no registration service matched within {} ms: frames will not wait for registrations until one is",
                   options.registration_link_wait.count());
    }
    return twinslam::dds::serve_until_shutdown(heartbeat, node);
  });
}

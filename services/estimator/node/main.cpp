// twinslam-estimator: sliding-window visual-inertial estimator (features + IMU in, odometry and local maps out).
#include "estimator_node.hpp"
#include "twinslam/camera/sensor_yaml.hpp"
#include "twinslam/dds/service_main.hpp"

int main(int argc, char** argv) {
  CLI::App app{"twinslam estimator service: sliding-window visual-inertial estimator (features + IMU in, odometry and "
               "local maps out)"};
  twinslam::dds::ServiceOptions service;
  twinslam::dds::add_service_options(app, service);
  std::string camera_file, imu_file;
  int window = 0;
  app.add_option("--camera", camera_file, "Camera calibration (EuRoC cam0/sensor.yaml: T_BS and fu are used)")
      ->required();
  app.add_option("--imu", imu_file, "IMU noise (EuRoC imu0/sensor.yaml)")->required();
  app.add_option("--window", window, "Keyframes in the sliding window (default 8)");
  return twinslam::dds::service_main("estimator", app, service, argc, argv, [&] {
    twinslam::estimator::EstimatorNodeOptions options;
    const twinslam::CameraConfig camera = twinslam::read_camera_sensor_yaml(camera_file);
    options.estimator.T_BC = camera.T_BC;
    options.estimator.focal_px = camera.intrinsics.fu;
    options.estimator.imu = twinslam::estimator::load_imu_noise(imu_file);
    if (window > 0) options.estimator.window_keyframes = window;
    // Lockstep replay (--max) promises repeatable trajectories (CONTRACTS.md: two runs within 1 mm); a wall-clock
    // solver cap would make the result depend on the machine's load, so there only the iteration count bounds it.
    if (!service.realtime) options.estimator.max_solver_time_s = 1.0;
    options.estimator.validate();
    twinslam::dds::Node node(service.node);
    twinslam::dds::Counters counters;
    twinslam::dds::HeartbeatPublisher heartbeat(node, counters);
    twinslam::estimator::EstimatorNode estimator(node, counters, options);
    return twinslam::dds::serve_until_shutdown(heartbeat, node);
  });
}

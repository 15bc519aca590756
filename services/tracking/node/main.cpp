// twinslam-tracking: visual frontend service (images + IMU -> FeatureFrame).
#include <memory>

#include <spdlog/spdlog.h>

#include "tracking_config.hpp"
#include "tracking_node.hpp"
#include "twinslam/camera/sensor_yaml.hpp"
#include "twinslam/dds/service_main.hpp"

int main(int argc, char** argv) {
  CLI::App app{"twinslam tracking service: images and IMU in, tracked features out"};
  twinslam::dds::ServiceOptions service;
  twinslam::dds::add_service_options(app, service);
  std::string camera_file, config_file;
  app.add_option("--camera", camera_file, "Camera calibration (EuRoC sensor.yaml: intrinsics, distortion, T_BS)")
      ->required();
  app.add_option("--config", config_file, "Tracking config YAML (deploy/config/tracking.yaml lists every key)");
  return twinslam::dds::service_main("tracking", app, service, argc, argv, [&] {
    twinslam::tracking::TrackingNodeOptions options;
    if (!config_file.empty()) {
      options = twinslam::tracking::load_tracking_config(config_file);
      spdlog::info("config {}: {}", config_file, twinslam::tracking::changed_from_defaults(options));
    }
    options.camera = twinslam::read_camera_sensor_yaml(camera_file);
    twinslam::dds::Node node(service.node);
    twinslam::dds::Counters counters;
    twinslam::dds::HeartbeatPublisher heartbeat(node, counters);
    twinslam::tracking::TrackingNode tracking(node, counters, options);
    return twinslam::dds::serve_until_shutdown(heartbeat, node);
  });
}

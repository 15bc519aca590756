// twinslam-ingest: replays a dataset (EuRoC ASL layout, CONTRACTS.md) onto the DDS sensor topics.
#include <spdlog/spdlog.h>

#include <memory>

#include "ingest_node.hpp"
#include "twinslam/camera/sensor_yaml.hpp"
#include "twinslam/core/shutdown.hpp"
#include "twinslam/dds/service_main.hpp"
#include "twinslam/ingest/ingest_config.hpp"

int main(int argc, char** argv) {
  CLI::App app{"twinslam ingest service: publishes a dataset's IMU, images and GNSS in timestamp order"};
  twinslam::dds::ServiceOptions service;
  twinslam::dds::add_service_options(app, service);
  std::string dataset_dir, config_file;
  twinslam::ingest::IngestOptions opt;
  twinslam::ingest::IngestConfig cli;  // what the command line gives; each option given wins over --config
  bool linger = false, features = false;
  app.add_option("--dataset", dataset_dir, "Dataset folder (EuRoC ASL layout)")->required();
  app.add_option("--config", config_file, "Ingest config YAML: speed, start_timeout_s, ack_timeout_s, faults");
  auto* speed = app.add_option("--speed", cli.speed, "Realtime pacing factor")->check(CLI::PositiveNumber)
                    ->capture_default_str();
  app.add_option("--ack-from", opt.ack_from, "Lockstep: services that must acknowledge each camera frame")
      ->delimiter(',');
  std::string wait_readers;
  app.add_option("--wait-readers", wait_readers,
                 "Matched readers needed before sending: N (imu and image) or imu=N,image=N,gnss=N");
  auto* start = app.add_option("--start-timeout", cli.start_timeout_s, "Seconds to wait for consumers")
                    ->capture_default_str();
  auto* ack = app.add_option("--ack-timeout", cli.ack_timeout_s, "Seconds to wait for a frame acknowledgement")
                  ->capture_default_str();
  app.add_flag("--features", features, "Publish mav0/cam0/features.csv as FeatureFrame instead of the images");
  app.add_flag("--linger", linger, "Stay up (state done) after the dataset until stopped");
  return twinslam::dds::service_main("ingest", app, service, argc, argv, [&] {
    twinslam::ingest::IngestConfig config;
    if (!config_file.empty()) config = twinslam::ingest::load_ingest_config(config_file);
    if (speed->count() > 0) config.speed = cli.speed;
    if (start->count() > 0) config.start_timeout_s = cli.start_timeout_s;
    if (ack->count() > 0) config.ack_timeout_s = cli.ack_timeout_s;
    config.validate(config_file.empty() ? "command line" : config_file);
    const auto dataset = twinslam::ingest::load_dataset(
        dataset_dir, features ? twinslam::ingest::CameraInput::kFeatureTracks : twinslam::ingest::CameraInput::kImages);
    spdlog::info("dataset {}: {} IMU, {} images, {} GNSS", dataset.root.string(), dataset.imu.size(),
                 dataset.images.size(), dataset.gnss.size());
    opt.realtime = service.realtime;
    opt.speed = config.speed;
    opt.faults = config.faults;
    opt.start_timeout = std::chrono::milliseconds(static_cast<long>(config.start_timeout_s * 1000));
    opt.ack_timeout = std::chrono::milliseconds(static_cast<long>(config.ack_timeout_s * 1000));
    opt.wait_readers = twinslam::ingest::parse_wait_readers(wait_readers, static_cast<int>(opt.ack_from.size()));
    twinslam::dds::Node node(service.node);
    std::unique_ptr<twinslam::ingest::FeatureReplay> replay;
    if (features) {
      replay = std::make_unique<twinslam::ingest::FeatureReplay>();
      replay->frames = twinslam::ingest::load_feature_tracks(dataset.root / "mav0/cam0/features.csv");
      replay->camera = twinslam::read_camera_sensor_yaml(dataset.root / "mav0/cam0/sensor.yaml");
      spdlog::info("feature tracks: {} frames", replay->frames.size());
    }
    twinslam::ingest::IngestNode ingest(node, dataset, opt, replay.get());
    const bool finished = ingest.run();
    if (finished && linger) twinslam::wait_for_shutdown(std::chrono::hours(24 * 365));
    return 0;
  });
}

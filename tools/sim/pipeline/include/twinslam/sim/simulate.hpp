#pragma once
// `twinslam sim`: one scenario -> one dataset folder in the layout of CONTRACTS.md. World and twin from the city
// generator, trajectory/IMU/GNSS/ground truth from the sensor simulator, grey images rendered through the
// scenario's camera, and optionally ideal feature tracks and preview pictures.
#include <cstdint>
#include <filesystem>
#include <optional>

#include "twinslam/sim/feature_tracks.hpp"
#include "twinslam/sim/scenario.hpp"

namespace twinslam::sim {

struct SimOptions {
  std::filesystem::path out;             // dataset folder DIR (created)
  bool features = false;                 // write mav0/cam0/features.csv
  FeatureTrackConfig feature_config;
  bool preview = false;                  // write DIR/preview/top_down.png and a few frames
  // false: no images are rendered (cam0/data.csv lists no frames); with `features` this makes a features-only dataset
  // in seconds, for estimator tests and benchmarks over many seeds.
  bool images = true;
  bool progress = true;                  // progress bar with ETA on stderr
  int render_threads = 2;                // threads per rendered frame
};

struct SimSummary {
  std::size_t frames = 0, imu = 0, gnss = 0, feature_rows = 0;
  std::size_t world_triangles = 0, twin_triangles = 0;
  double path_length_m = 0, duration_s = 0, wall_s = 0;
};

SimSummary simulate(const Scenario& scenario, const SimOptions& options);

}  // namespace twinslam::sim

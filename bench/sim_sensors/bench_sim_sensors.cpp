// Cost of the non-camera simulation: one trajectory state (spline + attitude jets), the IMU of a whole city-loops
// flight (60 001 samples), and writing all non-camera files of that flight.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <unistd.h>

#include "twinslam/sim/dataset_writer.hpp"
#include "twinslam/sim/scenario_io.hpp"

namespace {

using namespace twinslam::sim;

SceneHints hints() {
  SceneHints h;
  h.tall_building_center_W = Eigen::Vector2d(60, -30);
  return h;
}

void BM_TrajectoryState(benchmark::State& state) {
  const FlightTrajectory f = make_flight_trajectory(builtin_scenario("city-loops"), hints());
  double t = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(f.at(t));
    t = t > 290 ? 0 : t + 0.005;
  }
}
BENCHMARK(BM_TrajectoryState);

void BM_ImuCityLoops(benchmark::State& state) {
  const Scenario sc = builtin_scenario("city-loops");
  const FlightTrajectory f = make_flight_trajectory(sc, hints());
  for (auto _ : state) benchmark::DoNotOptimize(simulate_imu(f, sc.imu, sc.seed));
}
BENCHMARK(BM_ImuCityLoops)->Unit(benchmark::kMillisecond);

void BM_WriteSensorDatasetCityLoops(benchmark::State& state) {
  const Scenario sc = builtin_scenario("city-loops");
  const auto dir = std::filesystem::temp_directory_path() / ("twinslam_bench_sim_sensors_" + std::to_string(getpid()));
  for (auto _ : state) benchmark::DoNotOptimize(write_sensor_dataset(dir, sc, hints()));
  std::filesystem::remove_all(dir);
}
BENCHMARK(BM_WriteSensorDatasetCityLoops)->Unit(benchmark::kMillisecond);

}  // namespace

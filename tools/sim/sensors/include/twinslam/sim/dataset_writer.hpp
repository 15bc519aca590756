#pragma once
// Writers of the non-camera parts of the dataset layout (CONTRACTS.md "Dataset layout"). Numbers are written in the
// shortest form that reads back to the same double, so ingest reads exactly what was simulated; stamps are integer
// ns. Each writer creates the folders it needs and throws InputError naming the file if it cannot be written.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "twinslam/sim/clock.hpp"
#include "twinslam/sim/flight_trajectory.hpp"
#include "twinslam/sim/gnss_sim.hpp"
#include "twinslam/sim/imu_sim.hpp"

namespace twinslam::sim {

// DIR/mav0/imu0/data.csv (EuRoC: #timestamp [ns], w_RS_S xyz [rad s^-1], a_RS_S xyz [m s^-2]) and
// DIR/mav0/imu0/sensor.yaml (T_BS = identity, rate_hz, gyroscope/accelerometer noise densities and random walks).
void write_imu(const std::filesystem::path& dir, const std::vector<ImuSample>& samples, const ImuSimConfig& config);

// DIR/mav0/gnss0/data.csv with the CONTRACTS.md header.
void write_gnss(const std::filesystem::path& dir, const std::vector<GnssSample>& samples);

// Ground truth of B in W at the IMU stamps: DIR/mav0/state_groundtruth_estimate0/data.csv (EuRoC columns: position,
// quaternion w x y z, velocity, gyro and accel biases from `imu`) and DIR/groundtruth.tum (T_WB).
void write_groundtruth(const std::filesystem::path& dir, const FlightTrajectory& trajectory,
                       const std::vector<ImuSample>& imu);

// What dataset.yaml says about the twin; the twin writer fills it.
struct TwinReference {
  std::string path = "twin/";          // relative to DIR
  std::string crs = "ENU@origin";      // placeholder until the twin writer knows the real CRS
  // Where the twin is wrong (world building ids; empty when none or unknown), for evaluating registration there.
  std::vector<int> missing_building_ids = {};
  std::vector<int> added_building_ids = {};
  std::vector<int> shifted_building_ids = {};
  std::vector<Eigen::Vector3d> shifted_building_offsets_W = {};  // their shift [m, W], same order
  // The true footprint of each change (for evaluating twin-change reports): where a missing or shifted building
  // really stands, where an added one stands in the twin.
  struct Footprint {
    std::string kind;  // "missing", "added", "shifted"
    int building_id = 0;
    std::vector<Eigen::Vector2d> outline_W;  // [m, E N]
  };
  std::vector<Footprint> change_footprints = {};
};

// DIR/dataset.yaml: format version, origin, twin path, CRS and changes, and the scenario echo (scenario_to_yaml).
void write_dataset_yaml(const std::filesystem::path& dir, const Scenario& scenario, const TwinReference& twin);

// Everything above in one call (what `twinslam sim` needs besides the world and the camera): the trajectory from the
// scenario and the hints, IMU and GNSS from scenario.seed, all files written. Returns what was simulated, e.g. for the
// renderer to take camera poses from `trajectory` (T_WC = trajectory.at(t).T_WB() * camera_T_BC(scenario)).
struct SensorData {
  FlightTrajectory trajectory;
  std::vector<ImuSample> imu;
  std::vector<GnssSample> gnss;
};
// `gnss_model` replaces the simple GNSS model of gnss_sim.hpp when given (the ray-traced one needs the world, which
// this library does not have): it returns the fixes for the flight and may write its own files.
using GnssModelFn = std::function<std::vector<GnssSample>(const FlightTrajectory&)>;
SensorData write_sensor_dataset(const std::filesystem::path& dir, const Scenario& scenario, const SceneHints& hints,
                                const TwinReference& twin = {}, const GnssModelFn& gnss_model = {});

}  // namespace twinslam::sim

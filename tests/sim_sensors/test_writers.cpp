// Dataset files: same seed -> byte-identical files; what ingest and the trajectory readers read back is exactly what
// was simulated; dataset.yaml echoes the scenario.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include "test_support.hpp"
#include "twinslam/ingest/dataset.hpp"
#include "twinslam/sim/dataset_writer.hpp"
#include "twinslam/trajectory/io.hpp"

namespace twinslam::sim {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class SimWriters : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("twinslam_sim_writers_" + std::to_string(::getpid()));
    fs::remove_all(root_);
  }
  void TearDown() override { fs::remove_all(root_); }
  fs::path root_;
};

const char* const kFiles[] = {"mav0/imu0/data.csv", "mav0/imu0/sensor.yaml", "mav0/gnss0/data.csv",
                              "mav0/state_groundtruth_estimate0/data.csv", "groundtruth.tum", "dataset.yaml"};

TEST_F(SimWriters, SameSeedGivesIdenticalFiles) {
  const Scenario sc = builtin_scenario("tiny");
  write_sensor_dataset(root_ / "a", sc, testing::hints_for(sc));
  write_sensor_dataset(root_ / "b", sc, testing::hints_for(sc));
  Scenario other = sc;
  other.seed = sc.seed + 1;
  write_sensor_dataset(root_ / "c", other, testing::hints_for(other));
  for (const char* f : kFiles) {
    ASSERT_TRUE(fs::exists(root_ / "a" / f)) << f;
    EXPECT_EQ(slurp(root_ / "a" / f), slurp(root_ / "b" / f)) << f;
  }
  EXPECT_NE(slurp(root_ / "a" / "mav0/imu0/data.csv"), slurp(root_ / "c" / "mav0/imu0/data.csv"));
}

TEST_F(SimWriters, IngestReadsExactlyWhatWasSimulated) {
  const Scenario sc = builtin_scenario("tiny");
  const SensorData d = write_sensor_dataset(root_, sc, testing::hints_for(sc));
  // ingest needs a camera stream; the renderer writes the real one.
  fs::create_directories(root_ / "mav0/cam0/data");
  std::ofstream(root_ / "mav0/cam0/data.csv") << "#timestamp [ns],filename\n" << kEpochNs << "," << kEpochNs << ".png\n";
  std::ofstream(root_ / "mav0/cam0/data" / (std::to_string(kEpochNs) + ".png")) << "";
  const ingest::Dataset ds = ingest::load_dataset(root_);
  ASSERT_EQ(ds.imu.size(), d.imu.size());
  for (std::size_t k = 0; k < d.imu.size(); ++k) {
    ASSERT_EQ(ds.imu[k].stamp_ns, d.imu[k].stamp_ns);
    ASSERT_EQ(ds.imu[k].gyro_radps, d.imu[k].gyro_radps);  // bit-exact
    ASSERT_EQ(ds.imu[k].accel_mps2, d.imu[k].accel_mps2);
  }
  ASSERT_EQ(ds.gnss.size(), d.gnss.size());
  for (std::size_t i = 0; i < d.gnss.size(); ++i) {
    ASSERT_EQ(ds.gnss[i].latitude_deg, d.gnss[i].latitude_deg);
    ASSERT_EQ(ds.gnss[i].altitude_m, d.gnss[i].altitude_m);
    ASSERT_EQ(ds.gnss[i].std_up_m, d.gnss[i].std_up_m);
    ASSERT_EQ(ds.gnss[i].num_satellites, d.gnss[i].num_satellites);
  }
  std::ifstream gnss(root_ / "mav0/gnss0/data.csv");
  std::string header;
  std::getline(gnss, header);
  EXPECT_EQ(header,
            "#timestamp [ns],latitude [deg],longitude [deg],altitude [m],std_east [m],std_north [m],std_up [m],"
            "num_satellites");
}

TEST_F(SimWriters, GroundTruthFilesHoldTheTrajectory) {
  const Scenario sc = builtin_scenario("tiny");
  const SensorData d = write_sensor_dataset(root_, sc, testing::hints_for(sc));
  const Trajectory euroc = read_euroc_groundtruth(root_ / "mav0/state_groundtruth_estimate0/data.csv");
  const Trajectory tum = read_tum(root_ / "groundtruth.tum");
  ASSERT_EQ(euroc.size(), d.imu.size());
  ASSERT_EQ(tum.size(), d.imu.size());
  for (std::size_t k = 0; k < d.imu.size(); k += 97) {
    const FlightState s = d.trajectory.at(time_s(d.imu[k].stamp_ns));
    EXPECT_EQ(euroc.poses[k].stamp_ns, d.imu[k].stamp_ns);
    EXPECT_EQ(tum.poses[k].stamp_ns, d.imu[k].stamp_ns);
    EXPECT_LT((euroc.poses[k].p_X() - s.p_W).norm(), 1e-12);
    EXPECT_LT((tum.poses[k].p_X() - s.p_W).norm(), 1e-12);
    EXPECT_TRUE(tum.poses[k].T_XB.linear().isApprox(s.R_WB, 1e-12));
  }
  const std::string sensor = slurp(root_ / "mav0/imu0/sensor.yaml");
  const YAML::Node y = YAML::Load(sensor);
  EXPECT_EQ(y["gyroscope_noise_density"].as<double>(), sc.imu.gyro_noise);
  EXPECT_EQ(y["gyroscope_random_walk"].as<double>(), sc.imu.gyro_walk);
  EXPECT_EQ(y["accelerometer_noise_density"].as<double>(), sc.imu.accel_noise);
  EXPECT_EQ(y["accelerometer_random_walk"].as<double>(), sc.imu.accel_walk);
  EXPECT_EQ(y["rate_hz"].as<double>(), sc.imu.rate_hz);
}

TEST_F(SimWriters, DatasetYamlEchoesTheScenario) {
  Scenario sc = builtin_scenario("city-survey");
  sc.trajectory.duration_s = 40;
  TwinReference twin{"twin/", "EPSG:2056"};
  twin.missing_building_ids = {3, 17};
  twin.shifted_building_ids = {5};
  twin.shifted_building_offsets_W = {Eigen::Vector3d(0.1, -3.9987654321, 0)};
  write_dataset_yaml(root_, sc, twin);
  const YAML::Node y = YAML::LoadFile((root_ / "dataset.yaml").string());
  EXPECT_EQ(y["origin"]["lat"].as<double>(), sc.origin.lat_deg);
  EXPECT_EQ(y["twin"]["crs"].as<std::string>(), "EPSG:2056");
  // Where the twin is wrong, for evaluating registration there.
  EXPECT_EQ(y["twin"]["missing_building_ids"].as<std::vector<int>>(), twin.missing_building_ids);
  EXPECT_EQ(y["twin"]["added_building_ids"].size(), 0u);
  EXPECT_EQ(y["twin"]["shifted_building_ids"].as<std::vector<int>>(), twin.shifted_building_ids);
  EXPECT_EQ(y["twin"]["shifted_building_offsets_m"][0][1].as<double>(), -3.9987654321);
  EXPECT_EQ(y["stamp_epoch_ns"].as<std::int64_t>(), kEpochNs);
  YAML::Emitter e;
  e << y["scenario"];
  const Scenario back = parse_scenario_yaml(e.c_str(), "dataset.yaml");
  EXPECT_EQ(scenario_to_yaml(back), scenario_to_yaml(sc));
}

}  // namespace
}  // namespace twinslam::sim

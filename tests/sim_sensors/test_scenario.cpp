// Scenario files: every key read, unknown keys and bad values rejected with the file and the key in the message,
// built-ins valid, YAML echo reads back to the same scenario.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "twinslam/core/error.hpp"
#include "twinslam/sim/scenario_io.hpp"

namespace twinslam::sim {
namespace {

std::string error_of(const std::string& text) {
  try {
    parse_scenario_yaml(text, "scen.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SimScenario, ContractExampleReadsEveryKey) {
  const Scenario s = parse_scenario_yaml(R"(
seed: 11
origin: {lat: 47.5, lon: 8.25, alt: 400.5}
city:
  source: procedural
  size_m: 500
  height_m: [10, 50]
  path: null
trajectory:
  type: waypoints
  duration_s: 120
  speed_mps: 2.5
  altitude_m: [3, 20]
  waypoints: [[0, 0, 5], [50, 0, 8], [50, 40, 10]]
camera: {model: pinhole-radtan, width: 752, height: 480, rate_hz: 10, fov_deg: 90}
imu: {rate_hz: 400, gyro_noise: 2.0e-3, accel_noise: 9.0e-3, gyro_walk: 4.0e-5, accel_walk: 2.0e-4}
gnss: {rate_hz: 2, model: gaussian, sigma_m: 0.8}
twin: {noise_m: 0.3, missing_buildings: 1, added_buildings: 2, offset_m: [1, -2, 0.5],
       shifted_buildings: {count: 4, offset_m: 2.5}}
)",
                                         "scen.yaml");
  EXPECT_EQ(s.seed, 11u);
  EXPECT_DOUBLE_EQ(s.origin.lat_deg, 47.5);
  EXPECT_DOUBLE_EQ(s.origin.alt_m, 400.5);
  EXPECT_DOUBLE_EQ(s.city.size_m, 500);
  EXPECT_DOUBLE_EQ(s.city.height_m[1], 50);
  EXPECT_FALSE(s.city.path.has_value());
  EXPECT_EQ(s.trajectory.type, "waypoints");
  ASSERT_EQ(s.trajectory.waypoints_W.size(), 3u);
  EXPECT_DOUBLE_EQ(s.trajectory.waypoints_W[2].z(), 10);
  EXPECT_EQ(s.camera.model, "pinhole-radtan");
  EXPECT_EQ(s.camera.width, 752);
  EXPECT_DOUBLE_EQ(s.imu.rate_hz, 400);
  EXPECT_DOUBLE_EQ(s.imu.accel_walk, 2.0e-4);
  EXPECT_EQ(s.gnss.model, "gaussian");
  EXPECT_DOUBLE_EQ(s.gnss.sigma_m, 0.8);
  EXPECT_EQ(s.twin.added_buildings, 2);
  EXPECT_DOUBLE_EQ(s.twin.offset_m.y(), -2);
  EXPECT_EQ(s.twin.shifted_buildings.count, 4);
  EXPECT_DOUBLE_EQ(s.twin.shifted_buildings.offset_m, 2.5);
  ASSERT_TRUE(s.camera.T_BC.has_value());  // filled with the default of the type
}

TEST(SimScenario, ErrorsNameFileAndKey) {
  EXPECT_EQ(error_of("imu: {rate_hz: 0}\n"), "scen.yaml:1: imu.rate_hz: must be > 0 and <= 10000");
  EXPECT_NE(error_of("imu:\n  rate_hz: 200\n  gyro_nois: 1\n").find("scen.yaml:3: imu.gyro_nois: unknown key"),
            std::string::npos);
  EXPECT_NE(error_of("colour: red\n").find("scen.yaml:1: colour: unknown key"), std::string::npos);
  EXPECT_NE(error_of("trajectory:\n  speed_mps: fast\n").find("scen.yaml:2: trajectory.speed_mps: expected a number"),
            std::string::npos);
  EXPECT_NE(error_of("trajectory: {type: spiral}\n").find("trajectory.type: 'spiral' is not one of"), std::string::npos);
  EXPECT_NE(error_of("city: {height_m: [30, 10]}\n").find("city.height_m:"), std::string::npos);
  EXPECT_NE(error_of("city: {source: osm}\n").find("city.path: required"), std::string::npos);
  EXPECT_NE(error_of("twin: {offset_m: [1, 2]}\n").find("twin.offset_m: expected a list of 3 numbers"),
            std::string::npos);
  EXPECT_NE(error_of("trajectory: {type: waypoints}\n").find("trajectory.waypoints:"), std::string::npos);
  EXPECT_NE(error_of("camera: {T_BC: [2,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]}\n").find("camera.T_BC: rotation"),
            std::string::npos);
  EXPECT_NE(error_of("seed: [1\n").find("scen.yaml:"), std::string::npos);  // malformed YAML
  EXPECT_NE(error_of("base: nowhere\n").find("scen.yaml:1: base: unknown scenario 'nowhere'"), std::string::npos);
  EXPECT_EQ(error_of("city:\n  blocks: repeated\n"),
            "scen.yaml:2: city.blocks: 'repeated' is not one of identical | varied");
  EXPECT_NE(error_of("city: {source: osm, path: a.osm, blocks: identical}\n")
                .find("city.blocks: identical blocks need the procedural city"),
            std::string::npos);
}

TEST(SimScenario, ShiftedBuildingsErrorsNameTheKey) {
  EXPECT_EQ(Scenario{}.twin.shifted_buildings.count, 0);  // absent: nothing shifted
  EXPECT_EQ(error_of("twin:\n  shifted_buildings: {count: -1}\n"),
            "scen.yaml:2: twin.shifted_buildings.count: must be >= 0");
  EXPECT_EQ(error_of("twin:\n  shifted_buildings: {count: 2, offset_m: 25}\n"),
            "scen.yaml:2: twin.shifted_buildings.offset_m: must be in [0, 20] m");
  EXPECT_EQ(error_of("twin: {shifted_buildings: {offset_m: -1}}\n"),
            "scen.yaml:1: twin.shifted_buildings.offset_m: must be in [0, 20] m");
  EXPECT_NE(error_of("twin: {shifted_buildings: {offset_m: nan}}\n")
                .find("twin.shifted_buildings.offset_m: must be finite"),
            std::string::npos);
  EXPECT_NE(error_of("twin: {shifted_buildings: {count: 1.5}}\n")
                .find("twin.shifted_buildings.count: expected an integer"),
            std::string::npos);
  EXPECT_NE(error_of("twin: {shifted_buildings: 3}\n").find("twin.shifted_buildings: expected a mapping"),
            std::string::npos);
  EXPECT_NE(error_of("twin: {shifted_buildings: {count: 1, offset: 2}}\n")
                .find("twin.shifted_buildings.offset: unknown key (known here: count, offset_m)"),
            std::string::npos);
  EXPECT_NE(error_of("city: {source: osm, path: a.osm}\ntrajectory: {type: streets}\n")
                .find("trajectory.type: streets needs the procedural city"),
            std::string::npos);
}

TEST(SimScenario, BuiltinsAreValidAndDistinct) {
  for (const auto& name : builtin_scenario_names()) {
    const Scenario s = builtin_scenario(name);
    EXPECT_EQ(s.name, name);
    EXPECT_TRUE(s.camera.T_BC.has_value());
    EXPECT_EQ(s.camera.width, 640);
    EXPECT_EQ(s.camera.height, 400);
  }
  EXPECT_EQ(builtin_scenario("city-loops").trajectory.type, "loops");
  EXPECT_EQ(builtin_scenario("city-survey").trajectory.type, "survey");
  const Scenario long_flight = builtin_scenario("city-long");
  EXPECT_EQ(long_flight.trajectory.type, "streets");
  EXPECT_GE(long_flight.trajectory.duration_s, 12 * 60);
  EXPECT_GE(long_flight.trajectory.speed_mps * (long_flight.trajectory.duration_s - 4), 2000);  // cruise length
  EXPECT_GT(long_flight.twin.missing_buildings, 0);
  EXPECT_GT(long_flight.twin.shifted_buildings.count, 0);
  EXPECT_EQ(load_scenario("city-long").name, "city-long");
  EXPECT_LE(builtin_scenario("tiny").trajectory.duration_s, 30);
  EXPECT_THROW(builtin_scenario("mars"), UsageError);
  EXPECT_THROW(load_scenario("/nonexistent/scen.yaml"), InputError);
}

TEST(SimScenario, BaseOverridesBuiltinAndKeepsTheRest) {
  const Scenario s = parse_scenario_yaml("base: city-loops\nseed: 3\ntrajectory: {type: survey, altitude_m: [70, 80]}\n",
                                         "scen.yaml");
  EXPECT_EQ(s.seed, 3u);
  EXPECT_DOUBLE_EQ(s.trajectory.speed_mps, builtin_scenario("city-loops").trajectory.speed_mps);
  // The base's extrinsics were its type's default, so the survey gets the survey default (down-forward).
  EXPECT_TRUE(s.camera.T_BC->isApprox(default_T_BC("survey")));
}

TEST(SimScenario, DefaultExtrinsicsLookForwardOrDownForward) {
  const Eigen::Vector3d axis_loops = default_T_BC("loops").linear().col(2);   // optical axis in B
  const Eigen::Vector3d axis_survey = default_T_BC("survey").linear().col(2);
  EXPECT_TRUE(axis_loops.isApprox(Eigen::Vector3d(1, 0, 0)));
  EXPECT_TRUE(axis_survey.isApprox(Eigen::Vector3d(std::sqrt(0.5), 0, -std::sqrt(0.5))));
  // Image "down" (y_C) points down in the body for a level forward camera.
  EXPECT_TRUE(default_T_BC("loops").linear().col(1).isApprox(Eigen::Vector3d(0, 0, -1)));
  EXPECT_NEAR(default_T_BC("survey").linear().determinant(), 1.0, 1e-12);
}

TEST(SimScenario, YamlEchoReadsBackIdentically) {
  for (const auto& name : builtin_scenario_names()) {
    const std::string text = scenario_to_yaml(builtin_scenario(name));
    EXPECT_EQ(scenario_to_yaml(parse_scenario_yaml(text, "echo.yaml")), text) << name;
  }
  Scenario s = builtin_scenario("city-survey");
  s.twin.shifted_buildings = {7, 1.0 / 3.0};
  s.seed = 1234567890123ull;
  s.origin.lat_deg = 47.376912345678901;
  s.city.path = "some \"odd\" path.osm";
  s.city.crs = "EPSG:2056";
  s.trajectory.waypoints_W = {Eigen::Vector3d(0.1, 0.2, 70.3), Eigen::Vector3d(10, 20, 71)};
  s.imu.gyro_noise = 1.0 / 3.0;
  const std::string text = scenario_to_yaml(s);
  const Scenario r = parse_scenario_yaml(text, "echo.yaml");
  EXPECT_EQ(scenario_to_yaml(r), text);
  EXPECT_EQ(r.seed, s.seed);
  EXPECT_EQ(r.origin.lat_deg, s.origin.lat_deg);  // exact: shortest round-trip numbers
  EXPECT_EQ(r.imu.gyro_noise, s.imu.gyro_noise);
  EXPECT_EQ(r.twin.shifted_buildings.count, 7);
  EXPECT_EQ(r.twin.shifted_buildings.offset_m, 1.0 / 3.0);
  EXPECT_EQ(*r.city.path, *s.city.path);
  EXPECT_TRUE(r.camera.T_BC->isApprox(*s.camera.T_BC, 0.0));
}

// Imperfect sensors (issue 13): realistic by default, all off in `tiny`, read, range-checked and echoed.
TEST(SimScenario, ImperfectSensorKeys) {
  const Scenario s = parse_scenario_yaml(R"(
camera: {time_offset_s: -0.02, extrinsic_error_deg: 1.5, extrinsic_error_m: 0.03, auto_exposure_tau_s: 0,
         intrinsic_error_focal: 0.004, intrinsic_error_px: 0, intrinsic_error_k1: 0.001}
imu: {gyro_turn_on_bias: 0.01, accel_turn_on_bias: 0.2, gyro_bias_instability: 1e-4, accel_bias_instability: 2e-3,
      bias_tau_s: 0, gyro_scale_error: 0.01, accel_scale_error: 0, gyro_misalignment: 0.002, accel_misalignment: 0.003}
)",
                                         "scen.yaml");
  EXPECT_DOUBLE_EQ(s.camera.time_offset_s, -0.02);
  EXPECT_DOUBLE_EQ(s.camera.extrinsic_error_deg, 1.5);
  EXPECT_DOUBLE_EQ(s.camera.extrinsic_error_m, 0.03);
  EXPECT_EQ(s.camera.auto_exposure_tau_s, 0);
  EXPECT_DOUBLE_EQ(s.camera.intrinsic_error_focal, 0.004);
  EXPECT_EQ(s.camera.intrinsic_error_px, 0);
  EXPECT_DOUBLE_EQ(s.camera.intrinsic_error_k1, 0.001);
  EXPECT_DOUBLE_EQ(s.imu.gyro_turn_on_bias, 0.01);
  EXPECT_DOUBLE_EQ(s.imu.accel_turn_on_bias, 0.2);
  EXPECT_DOUBLE_EQ(s.imu.gyro_bias_instability, 1e-4);
  EXPECT_DOUBLE_EQ(s.imu.accel_bias_instability, 2e-3);
  EXPECT_EQ(s.imu.bias_tau_s, 0);
  EXPECT_DOUBLE_EQ(s.imu.gyro_scale_error, 0.01);
  EXPECT_EQ(s.imu.accel_scale_error, 0);
  EXPECT_DOUBLE_EQ(s.imu.gyro_misalignment, 0.002);
  EXPECT_DOUBLE_EQ(s.imu.accel_misalignment, 0.003);
  EXPECT_EQ(scenario_to_yaml(parse_scenario_yaml(scenario_to_yaml(s), "echo.yaml")), scenario_to_yaml(s));

  const Scenario loops = builtin_scenario("city-loops"), tiny = builtin_scenario("tiny");
  EXPECT_GT(loops.camera.time_offset_s, 0);
  EXPECT_GT(loops.camera.extrinsic_error_deg, 0);
  EXPECT_GT(loops.camera.extrinsic_error_m, 0);
  EXPECT_GT(loops.camera.auto_exposure_tau_s, 0);
  EXPECT_GT(loops.camera.intrinsic_error_focal, 0);
  EXPECT_GT(loops.camera.intrinsic_error_px, 0);
  EXPECT_GT(loops.camera.intrinsic_error_k1, 0);
  EXPECT_GT(loops.imu.gyro_turn_on_bias, 0);
  EXPECT_EQ(tiny.camera.time_offset_s, 0);
  EXPECT_EQ(tiny.camera.extrinsic_error_deg, 0);
  EXPECT_EQ(tiny.camera.extrinsic_error_m, 0);
  EXPECT_EQ(tiny.camera.auto_exposure_tau_s, 0);
  EXPECT_EQ(tiny.camera.intrinsic_error_focal, 0);
  EXPECT_EQ(tiny.camera.intrinsic_error_px, 0);
  EXPECT_EQ(tiny.camera.intrinsic_error_k1, 0);
  for (const double v : {tiny.imu.gyro_turn_on_bias, tiny.imu.accel_turn_on_bias, tiny.imu.gyro_bias_instability,
                         tiny.imu.accel_bias_instability, tiny.imu.bias_tau_s, tiny.imu.gyro_scale_error,
                         tiny.imu.accel_scale_error, tiny.imu.gyro_misalignment, tiny.imu.accel_misalignment})
    EXPECT_EQ(v, 0);
  // `base: tiny` keeps them off unless the file turns one on.
  EXPECT_EQ(parse_scenario_yaml("base: tiny\n", "scen.yaml").imu.gyro_scale_error, 0);

  EXPECT_EQ(error_of("camera:\n  extrinsic_error_deg: -1\n"),
            "scen.yaml:2: camera.extrinsic_error_deg: must be in [0, 10] deg (0 turns it off)");
  EXPECT_NE(error_of("camera: {extrinsic_error_m: nan}\n")
                .find("scen.yaml:1: camera.extrinsic_error_m: must be finite"),
            std::string::npos);
  EXPECT_NE(error_of("camera: {auto_exposure_tau_s: -0.1}\n").find("camera.auto_exposure_tau_s: must be in [0, 60] s"),
            std::string::npos);
  EXPECT_NE(error_of("camera: {time_offset_s: nan}\n").find("camera.time_offset_s: must be finite"),
            std::string::npos);
  EXPECT_NE(error_of("camera: {time_offset_s: -0.2}\n").find("camera.time_offset_s: must be in [-0.1, 0.1] s"),
            std::string::npos);
  EXPECT_NE(error_of("camera: {time_offset_s: 0.5}\n").find("camera.time_offset_s:"), std::string::npos);
  for (const char* key : {"gyro_turn_on_bias", "accel_turn_on_bias", "gyro_bias_instability", "accel_bias_instability",
                          "bias_tau_s", "gyro_scale_error", "accel_scale_error", "gyro_misalignment",
                          "accel_misalignment"}) {
    const std::string negative = error_of(std::string("imu: {") + key + ": -1e-3}\n");
    EXPECT_NE(negative.find(std::string("scen.yaml:1: imu.") + key + ": must be in [0, "), std::string::npos)
        << negative;
    const std::string nan = error_of(std::string("imu: {") + key + ": nan}\n");
    EXPECT_NE(nan.find(std::string("scen.yaml:1: imu.") + key + ": must be finite"), std::string::npos) << nan;
  }
  for (const auto& [key, range] : std::vector<std::pair<std::string, std::string>>{
           {"intrinsic_error_focal", "[0, 0.05]"}, {"intrinsic_error_px", "[0, 20] px"},
           {"intrinsic_error_k1", "[0, 0.05]"}}) {
    for (const char* bad : {"-1e-3", "0.5e2"})
      EXPECT_NE(error_of("camera: {" + key + ": " + bad + "}\n").find("scen.yaml:1: camera." + key + ": must be in " + range),
                std::string::npos)
          << key << bad;
    EXPECT_NE(error_of("camera: {" + key + ": nan}\n").find("camera." + key + ": must be finite"), std::string::npos);
  }
  EXPECT_NE(error_of("camera: {time_ofset_s: 0}\n").find("camera.time_ofset_s: unknown key"), std::string::npos);
}

}  // namespace
}  // namespace twinslam::sim

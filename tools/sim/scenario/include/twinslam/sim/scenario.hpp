#pragma once
// The simulator's scenario: every key of the scenario file in docs/CONTRACTS.md, with defaults and units.
// Parsing, validation and the built-in scenarios (tiny, city-loops, city-survey, city-long): scenario_io.hpp. Every
// other simulator module takes its own part of this struct.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace twinslam::sim {

struct Origin {
  double lat_deg = 47.3769;   // WGS84 origin of W (East-North-Up)
  double lon_deg = 8.5417;
  double alt_m = 408.0;
};

struct CityConfig {
  std::string source = "procedural";          // procedural | osm | cityjson | mesh | 3dtiles
  double size_m = 600;                        // procedural: side of the square city [m]
  std::array<double, 2> height_m{8, 60};      // procedural: building height range [m]
  std::optional<std::string> path;            // file for osm / cityjson / mesh / 3dtiles
  std::optional<std::string> crs;             // "EPSG:nnnn" when the file does not say
};

struct TrajectoryConfig {
  std::string type = "loops";                 // loops | survey | waypoints | streets
  double duration_s = 300;                    // [s]
  double speed_mps = 2.0;                     // cruise speed [m/s]
  std::array<double, 2> altitude_m{2, 17};    // min/max flight altitude above ground [m]
  std::vector<Eigen::Vector3d> waypoints_W;   // waypoints type only [m, W]
  double loops = 3;                           // loops type: number of loops around the tallest building
  double loop_rise_m = 4.5;                   // loops type: altitude gained per loop [m]
};

struct CameraSimConfig {
  std::string model = "fisheye-equidistant";  // fisheye-equidistant | pinhole-radtan
  int width = 640;                            // [px]
  int height = 400;                           // [px]
  double rate_hz = 20;                        // [Hz]
  double fov_deg = 120;                       // horizontal field of view [deg]
  // Camera extrinsics (body/IMU <- camera; C: x right, y down, z optical axis). Unset in a file = the default for the
  // trajectory type (default_T_BC in scenario_io.hpp); load_scenario() and builtin_scenario() always fill it.
  std::optional<Eigen::Isometry3d> T_BC;
};

struct ImuSimConfig {
  double rate_hz = 200;                       // [Hz]
  double gyro_noise = 1.2e-3;                 // white noise density [rad/s/sqrt(Hz)]
  double accel_noise = 8.0e-3;                // [m/s^2/sqrt(Hz)]
  double gyro_walk = 3.0e-5;                  // bias random walk density [rad/s^2/sqrt(Hz)]
  double accel_walk = 1.0e-4;                 // [m/s^3/sqrt(Hz)]
};

struct GnssSimConfig {
  double rate_hz = 5;                         // [Hz]
  std::string model = "raytrace";             // raytrace (city geometry) | gaussian (sigma_m) | learned (refused)
  double sigma_m = 1.5;                       // gaussian: horizontal standard deviation [m]
};

// Whole buildings the twin has in the wrong place (a mapping error): `count` of them moved horizontally by `offset_m`
// in a seeded random direction each. More than a street width (12 m) would make it a different city, not an error.
inline constexpr double kMaxBuildingShift_m = 20.0;
struct ShiftedBuildings {
  int count = 0;
  double offset_m = 0;                        // [m], horizontal
};

struct TwinConfig {
  double noise_m = 0.2;                       // perturbation of twin surfaces [m]
  int missing_buildings = 0;                  // buildings removed from the twin (environment change)
  int added_buildings = 0;                    // buildings in the twin that do not exist
  Eigen::Vector3d offset_m = Eigen::Vector3d::Zero();  // georeferencing error of the twin [m, W]
  ShiftedBuildings shifted_buildings;         // buildings misplaced in the twin
};

struct Scenario {
  std::string name = "custom";
  std::uint64_t seed = 7;
  Origin origin;
  CityConfig city;
  TrajectoryConfig trajectory;
  CameraSimConfig camera;
  ImuSimConfig imu;
  GnssSimConfig gnss;
  TwinConfig twin;
};

// Street grid of a procedural city: the centrelines of the streets between blocks (not the outer ring at the city's
// edge, which has buildings on one side only). Empty when the world has no grid.
struct StreetGrid {
  std::vector<double> east_m;                  // E of the north-south streets, increasing [m]
  std::vector<double> north_m;                 // N of the east-west streets, increasing [m]
  double width_m = 0;                          // kerb to kerb [m]
};

// A building as the trajectory generator sees it: its footprint and how high it reaches.
struct BuildingHint {
  int id = 0;
  std::vector<Eigen::Vector4d> rects_W;        // footprint as union of rectangles [min e, min n, max e, max n] [m]
  double height_m = 0;                         // eave height above ground [m]
  double top_m = 0;                            // highest point incl. roof structures [m]
};

// What the trajectory generator needs to know about the world (filled from the built city).
struct SceneHints {
  Eigen::Vector2d tall_building_center_W = Eigen::Vector2d::Zero();  // [m, E N]
  double tall_building_radius_m = 15;          // half-diagonal of its footprint [m]
  double tall_building_height_m = 60;          // [m]
  // Radius around tall_building_center_W that is free of other buildings and street furniture [m]; 0 = unknown.
  // The loops ring stays 3 m inside it.
  double clear_radius_m = 0;
  double ground_z_m = 0;                       // [m, U]
  std::array<double, 4> extent_W{-300, -300, 300, 300};  // min e, min n, max e, max n [m]
  // For `streets` flights (all empty/0 when the world does not say):
  StreetGrid streets;
  std::vector<BuildingHint> buildings;
  std::vector<Eigen::Vector4d> open_areas_W;   // whole blocks without buildings (parks) [min e, min n, max e, max n]
  double furniture_top_m = 0;                  // highest tree or parked car above ground [m]
};

}  // namespace twinslam::sim

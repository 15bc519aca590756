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
  // procedural: varied (every block drawn on its own) | identical (one block drawn and repeated on the whole grid,
  // no parks: a 3D-aliased city whose streets look the same every block pitch, the tower at the centre aside)
  std::string blocks = "varied";
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
  // Imperfections (0 turns one off; the built-in `tiny` has them all off). Time offset: the image stamped t was exposed
  // at t - time_offset_s on the IMU clock (stamped late, as by a host clock on arrival); a few ms is what a camera
  // stamped by its driver shows without hardware triggering.
  double time_offset_s = 0.005;               // [s], may be negative
  // The T_BC written to cam0/sensor.yaml is the true one (rendered with) turned by extrinsic_error_deg about a seeded
  // axis and moved by extrinsic_error_m in a seeded direction: the residual of a good Kalibr camera-IMU calibration
  // (a few tenths of a degree; translation, weakly observable, to about a centimetre).
  double extrinsic_error_deg = 0.5;           // [deg]
  double extrinsic_error_m = 0.01;            // [m]
  // The intrinsics written to cam0/sensor.yaml are the true ones (rendered with) with the focal lengths scaled by
  // 1 +- intrinsic_error_focal, the principal point moved by intrinsic_error_px in a seeded direction and
  // +- intrinsic_error_k1 added to the first distortion coefficient, one seeded sign for focal and k1 (so that they
  // add off-axis, camera_calibration.hpp): what a checkerboard calibration of a
  // wide-angle camera leaves (focal length to a few tenths of a percent, about a pixel at 305 px; the principal point
  // to about a pixel; the equidistant k1 to a few thousandths, 0.7 px at 60 deg off-axis).
  double intrinsic_error_focal = 0.003;       // [-], relative
  double intrinsic_error_px = 1.0;            // [px]
  double intrinsic_error_k1 = 0.002;          // [-]
  // Auto-exposure: the gain follows the scene's mean brightness toward a target with this time constant [s]
  // (pipeline/auto_exposure.hpp). An ISP's loop settles in about a second.
  double auto_exposure_tau_s = 0.3;           // [s]
  // Rolling shutter: row r is read (r - (height - 1) / 2) * line_time_us after the image's time, which is that of the
  // middle row (30 us x 400 rows = a 12 ms readout, a common CMOS sensor's). Motion blur: each row integrates the true
  // motion over exposure_ms centred on its own time (a few ms in daylight). 0 turns either off.
  double line_time_us = 30;                   // [us]
  double exposure_ms = 5;                     // [ms]
};

struct ImuSimConfig {
  double rate_hz = 200;                       // [Hz]
  double gyro_noise = 1.2e-3;                 // white noise density [rad/s/sqrt(Hz)]
  double accel_noise = 8.0e-3;                // [m/s^2/sqrt(Hz)]
  double gyro_walk = 3.0e-5;                  // bias random walk density [rad/s^2/sqrt(Hz)]
  double accel_walk = 1.0e-4;                 // [m/s^3/sqrt(Hz)]
  // Consumer MEMS errors beyond the densities above (which are all imu0/sensor.yaml states); imu_sim.hpp has the model.
  // Defaults from the TDK InvenSense ICM-20602 datasheet (DS-000176 v1.0): initial zero-rate offset +-1 deg/s,
  // zero-g offset +-25 mg, sensitivity tolerance +-1 %, cross-axis sensitivity +-2 %; per-axis standard deviations of
  // half those bounds. Bias instability as an Allan-variance floor of that class (about 10 deg/h, 0.1 mg at
  // 100-200 s), as a first-order Gauss-Markov process of std 1.5x the floor and correlation time bias_tau_s.
  double gyro_turn_on_bias = 8.7e-3;          // std per axis of the bias at power-on [rad/s] (0.5 deg/s)
  double accel_turn_on_bias = 0.12;           // [m/s^2] (12 mg)
  double gyro_bias_instability = 7.3e-5;      // std of the Gauss-Markov bias [rad/s] (15 deg/h)
  double accel_bias_instability = 1.5e-3;     // [m/s^2] (0.15 mg)
  double bias_tau_s = 100;                    // its correlation time [s]
  double gyro_scale_error = 5e-3;             // std per axis of the scale-factor error [-] (0.5 %)
  double accel_scale_error = 5e-3;            // [-]
  double gyro_misalignment = 0.01;            // std of each cross-axis coupling [rad] (1 %)
  double accel_misalignment = 0.01;           // [rad]
};

struct GnssSimConfig {
  double rate_hz = 5;                         // [Hz]
  std::string model = "raytrace";             // raytrace (city geometry) | learned (GP + GMM) | gaussian (sigma_m)
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

// Moving cars on the procedural city's street grid (world/traffic.hpp): in the images and the ideal feature tracks, not
// in the twin nor in the GNSS ray tracing. 0 cars = none; a world without a street grid has none.
struct TrafficSimConfig {
  int cars = 60;                              // cars in the city (60: about one per 110 m of street in the default city)
  double speed_mps = 8;                       // their speed [m/s] (0: they stand still in their lanes)
};

struct Scenario {
  std::string name = "custom";
  std::uint64_t seed = 7;
  Origin origin;
  // True when the scenario file itself names `origin:`. A real city (city.source other than procedural) without it
  // is placed at its model's centre at ground level instead (sim writes that origin into dataset.yaml).
  bool origin_given = false;
  CityConfig city;
  TrajectoryConfig trajectory;
  CameraSimConfig camera;
  ImuSimConfig imu;
  GnssSimConfig gnss;
  TwinConfig twin;
  TrafficSimConfig traffic;
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

#include "twinslam/sim/dataset_writer.hpp"

#include <fstream>

#include "number_format.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/sim/camera_calibration.hpp"
#include "twinslam/sim/clock.hpp"
#include "twinslam/sim/scenario_io.hpp"
#include "twinslam/trajectory/io.hpp"

namespace twinslam::sim {

namespace fs = std::filesystem;
using detail::append_number;

namespace {

void write_text(const fs::path& file, const std::string& text) {
  std::error_code ec;
  fs::create_directories(file.parent_path(), ec);
  std::ofstream out(file, std::ios::binary);
  out << text;
  out.close();
  if (!out) throw InputError(where(file.string(), 0, "cannot write file"));
}

void append_row(std::string& out, std::int64_t stamp, std::initializer_list<double> values) {
  out += std::to_string(stamp);
  for (const double v : values) {
    out += ',';
    append_number(out, v);
  }
  out += '\n';
}

void append_ids(std::string& out, const char* key, const std::vector<int>& ids, const char* comment) {
  out += std::string("  ") + key + ": [";
  for (std::size_t k = 0; k < ids.size(); ++k) out += (k ? ", " : "") + std::to_string(ids[k]);
  out += "]   # " + std::string(comment) + "\n";
}

// [[x, y], ...] of the first two coordinates of each point.
template <typename Points>
void append_xy_list(std::string& y, const Points& points) {
  y += "[";
  for (std::size_t k = 0; k < points.size(); ++k) {
    y += k ? ", [" : "[";
    append_number(y, points[k].x());
    y += ", ";
    append_number(y, points[k].y());
    y += "]";
  }
  y += "]";
}

void append_twin(std::string& y, const TwinReference& twin) {
  y += "twin:\n  path: \"" + twin.path + "\"\n  crs: \"" + twin.crs + "\"\n";
  append_ids(y, "missing_building_ids", twin.missing_building_ids, "world buildings the twin lacks");
  append_ids(y, "added_building_ids", twin.added_building_ids, "twin-only buildings");
  append_ids(y, "shifted_building_ids", twin.shifted_building_ids, "buildings the twin has elsewhere");
  y += "  shifted_building_offsets_m: ";
  append_xy_list(y, twin.shifted_building_offsets_W);
  y += "   # their shift [east, north] in W, same order\n";
  y += "  change_footprints_W:";
  y += twin.change_footprints.empty() ? " []   # true footprints of the changes [m, E N]\n"
                                      : "   # true footprints of the changes [m, E N]: missing and shifted where the "
                                        "building really stands, added where the twin has it\n";
  for (const auto& f : twin.change_footprints) {
    y += "    - {kind: " + f.kind + ", building_id: " + std::to_string(f.building_id) + ", outline: ";
    append_xy_list(y, f.outline_W);
    y += "}\n";
  }
}

template <typename Matrix>
void append_rows(std::string& y, const char* key, const Matrix& m, const char* comment) {
  y += std::string("  ") + key + ": [";
  for (int r = 0; r < m.rows(); ++r)
    for (int c = 0; c < m.cols(); ++c) {
      if (r || c) y += ", ";
      append_number(y, m(r, c));
    }
  y += "]   # " + std::string(comment) + "\n";
}

// The true imperfections (CONTRACTS.md "Scenario file"), which no calibration file of the dataset states.
void append_sensor_errors(std::string& y, const Scenario& scenario) {
  y += "sensor_errors:   # the truth behind the calibration files, for evaluation only\n  camera_time_offset_s: ";
  append_number(y, scenario.camera.time_offset_s);
  y += "   # image stamp - exposure time (IMU clock)\n";
  append_rows(y, "T_BC_true", camera_T_BC(scenario).matrix(), "body <- camera of the images, row-major");
  append_rows(y, "T_BC_calibrated", calibrated_T_BC(scenario).matrix(), "what mav0/cam0/sensor.yaml states");
  const CameraIntrinsicErrors k = camera_intrinsic_errors(scenario);
  y += "  camera_focal_scale: ";
  append_number(y, k.focal_scale);
  y += "   # stated fu, fv = true x this\n";
  append_rows(y, "camera_principal_point_shift_px", k.principal_point_shift_px.transpose(),
              "stated (cu, cv) - true [px]");
  y += "  camera_k1_offset: ";
  append_number(y, k.k1_offset);
  y += "   # stated - true first distortion coefficient\n";
  const ImuDeviceErrors imu = imu_device_errors(scenario.imu, scenario.seed);
  append_rows(y, "imu_gyro_matrix", imu.gyro_matrix, "gyro = M w_B + b_g + n, row-major");
  append_rows(y, "imu_accel_matrix", imu.accel_matrix, "accel = M f_B + b_a + n, row-major");
  append_rows(y, "imu_gyro_turn_on_bias", imu.gyro_turn_on_bias.transpose(), "[rad/s], part of the ground-truth bias");
  append_rows(y, "imu_accel_turn_on_bias", imu.accel_turn_on_bias.transpose(), "[m/s^2]");
}

}  // namespace

void write_imu(const fs::path& dir, const std::vector<ImuSample>& samples, const ImuSimConfig& config) {
  std::string csv =
      "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
      "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n";
  csv.reserve(samples.size() * 140);
  for (const ImuSample& m : samples)
    append_row(csv, m.stamp_ns, {m.gyro_radps.x(), m.gyro_radps.y(), m.gyro_radps.z(), m.accel_mps2.x(),
                                 m.accel_mps2.y(), m.accel_mps2.z()});
  write_text(dir / "mav0" / "imu0" / "data.csv", csv);

  std::string yaml =
      "# twinslam sim: IMU noise in continuous-time densities (Kalibr/EuRoC convention)\n"
      "sensor_type: imu\ncomment: simulated IMU (body frame B = this sensor)\n"
      "T_BS:\n  cols: 4\n  rows: 4\n  data: [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, "
      "1.0]\nrate_hz: ";
  append_number(yaml, config.rate_hz);
  yaml += "\ngyroscope_noise_density: ";      // [rad/s/sqrt(Hz)]
  append_number(yaml, config.gyro_noise);
  yaml += "\ngyroscope_random_walk: ";        // [rad/s^2/sqrt(Hz)]
  append_number(yaml, config.gyro_walk);
  yaml += "\naccelerometer_noise_density: ";  // [m/s^2/sqrt(Hz)]
  append_number(yaml, config.accel_noise);
  yaml += "\naccelerometer_random_walk: ";    // [m/s^3/sqrt(Hz)]
  append_number(yaml, config.accel_walk);
  yaml += "\n";
  write_text(dir / "mav0" / "imu0" / "sensor.yaml", yaml);
}

void write_gnss(const fs::path& dir, const std::vector<GnssSample>& samples) {
  std::string csv =
      "#timestamp [ns],latitude [deg],longitude [deg],altitude [m],std_east [m],std_north [m],std_up [m],"
      "num_satellites\n";
  for (const GnssSample& g : samples) {
    csv += std::to_string(g.stamp_ns);
    for (const double v : {g.latitude_deg, g.longitude_deg, g.altitude_m, g.std_east_m, g.std_north_m, g.std_up_m}) {
      csv += ',';
      append_number(csv, v);
    }
    csv += ',' + std::to_string(g.num_satellites) + '\n';
  }
  write_text(dir / "mav0" / "gnss0" / "data.csv", csv);
}

void write_groundtruth(const fs::path& dir, const FlightTrajectory& trajectory, const std::vector<ImuSample>& imu) {
  std::string csv =
      "#timestamp,p_RS_R_x [m],p_RS_R_y [m],p_RS_R_z [m],q_RS_w [],q_RS_x [],q_RS_y [],q_RS_z [],"
      "v_RS_R_x [m s^-1],v_RS_R_y [m s^-1],v_RS_R_z [m s^-1],b_w_RS_S_x [rad s^-1],b_w_RS_S_y [rad s^-1],"
      "b_w_RS_S_z [rad s^-1],b_a_RS_S_x [m s^-2],b_a_RS_S_y [m s^-2],b_a_RS_S_z [m s^-2]\n";
  Trajectory tum;
  tum.poses.reserve(imu.size());
  for (const ImuSample& m : imu) {
    const FlightState s = trajectory.at(time_s(m.stamp_ns));
    Eigen::Quaterniond q(s.R_WB);
    if (q.w() < 0) q.coeffs() *= -1;  // one sign convention, w >= 0
    append_row(csv, m.stamp_ns,
               {s.p_W.x(), s.p_W.y(), s.p_W.z(), q.w(), q.x(), q.y(), q.z(), s.v_W.x(), s.v_W.y(), s.v_W.z(),
                m.gyro_bias_radps.x(), m.gyro_bias_radps.y(), m.gyro_bias_radps.z(), m.accel_bias_mps2.x(),
                m.accel_bias_mps2.y(), m.accel_bias_mps2.z()});
    tum.poses.push_back(make_pose(m.stamp_ns, s.p_W, q));
  }
  write_text(dir / "mav0" / "state_groundtruth_estimate0" / "data.csv", csv);
  write_tum(dir / "groundtruth.tum", tum);
}

void write_dataset_yaml(const fs::path& dir, const Scenario& scenario, const TwinReference& twin) {
  std::string y = "# twinslam simulated dataset (CONTRACTS.md \"Dataset layout\")\nformat: twinslam-dataset-1\n";
  y += "origin: {lat: ";
  append_number(y, scenario.origin.lat_deg);
  y += ", lon: ";
  append_number(y, scenario.origin.lon_deg);
  y += ", alt: ";
  append_number(y, scenario.origin.alt_m);
  y += "}   # W = ENU at this WGS84 point (GeographicLib LocalCartesian)\n";
  y += "stamp_epoch_ns: " + std::to_string(kEpochNs) + "   # stamp of simulation time 0\n";
  append_twin(y, twin);
  append_sensor_errors(y, scenario);
  y += "scenario:\n";
  const std::string echo = scenario_to_yaml(scenario);
  std::size_t start = 0;
  while (start < echo.size()) {  // indent the echo under `scenario:`
    const std::size_t end = echo.find('\n', start);
    y += "  " + echo.substr(start, end - start) + "\n";
    start = end == std::string::npos ? echo.size() : end + 1;
  }
  write_text(dir / "dataset.yaml", y);
}

SensorData write_sensor_dataset(const fs::path& dir, const Scenario& scenario, const SceneHints& hints,
                                const TwinReference& twin, const GnssModelFn& gnss_model) {
  SensorData d{make_flight_trajectory(scenario, hints), {}, {}};
  d.imu = simulate_imu(d.trajectory, scenario.imu, scenario.seed);
  fs::create_directories(dir / "mav0" / "gnss0");
  d.gnss = gnss_model ? gnss_model(d.trajectory)
                      : simulate_gnss(d.trajectory, scenario.gnss, scenario.origin, scenario.seed);
  write_imu(dir, d.imu, scenario.imu);
  write_gnss(dir, d.gnss);
  write_groundtruth(dir, d.trajectory, d.imu);
  write_dataset_yaml(dir, scenario, twin);
  return d;
}

}  // namespace twinslam::sim

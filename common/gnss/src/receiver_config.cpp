#include "twinslam/gnss/receiver_config.hpp"

#include "twinslam/core/error.hpp"
#include "twinslam/core/yaml_fields.hpp"

namespace twinslam::gnss {

void ReceiverConfig::validate(const std::string& file) const {
  auto fail = [&](const char* key, const char* what) {
    throw InputError(file + ": receiver key '" + key + "': " + what);
  };
  if (max_iterations < 1) fail("max_iterations", "must be >= 1");
  if (!(convergence_m > 0)) fail("convergence_m", "must be > 0");
  if (elevation_mask_deg < -90 || elevation_mask_deg >= 90) fail("elevation_mask_deg", "must be in [-90, 90)");
  if (!(false_alarm_probability > 0 && false_alarm_probability < 1)) {
    fail("false_alarm_probability", "must be in (0, 1)");
  }
  if (cn0_reference_dbhz < 0 || cn0_reference_dbhz > 70) fail("cn0_reference_dbhz", "must be in [0, 70]");
  if (max_exclusions < 0) fail("max_exclusions", "must be >= 0");
  if (!(max_residual_m > 0)) fail("max_residual_m", "must be > 0");
}

ReceiverConfig load_receiver_config(const std::string& path) {
  ReceiverConfig c;
  yaml::Fields top("config");
  yaml::Fields& r = top.section("receiver");
  r.integer("max_iterations", c.max_iterations)
      .number("convergence_m", c.convergence_m, "m")
      .flag("earth_rotation", c.earth_rotation)
      .number("elevation_mask_deg", c.elevation_mask_deg, "deg")
      .number("cn0_reference_dbhz", c.cn0_reference_dbhz, "dB-Hz")
      .number("false_alarm_probability", c.false_alarm_probability)
      .integer("max_exclusions", c.max_exclusions)
      .number("max_residual_m", c.max_residual_m, "m");
  top.load(path);
  c.validate(path);
  return c;
}

}  // namespace twinslam::gnss

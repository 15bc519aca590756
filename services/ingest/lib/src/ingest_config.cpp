#include "twinslam/ingest/ingest_config.hpp"

#include <cmath>
#include <sstream>

#include "twinslam/core/error.hpp"
#include "twinslam/core/yaml_fields.hpp"

namespace twinslam::ingest {
namespace {

std::string num(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

void in_range(const std::string& source, const char* key, double value, double lo, double hi, const char* unit) {
  if (!std::isfinite(value) || value <= lo || value > hi) {
    throw InputError(where(source, 0, std::string("ingest key '") + key + "': must lie in (" + num(lo) + ", " +
                                          num(hi) + "]" + unit + ", got " + num(value)));
  }
}

}  // namespace

void IngestConfig::validate(const std::string& source) const {
  in_range(source, "speed", speed, 0.0, 1000.0, "");
  // A day: beyond it a wait is a hang, not a slow start.
  in_range(source, "start_timeout_s", start_timeout_s, 0.0, 86400.0, " s");
  in_range(source, "ack_timeout_s", ack_timeout_s, 0.0, 86400.0, " s");
  faults.validate(source);
}

void bind_ingest_config(yaml::Fields& fields, IngestConfig& config) {
  fields.number("speed", config.speed)
      .number("start_timeout_s", config.start_timeout_s, "s")
      .number("ack_timeout_s", config.ack_timeout_s, "s");
  bind_fault_config(fields.section("faults"), config.faults);
}

IngestConfig parse_ingest_config(const std::string& text, const std::string& file, const IngestConfig& base) {
  IngestConfig config = base;
  yaml::Fields fields("ingest");
  bind_ingest_config(fields, config);
  fields.parse(text, file);
  config.validate(file);
  return config;
}

IngestConfig load_ingest_config(const std::string& path, const IngestConfig& base) {
  return parse_ingest_config(yaml::read_text_file(path), path, base);
}

}  // namespace twinslam::ingest

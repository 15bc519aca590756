#include "tracking_config.hpp"

#include "twinslam/core/error.hpp"
#include "twinslam/core/yaml_fields.hpp"
#include "twinslam/tracking/frontend_config_yaml.hpp"

namespace twinslam::tracking {

void bind_tracking_config(yaml::Fields& fields, TrackingNodeOptions& options) {
  bind_frontend_config(fields, options.frontend);
  fields.section("node").milliseconds("imu_wait_ms", options.imu_wait);
}

std::string changed_from_defaults(const TrackingNodeOptions& options) {
  TrackingNodeOptions now = options, defaults;
  yaml::Fields a("tracking"), b("tracking");
  bind_tracking_config(a, now);
  bind_tracking_config(b, defaults);
  return yaml::changed_values(a.values(), b.values());
}

TrackingNodeOptions parse_tracking_config(const std::string& text, const std::string& file,
                                          const TrackingNodeOptions& base) {
  TrackingNodeOptions o = base;
  yaml::Fields fields("tracking");
  bind_tracking_config(fields, o);
  fields.parse(text, file);
  o.frontend.validate(file);
  if (o.imu_wait.count() < 0) throw InputError(where(file, 0, "tracking key 'node.imu_wait_ms': must be >= 0"));
  return o;
}

TrackingNodeOptions load_tracking_config(const std::string& path, const TrackingNodeOptions& base) {
  return parse_tracking_config(yaml::read_text_file(path), path, base);
}

}  // namespace twinslam::tracking

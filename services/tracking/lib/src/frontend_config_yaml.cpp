#include "twinslam/tracking/frontend_config_yaml.hpp"

namespace twinslam::tracking {
namespace {

void bind_detection_and_klt(yaml::Fields& f, FrontendConfig& c) {
  f.integer("max_features", c.max_features)
      .integer("grid_cols", c.grid_cols)
      .integer("grid_rows", c.grid_rows)
      .number("min_distance_px", c.min_distance_px, "px")
      .number("quality_level", c.quality_level)
      .number("min_eigenvalue", c.min_eigenvalue)
      .integer("border_px", c.border_px)
      .integer("klt_window_px", c.klt_window_px)
      .integer("klt_levels", c.klt_levels)
      .integer("klt_max_iterations", c.klt_max_iterations)
      .number("klt_epsilon_px", c.klt_epsilon_px, "px")
      .number("fb_threshold_px", c.fb_threshold_px, "px")
      .integer("ref_window_px", c.ref_window_px)
      .number("ref_min_zncc", c.ref_min_zncc);
}

void bind_ransac_and_images(yaml::Fields& f, FrontendConfig& c) {
  using Model = FrontendConfig::RansacModel;
  f.choice("ransac_model", c.ransac_model,
           {{"essential", Model::kEssential}, {"known_rotation", Model::kKnownRotation}})
      .number("ransac_threshold_px", c.ransac_threshold_px, "px")
      .number("ransac_confidence", c.ransac_confidence)
      .integer("ransac_max_iterations", c.ransac_max_iterations)
      .integer("ransac_span_frames", c.ransac_span_frames)
      .count("ransac_seed", c.ransac_seed)
      .flag("clahe", c.clahe)
      .number("clahe_clip_limit", c.clahe_clip_limit)
      .integer("clahe_tiles", c.clahe_tiles)
      .number("presmooth_sigma_px", c.presmooth_sigma_px, "px");
}

}  // namespace

void bind_frontend_config(yaml::Fields& fields, FrontendConfig& config) {
  bind_detection_and_klt(fields, config);
  bind_ransac_and_images(fields, config);
}

FrontendConfig parse_frontend_config(const std::string& text, const std::string& file, const FrontendConfig& base) {
  FrontendConfig config = base;
  yaml::Fields fields("tracking");
  bind_frontend_config(fields, config);
  fields.parse(text, file);
  config.validate(file);
  return config;
}

FrontendConfig load_frontend_config(const std::string& path, const FrontendConfig& base) {
  return parse_frontend_config(yaml::read_text_file(path), path, base);
}

}  // namespace twinslam::tracking

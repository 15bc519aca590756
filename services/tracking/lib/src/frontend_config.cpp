#include "twinslam/tracking/frontend_config.hpp"

#include <cmath>
#include <sstream>

#include "twinslam/core/error.hpp"

namespace twinslam::tracking {
namespace {

[[noreturn]] void bad(const std::string& source, const char* key, const std::string& what) {
  throw InputError(where(source, 0, std::string("tracking key '") + key + "': " + what));
}

std::string num(double x) {
  std::ostringstream s;
  s.precision(10);
  s << x;
  return s.str();
}

void positive_int(const std::string& source, const char* key, int value) {
  if (value <= 0) bad(source, key, "must be a positive integer, got " + std::to_string(value));
}

void positive(const std::string& source, const char* key, double value) {
  if (!std::isfinite(value) || value <= 0.0) bad(source, key, "must be finite and positive, got " + num(value));
}

}  // namespace

void FrontendConfig::validate(const std::string& source) const {
  positive_int(source, "max_features", max_features);
  positive_int(source, "grid_cols", grid_cols);
  positive_int(source, "grid_rows", grid_rows);
  if (!std::isfinite(min_distance_px) || min_distance_px < 0.0) {
    bad(source, "min_distance_px", "must be finite and >= 0, got " + num(min_distance_px));
  }
  if (!std::isfinite(quality_level) || quality_level <= 0.0 || quality_level >= 1.0) {
    bad(source, "quality_level", "must lie in (0, 1), got " + num(quality_level));
  }
  if (!std::isfinite(min_eigenvalue) || min_eigenvalue < 0.0) {
    bad(source, "min_eigenvalue", "must be finite and >= 0, got " + num(min_eigenvalue));
  }
  if (border_px < 0) bad(source, "border_px", "must be >= 0, got " + std::to_string(border_px));
  if (klt_window_px < 5 || klt_window_px % 2 == 0) {
    bad(source, "klt_window_px", "must be odd and >= 5, got " + std::to_string(klt_window_px));
  }
  if (klt_levels < 0 || klt_levels > 8) {
    bad(source, "klt_levels", "must lie in [0, 8], got " + std::to_string(klt_levels));
  }
  positive_int(source, "klt_max_iterations", klt_max_iterations);
  positive(source, "klt_epsilon_px", klt_epsilon_px);
  positive(source, "fb_threshold_px", fb_threshold_px);
  if (ref_window_px != 0 && (ref_window_px < 5 || ref_window_px % 2 == 0)) {
    bad(source, "ref_window_px", "must be 0 (off) or odd and >= 5, got " + std::to_string(ref_window_px));
  }
  if (!std::isfinite(ref_min_zncc) || ref_min_zncc < -1.0 || ref_min_zncc >= 1.0) {
    bad(source, "ref_min_zncc", "must lie in [-1, 1), got " + num(ref_min_zncc));
  }
  positive(source, "ransac_threshold_px", ransac_threshold_px);
  if (!std::isfinite(ransac_confidence) || ransac_confidence <= 0.0 || ransac_confidence >= 1.0) {
    bad(source, "ransac_confidence", "must lie in (0, 1), got " + num(ransac_confidence));
  }
  positive_int(source, "ransac_max_iterations", ransac_max_iterations);
  if (ransac_span_frames < 0 || ransac_span_frames > 7) {
    bad(source, "ransac_span_frames", "must lie in [0, 7], got " + std::to_string(ransac_span_frames));
  }
  positive(source, "clahe_clip_limit", clahe_clip_limit);
  positive_int(source, "clahe_tiles", clahe_tiles);
  if (!std::isfinite(presmooth_sigma_px) || presmooth_sigma_px < 0.0 || presmooth_sigma_px > 10.0) {
    bad(source, "presmooth_sigma_px", "must lie in [0, 10], got " + num(presmooth_sigma_px));
  }
}

}  // namespace twinslam::tracking

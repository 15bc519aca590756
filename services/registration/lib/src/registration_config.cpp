#include "twinslam/registration/registration_config.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <variant>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "twinslam/core/error.hpp"

namespace twinslam::registration {
namespace {

using C = RegistrationConfig;

[[noreturn]] void bad(const std::string& file, std::size_t line, const std::string& key, const std::string& what) {
  throw InputError(where(file, line, "registration key '" + key + "': " + what));
}

std::size_t line_of(const YAML::Node& node) { return static_cast<std::size_t>(node.Mark().line + 1); }

template <class T>
T read(const std::string& file, const std::string& key, const YAML::Node& node, const char* type) {
  try {
    return node.as<T>();
  } catch (const YAML::Exception&) {
    bad(file, line_of(node), key, std::string("expected ") + type);
  }
}

// One row per YAML key: the parser and the "known keys" message come from the same table, so they cannot disagree.
using Field = std::variant<double C::*, int C::*, WeightMode C::*, bool C::*>;
struct Key {
  const char* name;
  Field field;
};
const std::vector<Key>& keys() {
  static const std::vector<Key> k = {
      {"min_quality", &C::min_quality},
      {"voxel_size_m", &C::voxel_size_m},
      {"outlier_neighbors", &C::outlier_neighbors},
      {"outlier_stddev", &C::outlier_stddev},
      {"min_points", &C::min_points},
      {"surface_sigma_m", &C::surface_sigma_m},
      {"threads", &C::threads},
      {"max_iterations", &C::max_iterations},
      {"initial_threshold_m", &C::initial_threshold_m},
      {"initial_threshold_sigmas", &C::initial_threshold_sigmas},
      {"max_initial_threshold_m", &C::max_initial_threshold_m},
      {"min_threshold_m", &C::min_threshold_m},
      {"threshold_sigmas", &C::threshold_sigmas},
      {"convergence_translation_m", &C::convergence_translation_m},
      {"convergence_rotation_deg", &C::convergence_rotation_deg},
      {"yaw_search_min_sigma_deg", &C::yaw_search_min_sigma_deg},
      {"yaw_search_step_deg", &C::yaw_search_step_deg},
      {"yaw_search_max_deg", &C::yaw_search_max_deg},
      {"yaw_search_ambiguity", &C::yaw_search_ambiguity},
      {"weights", &C::weights},
      {"paper_beta", &C::paper_beta},
      {"correlation_inflation", &C::correlation_inflation},
      {"min_sigma_m", &C::min_sigma_m},
      {"degeneracy_threshold", &C::degeneracy_threshold},
      {"surface_error_m", &C::surface_error_m},
      {"surface_group_angle_deg", &C::surface_group_angle_deg},
      {"surface_group_offset_m", &C::surface_group_offset_m},
      {"fixed_rotation_information", &C::fixed_rotation_information},
      {"fixed_translation_information", &C::fixed_translation_information},
      {"min_inliers", &C::min_inliers},
      {"min_fitness", &C::min_fitness},
      {"max_rmse_m", &C::max_rmse_m},
      {"max_zero_directions", &C::max_zero_directions},
      {"max_position_sigma_m", &C::max_position_sigma_m},
      {"max_mahalanobis_sq", &C::max_mahalanobis_sq},
      {"mahalanobis_floor_m", &C::mahalanobis_floor_m},
      {"mahalanobis_floor_deg", &C::mahalanobis_floor_deg},
      {"estimate_scale", &C::estimate_scale},
      {"scale_prior_walk", &C::scale_prior_walk},
      {"scale_prior_measurement_sigma", &C::scale_prior_measurement_sigma},
      {"scale_prior_max_heading_sigma_deg", &C::scale_prior_max_heading_sigma_deg},
      {"scale_prior_max_position_sigma_m", &C::scale_prior_max_position_sigma_m},
      {"persistent_corrections", &C::persistent_corrections},
      {"persistent_tolerance_m", &C::persistent_tolerance_m},
      {"persistent_tolerance_deg", &C::persistent_tolerance_deg},
      {"persistent_tolerance_fraction", &C::persistent_tolerance_fraction},
      {"persistent_span_s", &C::persistent_span_s},
      {"acquisition_heading_sigma_deg", &C::acquisition_heading_sigma_deg},
      {"acquisition_min_correction_m", &C::acquisition_min_correction_m},
      {"acquisition_min_correction_deg", &C::acquisition_min_correction_deg},
      {"acquisition_corrections", &C::acquisition_corrections},
      {"acquisition_span_s", &C::acquisition_span_s},
  };
  return k;
}

WeightMode parse_mode(const std::string& file, const std::string& key, const YAML::Node& node) {
  const std::string s = read<std::string>(file, key, node, "paper, adaptive or fixed");
  if (s == "paper") return WeightMode::kPaper;
  if (s == "adaptive") return WeightMode::kAdaptive;
  if (s == "fixed") return WeightMode::kFixed;
  bad(file, line_of(node), key, "expected paper, adaptive or fixed, got '" + s + "'");
}

void set(C& c, const Key& k, const std::string& file, const YAML::Node& node) {
  if (auto d = std::get_if<double C::*>(&k.field)) c.*(*d) = read<double>(file, k.name, node, "a number");
  if (auto i = std::get_if<int C::*>(&k.field)) c.*(*i) = read<int>(file, k.name, node, "an integer");
  if (auto m = std::get_if<WeightMode C::*>(&k.field)) c.*(*m) = parse_mode(file, k.name, node);
  if (auto b = std::get_if<bool C::*>(&k.field)) c.*(*b) = read<bool>(file, k.name, node, "true or false");
}

// faults: {correction_offset: {at_s, duration_s, east_m}} (CorrectionFault).
void parse_faults(const std::string& file, const YAML::Node& node, C& c) {
  if (!node.IsMap()) bad(file, line_of(node), "faults", "expected a mapping (known: correction_offset)");
  for (const auto& fault : node) {
    const std::string name = fault.first.as<std::string>();
    const std::string key = "faults." + name;
    if (name != "correction_offset") bad(file, line_of(fault.first), key, "unknown key (known: correction_offset)");
    if (!fault.second.IsMap()) bad(file, line_of(fault.second), key, "expected a mapping of at_s, duration_s, east_m");
    CorrectionFault& f = c.fault_correction_offset;
    for (const auto& field : fault.second) {
      const std::string sub = field.first.as<std::string>();
      double* target = sub == "at_s" ? &f.at_s : sub == "duration_s" ? &f.duration_s : sub == "east_m" ? &f.east_m : nullptr;
      if (!target) bad(file, line_of(field.first), key + "." + sub, "unknown key (known: at_s, duration_s, east_m)");
      *target = read<double>(file, key + "." + sub, field.second, "a number");
    }
  }
}

std::string known_keys() {
  std::string s;
  for (const Key& k : keys()) s += (s.empty() ? "" : ", ") + std::string(k.name);
  return s;
}

void check(bool ok, const std::string& source, const char* key, const std::string& what, double got) {
  if (!ok) bad(source, 0, key, what + ", got " + std::to_string(got));
}

}  // namespace

const char* weight_mode_name(WeightMode mode) {
  switch (mode) {
    case WeightMode::kPaper: return "paper";
    case WeightMode::kAdaptive: return "adaptive";
    case WeightMode::kFixed: return "fixed";
  }
  return "?";
}

void RegistrationConfig::validate(const std::string& s) const {
  const auto pos = [](double v) { return std::isfinite(v) && v > 0.0; };
  const auto nonneg = [](double v) { return std::isfinite(v) && v >= 0.0; };
  check(nonneg(min_quality) && min_quality <= 1.0, s, "min_quality", "must lie in [0, 1]", min_quality);
  check(nonneg(voxel_size_m), s, "voxel_size_m", "must be >= 0 m", voxel_size_m);
  check(outlier_neighbors >= 0 && outlier_neighbors <= 32, s, "outlier_neighbors", "must be in [0, 32]",
        outlier_neighbors);
  check(pos(outlier_stddev), s, "outlier_stddev", "must be > 0", outlier_stddev);
  check(min_points >= 6, s, "min_points", "must be >= 6 (6 unknowns)", min_points);
  check(nonneg(surface_sigma_m), s, "surface_sigma_m", "must be >= 0 m", surface_sigma_m);
  check(threads >= 1 && threads <= 256, s, "threads", "must be in [1, 256]", threads);
  check(max_iterations >= 1, s, "max_iterations", "must be >= 1", max_iterations);
  check(pos(initial_threshold_m), s, "initial_threshold_m", "must be > 0 m", initial_threshold_m);
  check(nonneg(initial_threshold_sigmas), s, "initial_threshold_sigmas", "must be >= 0", initial_threshold_sigmas);
  check(max_initial_threshold_m >= initial_threshold_m, s, "max_initial_threshold_m", "must be >= initial_threshold_m",
        max_initial_threshold_m);
  check(pos(min_threshold_m) && min_threshold_m <= initial_threshold_m, s, "min_threshold_m",
        "must lie in (0, initial_threshold_m] m", min_threshold_m);
  check(pos(threshold_sigmas), s, "threshold_sigmas", "must be > 0", threshold_sigmas);
  check(pos(convergence_translation_m), s, "convergence_translation_m", "must be > 0 m", convergence_translation_m);
  check(pos(convergence_rotation_deg), s, "convergence_rotation_deg", "must be > 0 deg", convergence_rotation_deg);
  check(pos(yaw_search_min_sigma_deg), s, "yaw_search_min_sigma_deg", "must be > 0 deg", yaw_search_min_sigma_deg);
  check(pos(yaw_search_step_deg), s, "yaw_search_step_deg", "must be > 0 deg", yaw_search_step_deg);
  check(nonneg(yaw_search_max_deg) && yaw_search_max_deg <= 90.0, s, "yaw_search_max_deg", "must lie in [0, 90] deg",
        yaw_search_max_deg);
  check(std::isfinite(yaw_search_ambiguity) && yaw_search_ambiguity > 0.0 && yaw_search_ambiguity <= 1.0, s,
        "yaw_search_ambiguity", "must lie in (0, 1]", yaw_search_ambiguity);
  check(nonneg(scale_prior_walk), s, "scale_prior_walk", "must be >= 0 /sqrt(s) (0: off)", scale_prior_walk);
  check(pos(scale_prior_measurement_sigma), s, "scale_prior_measurement_sigma", "must be > 0",
        scale_prior_measurement_sigma);
  check(pos(scale_prior_max_heading_sigma_deg), s, "scale_prior_max_heading_sigma_deg", "must be > 0 deg",
        scale_prior_max_heading_sigma_deg);
  check(pos(scale_prior_max_position_sigma_m), s, "scale_prior_max_position_sigma_m", "must be > 0 m",
        scale_prior_max_position_sigma_m);
  check(pos(paper_beta), s, "paper_beta", "must be > 0", paper_beta);
  check(std::isfinite(correlation_inflation) && correlation_inflation >= 1.0, s, "correlation_inflation",
        "must be >= 1", correlation_inflation);
  check(pos(min_sigma_m), s, "min_sigma_m", "must be > 0 m", min_sigma_m);
  check(nonneg(degeneracy_threshold) && degeneracy_threshold < 1.0, s, "degeneracy_threshold", "must lie in [0, 1)",
        degeneracy_threshold);
  check(nonneg(surface_error_m), s, "surface_error_m", "must be >= 0 m (0: off)", surface_error_m);
  check(pos(surface_group_angle_deg) && surface_group_angle_deg < 90.0, s, "surface_group_angle_deg",
        "must lie in (0, 90) deg", surface_group_angle_deg);
  check(pos(surface_group_offset_m), s, "surface_group_offset_m", "must be > 0 m", surface_group_offset_m);
  check(pos(fixed_rotation_information), s, "fixed_rotation_information", "must be > 0", fixed_rotation_information);
  check(pos(fixed_translation_information), s, "fixed_translation_information", "must be > 0",
        fixed_translation_information);
  check(min_inliers >= 6, s, "min_inliers", "must be >= 6 (6 unknowns)", min_inliers);
  check(nonneg(min_fitness) && min_fitness <= 1.0, s, "min_fitness", "must lie in [0, 1]", min_fitness);
  check(pos(max_rmse_m), s, "max_rmse_m", "must be > 0 m", max_rmse_m);
  check(max_zero_directions >= 0 && max_zero_directions <= 6, s, "max_zero_directions", "must lie in [0, 6]",
        max_zero_directions);
  check(nonneg(max_position_sigma_m), s, "max_position_sigma_m", "must be >= 0 m (0: off)", max_position_sigma_m);
  check(pos(max_mahalanobis_sq), s, "max_mahalanobis_sq", "must be > 0", max_mahalanobis_sq);
  check(nonneg(mahalanobis_floor_m), s, "mahalanobis_floor_m", "must be >= 0 m", mahalanobis_floor_m);
  check(nonneg(mahalanobis_floor_deg), s, "mahalanobis_floor_deg", "must be >= 0 deg", mahalanobis_floor_deg);
  check(persistent_corrections >= 0 && persistent_corrections <= 100, s, "persistent_corrections",
        "must lie in [0, 100] (0: off)", persistent_corrections);
  check(pos(persistent_tolerance_m), s, "persistent_tolerance_m", "must be > 0 m", persistent_tolerance_m);
  check(pos(persistent_tolerance_deg), s, "persistent_tolerance_deg", "must be > 0 deg", persistent_tolerance_deg);
  check(nonneg(persistent_tolerance_fraction) && persistent_tolerance_fraction < 1.0, s,
        "persistent_tolerance_fraction", "must lie in [0, 1)", persistent_tolerance_fraction);
  // > 0: refusals older than 2 spans are forgotten, so a span of 0 would keep runs of one and silently turn it off
  check(pos(persistent_span_s), s, "persistent_span_s", "must be > 0 s", persistent_span_s);
  check(nonneg(acquisition_heading_sigma_deg), s, "acquisition_heading_sigma_deg", "must be >= 0 deg (0: off)",
        acquisition_heading_sigma_deg);
  check(nonneg(acquisition_min_correction_m), s, "acquisition_min_correction_m", "must be >= 0 m",
        acquisition_min_correction_m);
  check(nonneg(acquisition_min_correction_deg), s, "acquisition_min_correction_deg", "must be >= 0 deg",
        acquisition_min_correction_deg);
  check(acquisition_corrections >= 1 && acquisition_corrections <= 100, s, "acquisition_corrections",
        "must lie in [1, 100]", acquisition_corrections);
  const CorrectionFault& f = fault_correction_offset;
  check(std::isfinite(f.at_s), s, "faults.correction_offset.at_s", "must be finite (< 0: off)", f.at_s);
  check(nonneg(f.duration_s), s, "faults.correction_offset.duration_s", "must be >= 0 s", f.duration_s);
  check(std::isfinite(f.east_m), s, "faults.correction_offset.east_m", "must be finite [m]", f.east_m);
  check(pos(acquisition_span_s) && acquisition_span_s <= 2.0 * persistent_span_s, s, "acquisition_span_s",
        "must be > 0 s and at most 2 x persistent_span_s (older votes are forgotten)", acquisition_span_s);
}

bool CorrectionFault::contains(std::int64_t keyframe_stamp_ns, std::int64_t first_stamp_ns) const {
  if (at_s < 0.0) return false;
  const double t_s = 1e-9 * static_cast<double>(keyframe_stamp_ns - first_stamp_ns);
  return t_s >= at_s && t_s < at_s + duration_s;
}

RegistrationConfig parse_registration_config(const std::string& text, const std::string& file,
                                             const RegistrationConfig& base) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(where(file, static_cast<std::size_t>(e.mark.line + 1), "malformed YAML: " + e.msg));
  }
  RegistrationConfig config = base;
  if (root.IsNull()) return config;
  if (!root.IsMap()) throw InputError(where(file, 0, "expected a YAML mapping of registration keys"));
  for (const auto& item : root) {
    const std::string key = item.first.as<std::string>();
    if (key == "faults") {
      parse_faults(file, item.second, config);
      continue;
    }
    const Key* found = nullptr;
    for (const Key& k : keys()) found = (key == k.name) ? &k : found;
    if (!found) bad(file, line_of(item.first), key, "unknown key (known: " + known_keys() + ", faults)");
    set(config, *found, file, item.second);
  }
  return config;
}

RegistrationConfig load_registration_config(const std::string& path, const RegistrationConfig& base) {
  std::ifstream in(path);
  if (!in) throw InputError(where(path, 0, "cannot open file"));
  std::stringstream text;
  text << in.rdbuf();
  return parse_registration_config(text.str(), path, base);
}

}  // namespace twinslam::registration

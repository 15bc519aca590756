// RegistrationConfig: the shipped default file equals the defaults, and every YAML mistake names file, line and key.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "twinslam/core/error.hpp"
#include "twinslam/registration/registration_config.hpp"

namespace twinslam::registration {
namespace {

std::string message(const std::string& text) {
  try {
    parse_registration_config(text, "r.yaml").validate("r.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(RegistrationConfig, DeployedDefaultFileLoadsAndEqualsTheDefaults) {
  const std::string path = std::string(TWINSLAM_SOURCE_DIR) + "/deploy/config/registration.yaml";
  const RegistrationConfig loaded = load_registration_config(path);
  EXPECT_NO_THROW(loaded.validate(path));
  EXPECT_TRUE(loaded == RegistrationConfig{});
  // The file spells out every key: changing one value there changes the config (the file is not ignored).
  RegistrationConfig base;
  base.max_iterations = 7;
  EXPECT_EQ(load_registration_config(path, base).max_iterations, RegistrationConfig{}.max_iterations);
}

TEST(RegistrationConfig, ParsesValuesOverBase) {
  const RegistrationConfig c =
      parse_registration_config("weights: paper\nmax_iterations: 12\nvoxel_size_m: 0.5\n", "r.yaml");
  EXPECT_EQ(c.weights, WeightMode::kPaper);
  EXPECT_EQ(c.max_iterations, 12);
  EXPECT_DOUBLE_EQ(c.voxel_size_m, 0.5);
  EXPECT_EQ(c.min_points, RegistrationConfig{}.min_points);  // untouched keys keep the base
  EXPECT_EQ(parse_registration_config("weights: fixed\n", "r.yaml").weights, WeightMode::kFixed);
}

TEST(RegistrationConfig, ErrorsNameFileLineAndKey) {
  EXPECT_EQ(message("max_iteration: 3\n").rfind("r.yaml:1: registration key 'max_iteration': unknown key (known: ", 0),
            0u);
  EXPECT_EQ(message("min_points: 5\nmax_iterations: many\n"),
            "r.yaml:2: registration key 'max_iterations': expected an integer");
  EXPECT_EQ(message("weights: robust\n"),
            "r.yaml:1: registration key 'weights': expected paper, adaptive or fixed, got 'robust'");
  EXPECT_EQ(message("min_quality: 1.5\n"), "r.yaml: registration key 'min_quality': must lie in [0, 1], got 1.500000");
  EXPECT_EQ(message("min_threshold_m: 5\n"),
            "r.yaml: registration key 'min_threshold_m': must lie in (0, initial_threshold_m] m, got 5.000000");
  EXPECT_EQ(message("correlation_inflation: 0.5\n"),
            "r.yaml: registration key 'correlation_inflation': must be >= 1, got 0.500000");
  EXPECT_EQ(message("persistent_corrections: -1\n"),
            "r.yaml: registration key 'persistent_corrections': must lie in [0, 100] (0: off), got -1.000000");
  EXPECT_EQ(message("scale_prior_walk: -0.1\n"),
            "r.yaml: registration key 'scale_prior_walk': must be >= 0 /sqrt(s) (0: off), got -0.100000");
  EXPECT_EQ(message("scale_prior_measurement_sigma: 0\n"),
            "r.yaml: registration key 'scale_prior_measurement_sigma': must be > 0, got 0.000000");
  EXPECT_EQ(message("scale_prior_max_heading_sigma_deg: 0\n"),
            "r.yaml: registration key 'scale_prior_max_heading_sigma_deg': must be > 0 deg, got 0.000000");
  EXPECT_EQ(message("scale_prior_max_position_sigma_m: -1\n"),
            "r.yaml: registration key 'scale_prior_max_position_sigma_m': must be > 0 m, got -1.000000");
  EXPECT_EQ(message("- a\n- b\n"), "r.yaml: expected a YAML mapping of registration keys");
  EXPECT_NE(message("a: [1,\n").find("r.yaml:"), std::string::npos);  // malformed YAML names the file
  EXPECT_EQ(message(""), "no error");
}

// faults.correction_offset (issue 15): a wrong registration on purpose, for the estimator's gate to meet.
TEST(RegistrationConfig, TheCorrectionOffsetFaultParsesAndCountsFromTheFirstLocalMap) {
  const RegistrationConfig c = parse_registration_config(
      "faults:\n  correction_offset: {at_s: 23, duration_s: 3, east_m: 20}\n", "r.yaml");
  const CorrectionFault& f = c.fault_correction_offset;
  EXPECT_DOUBLE_EQ(f.at_s, 23.0);
  const std::int64_t first = 1'000'000'000'500'000'000;
  EXPECT_FALSE(f.contains(first + 22'900'000'000, first));
  EXPECT_TRUE(f.contains(first + 23'000'000'000, first));
  EXPECT_TRUE(f.contains(first + 25'900'000'000, first));
  EXPECT_FALSE(f.contains(first + 26'000'000'000, first));
  EXPECT_FALSE(RegistrationConfig{}.fault_correction_offset.contains(first + 23'000'000'000, first));  // off
  EXPECT_EQ(message("faults:\n  correction_offset: {at_s: 1, east: 3}\n"),
            "r.yaml:2: registration key 'faults.correction_offset.east': unknown key (known: at_s, duration_s, east_m)");
  EXPECT_EQ(message("faults:\n  registration_nan: {at_s: 1}\n"),
            "r.yaml:2: registration key 'faults.registration_nan': unknown key (known: correction_offset)");
  EXPECT_EQ(message("faults: 3\n"), "r.yaml:1: registration key 'faults': expected a mapping (known: correction_offset)");
  EXPECT_EQ(message("faults: {correction_offset: {at_s: 1, duration_s: -2}}\n"),
            "r.yaml: registration key 'faults.correction_offset.duration_s': must be >= 0 s, got -2.000000");
  EXPECT_EQ(message("faults: {correction_offset: {at_s: 1, east_m: twenty}}\n"),
            "r.yaml:1: registration key 'faults.correction_offset.east_m': expected a number");
}

TEST(RegistrationConfig, MissingFileNamesIt) {
  try {
    load_registration_config("/nonexistent/registration.yaml");
    FAIL() << "no throw";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/registration.yaml: cannot open file");
  }
}

}  // namespace
}  // namespace twinslam::registration

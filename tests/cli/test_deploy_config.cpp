// deploy/config/*.yaml stay true: each file sets every key its loader knows, to the code's default, and every loader
// turns bad input into a one-line InputError naming the file and the key.
#include <filesystem>
#include <fstream>
#include <functional>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "estimator_config.hpp"
#include "tracking_config.hpp"
#include "twinslam/bridge/bridge_config.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/core/yaml_fields.hpp"
#include "twinslam/ingest/ingest_config.hpp"
#include "twinslam/tiles/tiles_config.hpp"

namespace fs = std::filesystem;
using namespace twinslam;

namespace {

const fs::path kConfigDir = fs::path(TWINSLAM_SOURCE_DIR) / "deploy/config";

using Values = std::vector<std::pair<std::string, std::string>>;

// One service's file: its loader, and the key/value list of a config (default or loaded) through its bind function.
struct Service {
  std::string file;
  std::function<Values()> defaults;
  std::function<Values(const fs::path&)> load;  // the real loader (with validation)
};

template <class Config>
Values values_of(Config config, void (*bind)(yaml::Fields&, Config&)) {
  yaml::Fields fields("check");
  bind(fields, config);
  return fields.values();
}

std::vector<Service> services() {
  using estimator::EstimatorServiceConfig;
  using tracking::TrackingNodeOptions;
  return {
      {"estimator.yaml", [] { return values_of(EstimatorServiceConfig{}, estimator::bind_estimator_service_config); },
       [](const fs::path& p) {
         return values_of(estimator::load_estimator_service_config(p.string()),
                          estimator::bind_estimator_service_config);
       }},
      {"tracking.yaml", [] { return values_of(TrackingNodeOptions{}, tracking::bind_tracking_config); },
       [](const fs::path& p) {
         return values_of(tracking::load_tracking_config(p.string()), tracking::bind_tracking_config);
       }},
      {"tiles.yaml", [] { return values_of(tiles::TilesConfig{}, tiles::bind_tiles_config); },
       [](const fs::path& p) { return values_of(tiles::load_tiles_config(p.string()), tiles::bind_tiles_config); }},
      {"ingest.yaml", [] { return values_of(ingest::IngestConfig{}, ingest::bind_ingest_config); },
       [](const fs::path& p) {
         return values_of(ingest::load_ingest_config(p.string()), ingest::bind_ingest_config);
       }},
      {"bridge.yaml", [] { return values_of(bridge::BridgeConfig{}, bridge::bind_bridge_config); },
       [](const fs::path& p) {
         return values_of(bridge::load_bridge_config(p.string()), bridge::bind_bridge_config);
       }},
  };
}

// "a.b" looked up in a parsed document.
bool has_key(const YAML::Node& root, const std::string& key) {
  const auto dot = key.find('.');
  if (dot == std::string::npos) return static_cast<bool>(root[key]);
  const YAML::Node inner = root[key.substr(0, dot)];
  return inner && inner.IsMap() && has_key(inner, key.substr(dot + 1));
}

std::string error_of(const Service& s, const std::string& text) {
  const fs::path file = fs::temp_directory_path() / ("twinslam_cfg_" + std::to_string(::getpid()) + "_" + s.file);
  std::ofstream(file) << text;
  std::string message = "no error";
  try {
    s.load(file);
  } catch (const InputError& e) {
    message = e.what();
  }
  fs::remove(file);
  // The temp path differs per run: report it as the bare file name.
  if (message.rfind(file.string(), 0) == 0) message = s.file + message.substr(file.string().size());
  return message;
}

}  // namespace

TEST(DeployConfig, EveryFileSetsEveryKeyToTheCodeDefault) {
  for (const auto& s : services()) {
    SCOPED_TRACE(s.file);
    const fs::path path = kConfigDir / s.file;
    ASSERT_TRUE(fs::exists(path));
    const Values defaults = s.defaults(), loaded = s.load(path);
    ASSERT_EQ(loaded.size(), defaults.size());
    const YAML::Node root = YAML::LoadFile(path.string());
    for (std::size_t i = 0; i < defaults.size(); ++i) {
      EXPECT_EQ(loaded[i], defaults[i]) << "key " << defaults[i].first;
      EXPECT_TRUE(has_key(root, defaults[i].first)) << defaults[i].first << " is not documented in " << s.file;
    }
  }
}

TEST(DeployConfig, EstimatorFileMatchesTheNodeAndLockstepDefaults) {
  // The values that used to be literals in the estimator's main and node header.
  const auto c = estimator::load_estimator_service_config((kConfigDir / "estimator.yaml").string());
  EXPECT_EQ(c.options.imu_wait, estimator::EstimatorNodeOptions{}.imu_wait);
  EXPECT_EQ(c.for_replay(true).estimator.max_solver_time_s, 1.0);
  EXPECT_EQ(c.for_replay(false).estimator.max_solver_time_s, estimator::SlidingWindowConfig{}.max_solver_time_s);
}

TEST(DeployConfig, MalformedYamlNamesTheFileAndLine) {
  for (const auto& s : services()) {
    const std::string e = error_of(s, "a: 1\nb: [1, 2\n");
    EXPECT_EQ(e.rfind(s.file + ":", 0), 0u) << e;
    EXPECT_NE(e.find("malformed YAML"), std::string::npos) << e;
  }
}

TEST(DeployConfig, UnknownKeyIsNamedWithTheKnownOnes) {
  for (const auto& s : services()) {
    const std::string e = error_of(s, "no_such_key: 1\n");
    EXPECT_EQ(e.rfind(s.file + ":1: ", 0), 0u) << e;
    EXPECT_NE(e.find("key 'no_such_key': unknown key (known: "), std::string::npos) << e;
  }
  EXPECT_EQ(error_of(services()[0], "keyframe:\n  min_parallax_px: 3\n"),
            "estimator.yaml:2: estimator key 'keyframe.min_parallax_px': unknown key (known: min_mean_parallax_px, "
            "min_tracked_ratio)");
}

TEST(DeployConfig, WrongTypeNamesFileLineAndKey) {
  const auto s = services();
  EXPECT_EQ(error_of(s[0], "window_keyframes: eight\n"),
            "estimator.yaml:1: estimator key 'window_keyframes': expected an integer");
  EXPECT_EQ(error_of(s[0], "motion_init:\n  window_s: long\n"),
            "estimator.yaml:2: estimator key 'motion_init.window_s': expected a number [s]");
  EXPECT_EQ(error_of(s[0], "node:\n  imu_wait_ms: 0.5\n"),
            "estimator.yaml:2: estimator key 'node.imu_wait_ms': expected an integer [ms]");
  EXPECT_EQ(error_of(s[1], "ransac_model: lmeds\n"),
            "tracking.yaml:1: tracking key 'ransac_model': expected one of essential | known_rotation, got lmeds");
  EXPECT_EQ(error_of(s[1], "min_distance_px: .nan\n"),
            "tracking.yaml:1: tracking key 'min_distance_px': expected a finite number, got .nan");
  EXPECT_EQ(error_of(s[2], "window_m: wide\n"), "tiles.yaml:1: tiles key 'window_m': expected a number [m]");
  EXPECT_EQ(error_of(s[3], "ack_timeout_s: soon\n"),
            "ingest.yaml:1: ingest key 'ack_timeout_s': expected a number [s]");
}

TEST(DeployConfig, OutOfRangeNamesFileAndKey) {
  const auto s = services();
  EXPECT_EQ(error_of(s[0], "window_keyframes: 1\n"), "estimator.yaml: sliding_window.window_keyframes: must be >= 2");
  EXPECT_EQ(error_of(s[0], "motion_init:\n  min_span_s: 3.0\n"),
            "estimator.yaml: motion_init.min_span_s: must be <= window_s");
  EXPECT_EQ(error_of(s[0], "world_alignment_random_walk_deg: -0.1\n"),
            "estimator.yaml: sliding_window.world_alignment_random_walk_deg: must be in [0, 10] deg/sqrt(s) (0: T_WL "
            "constant)");
  EXPECT_EQ(error_of(s[0], "world_alignment_random_walk_m: 12\n"),
            "estimator.yaml: sliding_window.world_alignment_random_walk_m: must be in [0, 10] m/sqrt(s) (0: T_WL "
            "constant)");
  EXPECT_EQ(error_of(s[0], "world_alignment_random_walk_m: .nan\n"),
            "estimator.yaml:1: estimator key 'world_alignment_random_walk_m': expected a finite number, got .nan");
  EXPECT_EQ(error_of(s[0], "node:\n  lockstep_max_solver_time_s: 0\n"),
            "estimator.yaml: estimator key 'node.lockstep_max_solver_time_s': must be > 0");
  EXPECT_EQ(error_of(s[1], "klt_window_px: 4\n"),
            "tracking.yaml: tracking key 'klt_window_px': must be odd and >= 5, got 4");
  EXPECT_EQ(error_of(s[3], "speed: 0\n"), "ingest.yaml: ingest key 'speed': must lie in (0, 1000], got 0");
}

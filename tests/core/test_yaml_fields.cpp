// yaml::Fields: a config struct read from YAML one line per key, every bad input a one-line InputError naming the
// file, the line and the key.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "twinslam/core/error.hpp"
#include "twinslam/core/yaml_fields.hpp"

using namespace twinslam;

namespace {

enum class Model { kFast, kExact };

struct Demo {
  double speed_mps = 2.0;
  int count = 3;
  unsigned seed = 42;
  bool enabled = false;
  std::string path = "default";
  std::chrono::milliseconds wait{100};
  Model model = Model::kFast;
  double inner_m = 1.0;
};

yaml::Fields bind(Demo& d) {
  yaml::Fields f("demo");
  f.number("speed_mps", d.speed_mps, "m/s")
      .integer("count", d.count)
      .count("seed", d.seed)
      .flag("enabled", d.enabled)
      .text("path", d.path, "a path")
      .milliseconds("wait_ms", d.wait)
      .choice("model", d.model, {{"fast", Model::kFast}, {"exact", Model::kExact}});
  f.section("inner").number("inner_m", d.inner_m, "m");
  return f;
}

std::string error_of(const std::string& text) {
  Demo d;
  try {
    bind(d).parse(text, "f.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(YamlFields, AssignsTheKeysGivenAndKeepsTheOthers) {
  Demo d;
  bind(d).parse("speed_mps: 4.5\nenabled: true\nmodel: exact\nwait_ms: 250\ninner:\n  inner_m: 7\n", "f.yaml");
  EXPECT_EQ(d.speed_mps, 4.5);
  EXPECT_TRUE(d.enabled);
  EXPECT_EQ(d.model, Model::kExact);
  EXPECT_EQ(d.wait, std::chrono::milliseconds(250));
  EXPECT_EQ(d.inner_m, 7.0);
  EXPECT_EQ(d.count, 3);  // not in the file: default kept
  EXPECT_EQ(d.path, "default");
  Demo empty;
  bind(empty).parse("", "f.yaml");
  EXPECT_EQ(empty.speed_mps, 2.0);
}

TEST(YamlFields, BadInputNamesFileLineAndKey) {
  EXPECT_EQ(error_of("count: 1\nspeed_mps: fast\n"), "f.yaml:2: demo key 'speed_mps': expected a number [m/s]");
  EXPECT_EQ(error_of("count: 1.5\n"), "f.yaml:1: demo key 'count': expected an integer");
  EXPECT_EQ(error_of("speed_mps: .nan\n"), "f.yaml:1: demo key 'speed_mps': expected a finite number, got .nan");
  EXPECT_EQ(error_of("seed: -1\n"), "f.yaml:1: demo key 'seed': expected a non-negative integer");
  EXPECT_EQ(error_of("enabled: maybe\n"), "f.yaml:1: demo key 'enabled': expected true or false");
  EXPECT_EQ(error_of("model: slow\n"), "f.yaml:1: demo key 'model': expected one of fast | exact, got slow");
  EXPECT_EQ(error_of("speed_mps: [1, 2]\n"), "f.yaml:1: demo key 'speed_mps': expected a number [m/s]");
  EXPECT_EQ(error_of("sped_mps: 1\n"),
            "f.yaml:1: demo key 'sped_mps': unknown key (known: speed_mps, count, seed, enabled, path, wait_ms, "
            "model, inner)");
  EXPECT_EQ(error_of("inner:\n  outer_m: 1\n"), "f.yaml:2: demo key 'inner.outer_m': unknown key (known: inner_m)");
  EXPECT_EQ(error_of("inner:\n  inner_m: x\n"), "f.yaml:2: demo key 'inner.inner_m': expected a number [m]");
  EXPECT_EQ(error_of("inner: 3\n"), "f.yaml:1: demo key 'inner': expected a mapping of inner keys");
  EXPECT_EQ(error_of("- 1\n- 2\n"), "f.yaml: expected a YAML mapping of demo keys");
  EXPECT_EQ(error_of("count: 1\nspeed_mps: [1, 2\n").rfind("f.yaml:", 0), 0u);
  EXPECT_NE(error_of("count: 1\nspeed_mps: [1, 2\n").find("malformed YAML"), std::string::npos);
}

TEST(YamlFields, MissingFileIsNamed) {
  Demo d;
  try {
    bind(d).load("/nonexistent/demo.yaml");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/demo.yaml: cannot open file");
  }
}

TEST(YamlFields, ValuesListEveryKeyAndRoundTrip) {
  Demo d;
  d.speed_mps = 0.1;  // not exactly representable: the text must still give the same double back
  d.model = Model::kExact;
  std::string text;
  for (const auto& [key, value] : bind(d).values()) {
    const auto dot = key.find('.');
    text += dot == std::string::npos ? key + ": " + value + "\n"
                                     : key.substr(0, dot) + ":\n  " + key.substr(dot + 1) + ": " + value + "\n";
  }
  EXPECT_NE(text.find("inner:\n  inner_m: 1\n"), std::string::npos) << text;
  Demo back;
  bind(back).parse(text, "round.yaml");
  EXPECT_EQ(back.speed_mps, 0.1);
  EXPECT_EQ(back.model, Model::kExact);
  EXPECT_EQ(bind(back).values(), bind(d).values());
}

TEST(YamlFields, ChangedValuesListOnlyTheKeysThatDiffer) {
  Demo defaults, d;
  EXPECT_EQ(yaml::changed_values(bind(d).values(), bind(defaults).values()), "all defaults");
  d.count = 5;
  d.inner_m = 2.5;
  EXPECT_EQ(yaml::changed_values(bind(d).values(), bind(defaults).values()), "count=5, inner.inner_m=2.5");
}

// Simulator scenario YAML (twinslam sim --scenario FILE.yaml), parsed and validated.
#include <cstddef>
#include <cstdint>

#include "harness.hpp"
#include <string>
#include "twinslam/sim/scenario_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace twinslam;
  const std::string text(reinterpret_cast<const char*>(data), size);
  return fuzz::expect_input_error_only([&] {
    const sim::Scenario s = sim::parse_scenario_yaml(text, "fuzz.yaml");
    sim::validate_scenario(s, "fuzz.yaml");
  });
}

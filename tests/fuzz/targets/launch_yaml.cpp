// twinslam launch files (deploy/*.yaml).
#include <cstddef>
#include <cstdint>

#include "harness.hpp"
#include "launch_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace twinslam;
  const auto path = fuzz::write_scratch("launch.yaml", data, size);
  return fuzz::expect_input_error_only([&] { cli::load_launch_file(path); });
}

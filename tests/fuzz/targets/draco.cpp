// Draco-compressed tile bytes (what a MapTile carries over DDS) decoded into a mesh or point set.
#include <cstddef>
#include <cstdint>

#include "harness.hpp"
#include "twinslam/twin/store.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace twinslam;
  return fuzz::expect_input_error_only([&] { twin::decode_draco(data, size, "fuzz tile"); });
}

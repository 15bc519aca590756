// 3D Tiles Batched 3D Model: header (current and legacy), feature and batch tables, embedded glb; both checks.
#include <cstddef>
#include <cstdint>

#include "harness.hpp"
#include "twinslam/twin/b3dm.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace twinslam;
  return fuzz::expect_input_error_only([&] {
    twin::parse_b3dm(data, size, "fuzz.b3dm", size % 2 ? twin::B3dmCheck::kStrict : twin::B3dmCheck::kLenient);
  });
}

// PLY meshes and point clouds (ascii, binary little / big endian).
#include <cstddef>
#include <cstdint>

#include "harness.hpp"
#include "twinslam/twin/ply.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace twinslam;
  const auto path = fuzz::write_scratch("twin.ply", data, size);
  return fuzz::expect_input_error_only([&] { twin::read_ply(path.string()); });
}

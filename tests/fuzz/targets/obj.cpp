// Wavefront OBJ meshes.
#include <cstddef>
#include <cstdint>

#include "harness.hpp"
#include "twinslam/twin/obj.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace twinslam;
  const auto path = fuzz::write_scratch("twin.obj", data, size);
  return fuzz::expect_input_error_only([&] { twin::read_obj(path.string()); });
}

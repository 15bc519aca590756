// glTF 2.0: binary glb or JSON glTF with embedded (data:) buffers, incl. KHR_draco_mesh_compression, CESIUM_RTC.
#include <cstddef>
#include <cstdint>

#include "harness.hpp"
#include "twinslam/twin/gltf.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace twinslam;
  return fuzz::expect_input_error_only([&] { twin::load_gltf_content(data, size, "fuzz.glb"); });
}

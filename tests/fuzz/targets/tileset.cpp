// 3D Tiles tileset.json (1.0 / 1.1 / pre-1.0 quirks), with an external tileset: parts tileset.json, ext.json.
#include <cstddef>
#include <cstdint>

#include "harness.hpp"
#include "twinslam/twin/tiles3d.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace twinslam;
  const auto parts = fuzz::split_parts(data, size, 2);
  const auto path = fuzz::write_scratch("ts/tileset.json", parts[0]);
  fuzz::write_scratch("ts/ext.json", parts.size() > 1 ? parts[1] : std::string_view("{}"));
  return fuzz::expect_input_error_only([&] {
    twin::LoadOptions options;
    options.origin = twin::GeoOrigin{40.0425, -75.6114, 0.0};
    options.strict = size % 2;
    twin::LoadReport report;
    twin::load_3dtiles(path.string(), options, &report);
  });
}

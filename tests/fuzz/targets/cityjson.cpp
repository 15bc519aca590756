// CityJSON 1.0-2.0 (transform, geometry types, holes, metadata CRS).
#include <cstddef>
#include <cstdint>

#include "harness.hpp"
#include "twinslam/twin/cityjson.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace twinslam;
  const auto path = fuzz::write_scratch("city.json", data, size);
  return fuzz::expect_input_error_only([&] {
    twin::LoadOptions options;
    options.origin = twin::GeoOrigin{52.0116, 4.3571, 0.0};
    options.crs = "EPSG:7415";
    twin::LoadReport report;
    twin::load_cityjson(path.string(), options, &report);
  });
}

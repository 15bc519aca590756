// OpenStreetMap XML buildings (ways, multipolygon relations, height / levels tags).
#include <cstddef>
#include <cstdint>

#include "harness.hpp"
#include "twinslam/twin/osm.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace twinslam;
  const auto path = fuzz::write_scratch("map.osm", data, size);
  return fuzz::expect_input_error_only([&] {
    twin::LoadOptions options;
    options.origin = twin::GeoOrigin{52.0116, 4.3571, 0.0};
    twin::LoadReport report;
    twin::load_osm(path.string(), options, &report);
  });
}

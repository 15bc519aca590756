// One 3D Tiles content file as the tileset loader reads it: b3dm, glb, cmpt composites (nested), pnts / i3dm refused.
#include <cstddef>
#include <cstdint>

#include "harness.hpp"
#include "twinslam/twin/tiles3d.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace twinslam;
  static const twin::EnuFrame enu(twin::GeoOrigin{40.0425, -75.6114, 0.0});
  const auto path = fuzz::write_scratch("content.cmpt", data, size);
  return fuzz::expect_input_error_only([&] {
    twin::TileContentRef ref;
    ref.path = path.string();
    std::vector<std::uint32_t> ids;
    twin::BatchTable table;
    twin::LoadReport report;
    twin::load_tile_content(ref, enu, &ids, &table, &report);
  });
}

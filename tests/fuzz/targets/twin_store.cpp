// The tiled twin store: parts index.json, mesh Draco bytes, points Draco bytes (the latter two written for each of
// the first 4 tiles the index lists), read and decoded as the tiles service does.
#include <cstddef>
#include <cstdint>

#include "harness.hpp"
#include <filesystem>
#include "twinslam/twin/store.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace twinslam;
  const auto parts = fuzz::split_parts(data, size, 3);
  const std::filesystem::path dir = fuzz::scratch_dir() / "store";
  std::filesystem::remove_all(dir);
  fuzz::write_scratch("store/index.json", parts[0]);
  return fuzz::expect_input_error_only([&] {
    const twin::TwinIndex index = twin::read_twin_index(dir.string());
    std::size_t loaded = 0;
    for (const twin::TileInfo& t : index.tiles) {
      if (++loaded > 4) break;
      fuzz::write_scratch("store/tiles/" + t.key.str() + ".mesh.drc", parts.size() > 1 ? parts[1] : "");
      fuzz::write_scratch("store/tiles/" + t.key.str() + ".points.drc", parts.size() > 2 ? parts[2] : "");
      twin::load_tile(dir.string(), index, t.key);
    }
  });
}

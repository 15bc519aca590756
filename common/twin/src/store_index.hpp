#pragma once
// index.json of a twin store (store.hpp): writing is internal to build_twin_store; reading is read_twin_index.
#include <string>

#include "twinslam/twin/store.hpp"

namespace twinslam::twin {

inline constexpr int kTwinFormatVersion = 1;

// Writes TWIN_DIR/index.json through a temporary file and a rename, so a reader never sees half an index.
void write_twin_index(const TwinIndex& index, const std::string& twin_dir);

// File names of a tile relative to the twin folder: "tiles/<ix>_<iy>.mesh.drc" / ".points.drc".
std::string tile_file_name(const TileKey& key, bool points);

}  // namespace twinslam::twin

#pragma once
// Top-down picture of a twin store for `twinslam twin info --preview`: triangles filled and points dotted in a colour
// that follows height, tile boundaries as grey lines. Lives in tools/ (OpenCV) so common/twin stays free of it.
#include <string>

#include "twinslam/twin/store.hpp"

namespace twinslam::cli {

// Decodes every tile of the store and writes a PNG whose longer side is at most max_side_px. Returns its size
// (width, height) [px]. Throws InputError for unreadable tiles or an unwritable PNG.
std::pair<int, int> write_twin_preview(const std::string& twin_dir, const twin::TwinIndex& index,
                                       const std::string& png_path, int max_side_px = 1600);

}  // namespace twinslam::cli

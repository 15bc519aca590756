#pragma once
// OGC 3D Tiles 1.0 / 1.1 tilesets -> one Mesh in W.
// Tileset: `asset.version`, `root`, per tile `geometricError`, `boundingVolume` (box 12 / region 6 in radians and
// metres / sphere 4; parsed and validated, not used for selection), `transform` (column-major 4x4, chained
// parent * child; a referenced external tileset's root continues its referencing tile's chain), `refine`
// (ADD / REPLACE, inherited), `content.uri` (1.1) or `content.url` (1.0), 1.1 `contents` arrays, and external
// tilesets (content ending in .json).
// Level choice with tau = LoadOptions::max_geometric_error_m: descending from the root, a tile whose
// geometricError <= tau (or a leaf) contributes its content and stops the descent (the coarsest tiles good enough;
// tau = 0 gives the leaves); a coarser tile with REPLACE gives its place to its children, with ADD it keeps its own
// content and adds theirs. A tile whose content is an external tileset always descends into it.
// Content: b3dm, glb / glTF, and cmpt composites of these (recursively). pnts (point clouds), i3dm and implicit
// tiling are NOT loaded: each such tile (or inner tile) is listed in LoadReport::rejected with "not supported" so
// the user knows what is missing.
// Placement of a content vertex p (glTF model frame, y-up, node transforms applied), as the 3D Tiles spec orders it:
//   p_tile = Y_UP_TO_Z_UP * p  (+90 deg about X: (x, y, z) -> (x, -z, y))  + RTC_CENTER (b3dm, z-up)
//   p_ECEF = T_tile (accumulated transform) * p_tile;   p_W = EnuFrame(origin).from_ecef(p_ECEF)
// Content that fails (missing file, bad b3dm / glb, bad external tileset) goes into LoadReport::rejected with its
// reason and loading continues; a malformed top-level tileset.json throws InputError.
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "twinslam/twin/b3dm.hpp"
#include "twinslam/twin/geo.hpp"
#include "twinslam/twin/load.hpp"
#include "twinslam/twin/mesh.hpp"

namespace twinslam::twin {

// One selected renderable content of a tileset.
struct TileContentRef {
  std::string path;                                       // resolved file path
  Eigen::Matrix4d T_ECEF_tile = Eigen::Matrix4d::Identity();  // accumulated tile transform: tile frame -> ECEF
  double geometric_error = 0.0;                           // of the tile holding it [m]
};

// Walks the tileset (and its external tilesets) and returns the contents chosen for max_geometric_error_m.
// Throws InputError for a malformed top-level tileset; problems below it go to report->rejected. Quirks of pre-1.0
// tilesets (tiles3d_quirks.hpp: missing geometricError -> the parent's, missing asset.version, content.url, root
// without refine) are accepted with one line per quirk and file in report->warnings, or refused when strict.
std::vector<TileContentRef> select_3dtiles_contents(const std::string& tileset_json, double max_geometric_error_m,
                                                    LoadReport* report, bool strict = false);

// One content placed in W. batch_id (optional) receives the per-vertex batch ids of b3dm content (empty if none),
// batch_table the b3dm batch table (for a cmpt: those of its last b3dm, ids not offset: use them on b3dm content).
// Unsupported inner tiles of a cmpt are skipped with a line in report->rejected. Legacy / unpadded b3dm and
// CESIUM_RTC are accepted with a line in report->warnings, or refused when strict (then load_3dtiles fails as a
// whole). Throws InputError naming the file and problem.
Mesh load_tile_content(const TileContentRef& content, const EnuFrame& enu,
                       std::vector<std::uint32_t>* batch_id = nullptr, BatchTable* batch_table = nullptr,
                       LoadReport* report = nullptr, bool strict = false);

Mesh load_3dtiles(const std::string& tileset_json, const LoadOptions& options, LoadReport* report);

}  // namespace twinslam::twin

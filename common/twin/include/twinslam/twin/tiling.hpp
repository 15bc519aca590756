#pragma once
// The two geometric steps of the tiled store (store.hpp), exposed for tests and tools: cutting a mesh by the tile
// grid, and the area-uniform point sampling of a tile.
#include <cstdint>
#include <map>

#include "twinslam/twin/mesh.hpp"
#include "twinslam/twin/store.hpp"

namespace twinslam::twin {

// Tile of a W position (e, n) [m]: floor(e / size), floor(n / size). Throws InputError for a non-finite position or
// one so far from the origin that the index does not fit in an int (|index| > 1e8).
TileKey tile_of(double e_m, double n_m, double tile_size_m);

// Cuts every triangle by the grid lines e = k * size and n = k * size (Sutherland-Hodgman against each tile square it
// overlaps, the convex piece fanned into triangles; heights are never cut). Every piece lies inside its tile's closed
// square, no area is duplicated or lost (pieces of zero area are dropped), and a triangle lying exactly on a grid line
// (a facade in the plane e = k * size) goes to the tile on the line's east / north side, as the half-open tile
// ranges say. Vertices are shared within a tile where positions are bit-identical. Normals of the source are dropped.
std::map<TileKey, Mesh> cut_into_tiles(const Mesh& mesh_W, double tile_size_m);

// A point set with normals (no triangles) split by position; throws InputError if it has no normal per point.
std::map<TileKey, Mesh> split_points_into_tiles(const Mesh& points_W, double tile_size_m);

// Area-uniform points with the triangle's unit normal: per triangle floor(area / s^2) points plus one more with
// probability equal to the remainder, so the expected count is area / spacing^2 and small triangles are fair.
// Deterministic for (seed, stream): std::mt19937_64 with our own [0, 1) transform (no std distributions, whose
// output differs between standard libraries). The store passes the tile key as stream so tiles are independent.
Mesh sample_points(const Mesh& mesh_W, double spacing_m, std::uint64_t seed, std::uint64_t stream = 0);

}  // namespace twinslam::twin

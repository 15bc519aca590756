// Cutting a mesh by the tile grid (tiling.hpp): Sutherland-Hodgman clipping of each triangle against the squares of
// the tiles it overlaps, in (e, n) only, so a tile is a whole column.
#include <array>
#include <cmath>
#include <cstring>
#include <string>
#include <unordered_map>

#include "twinslam/core/error.hpp"
#include "twinslam/twin/tiling.hpp"

namespace twinslam::twin {
namespace {

using Polygon = std::vector<Eigen::Vector3d>;  // convex, planar (pieces of one triangle) [m, W]

// Keeps the part of `in` on one side of the line p[axis] = c. keep_above: p[axis] >= c (closed: the tile's west /
// south edge belongs to it); else p[axis] < c (open: its east / north edge belongs to the neighbour). A polygon lying
// on the line is thus kept by exactly one of the two tiles. Intersections are snapped onto the line exactly, so pieces
// of neighbouring tiles meet without gaps.
Polygon clip(const Polygon& in, int axis, double c, bool keep_above) {
  Polygon out;
  const auto inside = [&](const Eigen::Vector3d& p) { return keep_above ? p[axis] >= c : p[axis] < c; };
  for (std::size_t i = 0; i < in.size(); ++i) {
    const Eigen::Vector3d& p = in[i];
    const Eigen::Vector3d& q = in[(i + 1) % in.size()];
    const bool p_in = inside(p), q_in = inside(q);
    if (p_in) out.push_back(p);
    if (p_in != q_in) {  // the edge crosses the line: q[axis] != p[axis] here
      const double t = (c - p[axis]) / (q[axis] - p[axis]);
      Eigen::Vector3d x = p + t * (q - p);
      x[axis] = c;
      out.push_back(x);
    }
  }
  return out;
}

// Hash of a position's exact bits: vertices are shared only where they are bit-identical (clipping computes a cut
// point the same way for both pieces of an edge within a tile).
struct BitsHash {
  std::size_t operator()(const std::array<double, 3>& a) const {
    std::uint64_t h = 1469598103934665603ull;
    for (double d : a) {
      std::uint64_t bits;
      std::memcpy(&bits, &d, sizeof bits);
      h = (h ^ bits) * 1099511628211ull;
    }
    return static_cast<std::size_t>(h);
  }
};

struct TileBuilder {
  Mesh mesh;
  std::unordered_map<std::array<double, 3>, int, BitsHash> ids;

  int vertex(const Eigen::Vector3d& p) {
    const auto [it, added] = ids.try_emplace({p.x(), p.y(), p.z()}, static_cast<int>(mesh.p_W.size()));
    if (added) mesh.p_W.push_back(p);
    return it->second;
  }
  void add(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    // Pieces of zero area (a cut through a vertex, a sliver on a grid line) carry nothing: drop them [m^2].
    if (0.5 * (b - a).cross(c - a).norm() <= 1e-12) return;
    mesh.triangles.emplace_back(vertex(a), vertex(b), vertex(c));
  }
};

}  // namespace

TileKey tile_of(double e_m, double n_m, double tile_size_m) {
  const double fx = std::floor(e_m / tile_size_m), fy = std::floor(n_m / tile_size_m);
  if (!std::isfinite(fx) || !std::isfinite(fy) || std::abs(fx) > 1e8 || std::abs(fy) > 1e8) {
    throw InputError(where("twin store", 0,
                           "position (" + std::to_string(e_m) + ", " + std::to_string(n_m) +
                               ") m is not finite or too far from the origin for the tile grid"));
  }
  return TileKey{static_cast<int>(fx), static_cast<int>(fy)};
}

std::map<TileKey, Mesh> cut_into_tiles(const Mesh& mesh_W, double tile_size_m) {
  const double s = tile_size_m;
  const long n_vertices = static_cast<long>(mesh_W.p_W.size());
  std::map<TileKey, TileBuilder> builders;
  for (std::size_t t = 0; t < mesh_W.triangles.size(); ++t) {
    const Eigen::Vector3i& f = mesh_W.triangles[t];
    if ((f.array() < 0).any() || (f.array().cast<long>() >= n_vertices).any()) {
      throw InputError(
          where("twin store", 0,
                "triangle " + std::to_string(t) + " references a vertex outside 0.." + std::to_string(n_vertices - 1)));
    }
    const Polygon tri{mesh_W.p_W[f[0]], mesh_W.p_W[f[1]], mesh_W.p_W[f[2]]};
    TileKey lo = tile_of(tri[0].x(), tri[0].y(), s), hi = lo;
    for (int k = 1; k < 3; ++k) {
      const TileKey key = tile_of(tri[k].x(), tri[k].y(), s);
      lo = {std::min(lo.ix, key.ix), std::min(lo.iy, key.iy)};
      hi = {std::max(hi.ix, key.ix), std::max(hi.iy, key.iy)};
    }
    if (lo == hi) {  // inside one tile: the common case for tiles much larger than triangles
      builders[lo].add(tri[0], tri[1], tri[2]);
      continue;
    }
    for (int ix = lo.ix; ix <= hi.ix; ++ix) {
      Polygon strip = clip(clip(tri, 0, ix * s, true), 0, (ix + 1) * s, false);
      if (strip.size() < 3) continue;
      for (int iy = lo.iy; iy <= hi.iy; ++iy) {
        const Polygon piece = clip(clip(strip, 1, iy * s, true), 1, (iy + 1) * s, false);
        if (piece.size() < 3) continue;
        TileBuilder& b = builders[TileKey{ix, iy}];
        for (std::size_t k = 1; k + 1 < piece.size(); ++k) b.add(piece[0], piece[k], piece[k + 1]);  // convex: fan
      }
    }
  }
  std::map<TileKey, Mesh> tiles;
  for (auto& [key, b] : builders) {
    if (!b.mesh.triangles.empty()) tiles.emplace(key, std::move(b.mesh));
  }
  return tiles;
}

std::map<TileKey, Mesh> split_points_into_tiles(const Mesh& points_W, double tile_size_m) {
  if (points_W.n_W.size() != points_W.p_W.size()) {
    throw InputError(where("twin store", 0,
                           "a point set needs one normal per point (" + std::to_string(points_W.p_W.size()) +
                               " points, " + std::to_string(points_W.n_W.size()) + " normals)"));
  }
  std::map<TileKey, Mesh> tiles;
  for (std::size_t i = 0; i < points_W.p_W.size(); ++i) {
    const Eigen::Vector3d& p = points_W.p_W[i];
    Mesh& tile = tiles[tile_of(p.x(), p.y(), tile_size_m)];
    tile.p_W.push_back(p);
    tile.n_W.push_back(points_W.n_W[i]);
  }
  return tiles;
}

}  // namespace twinslam::twin

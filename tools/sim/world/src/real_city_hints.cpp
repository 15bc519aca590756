// What the flight planner and the twin need to know about a loaded city, read from its geometry: the tallest
// building (centre, radius, height) and how much room there is around it, the ground height, the extent, every
// building's footprint box, and empty lots where a twin may add buildings.
#include <algorithm>
#include <cmath>

#include "real_city_parts.hpp"

namespace twinslam::sim::detail {
namespace {

constexpr double kClearance_m = 3.0;  // the loops ring keeps this far from what stands around it [m]

double segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double u = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + u * ab - p).norm();
}

double max_z(const TriMesh& m, std::size_t tri) {
  const auto& t = m.triangles[tri];
  return std::max({m.p_W[t[0]].z(), m.p_W[t[1]].z(), m.p_W[t[2]].z()});
}

// Horizontal distance from the tallest building's centre to the nearest triangle of anything else that reaches above
// z_low (the ring's lowest altitude less the clearance): neighbours lower than the flight do not narrow the ring, nor
// does flat ground. Never 0 (which SceneHints reads as "unknown").
double clear_radius(const City& city, const Eigen::Vector2d& centre, double z_low) {
  const TriMesh& m = city.mesh;
  double best = 1e4;
  for (std::size_t i = 0; i < m.num_triangles(); ++i) {
    const double top = max_z(m, i);
    if (m.building_id[i] == city.tallest_id || top <= z_low) continue;
    if (m.kind[i] == SurfaceKind::kGround && top < city.hints.ground_z_m + 1.0) continue;
    const auto& t = m.triangles[i];
    best = std::min(best, horizontal_distance(centre, m.p_W[t[0]], m.p_W[t[1]], m.p_W[t[2]]));
  }
  return std::max(best, 0.01);
}

// Empty lots: lot_size_m squares inside the model's extent at least lot_clearance_m from anything but flat ground
// (found on a 1 m occupancy raster, greedily, on a grid of half a lot).
std::vector<Eigen::Vector4d> empty_lots(const City& city, const RealCityConfig& config, const Eigen::Vector4d& ext) {
  const double cell = 1.0, grow = config.lot_clearance_m;
  const int nx = static_cast<int>(std::ceil((ext[2] - ext[0]) / cell));
  const int ny = static_cast<int>(std::ceil((ext[3] - ext[1]) / cell));
  if (nx <= 0 || ny <= 0) return {};
  std::vector<int> occupied(static_cast<std::size_t>(nx) * ny, 0);
  auto mark = [&](double x0, double y0, double x1, double y1) {
    const int i0 = std::max(0, static_cast<int>(std::floor((x0 - ext[0]) / cell)));
    const int i1 = std::min(nx - 1, static_cast<int>(std::floor((x1 - ext[0]) / cell)));
    const int j0 = std::max(0, static_cast<int>(std::floor((y0 - ext[1]) / cell)));
    const int j1 = std::min(ny - 1, static_cast<int>(std::floor((y1 - ext[1]) / cell)));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) occupied[static_cast<std::size_t>(j) * nx + i] = 1;
  };
  const TriMesh& m = city.mesh;
  for (std::size_t i = 0; i < m.num_triangles(); ++i) {
    if (m.kind[i] == SurfaceKind::kGround && max_z(m, i) < city.hints.ground_z_m + 1.0) continue;
    const auto& t = m.triangles[i];
    const Eigen::Vector3d lo = m.p_W[t[0]].cwiseMin(m.p_W[t[1]]).cwiseMin(m.p_W[t[2]]);
    const Eigen::Vector3d hi = m.p_W[t[0]].cwiseMax(m.p_W[t[1]]).cwiseMax(m.p_W[t[2]]);
    mark(lo.x() - grow, lo.y() - grow, hi.x() + grow, hi.y() + grow);
  }
  std::vector<Eigen::Vector4d> lots;
  const int side = static_cast<int>(std::round(config.lot_size_m / cell)), step = std::max(1, side / 2);
  for (int j = 0; j + side <= ny; j += step)
    for (int i = 0; i + side <= nx; i += step) {
      bool free = true;
      for (int b = j; b < j + side && free; ++b)
        for (int a = i; a < i + side && free; ++a) free = !occupied[static_cast<std::size_t>(b) * nx + a];
      if (!free) continue;
      const Eigen::Vector4d lot(ext[0] + i * cell, ext[1] + j * cell, ext[0] + (i + side) * cell,
                                ext[1] + (j + side) * cell);
      lots.push_back(lot);
      mark(lot[0] + 0.5, lot[1] + 0.5, lot[2] - 0.5, lot[3] - 0.5);  // lots do not overlap
    }
  return lots;
}

}  // namespace

double horizontal_distance(const Eigen::Vector2d& p, const Eigen::Vector3d& a3, const Eigen::Vector3d& b3,
                           const Eigen::Vector3d& c3) {
  const Eigen::Vector2d a = a3.head<2>(), b = b3.head<2>(), c = c3.head<2>();
  auto side = [&](const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
    return (v - u).x() * (p - u).y() - (v - u).y() * (p - u).x();
  };
  const double d0 = side(a, b), d1 = side(b, c), d2 = side(c, a);
  if ((d0 >= 0 && d1 >= 0 && d2 >= 0) || (d0 <= 0 && d1 <= 0 && d2 <= 0)) return 0;
  return std::min({segment_distance(p, a, b), segment_distance(p, b, c), segment_distance(p, c, a)});
}

void fill_real_hints(const RealCityConfig& config, const TrajectoryConfig& trajectory, const Eigen::Vector4d& extent_W,
                     City* city) {
  SceneHints& h = city->hints;
  std::vector<double> base_z;
  for (const Building& b : city->buildings) base_z.push_back(b.base_z_m);
  std::nth_element(base_z.begin(), base_z.begin() + static_cast<std::ptrdiff_t>(base_z.size() / 2), base_z.end());
  h.ground_z_m = base_z[base_z.size() / 2];  // the median building's ground

  const Building& tall = city->buildings[static_cast<std::size_t>(city->tallest_id)];
  const Eigen::Vector4d& box = tall.rects_W.front();
  h.tall_building_center_W = Eigen::Vector2d(0.5 * (box[0] + box[2]), 0.5 * (box[1] + box[3]));
  h.tall_building_radius_m = 0;
  for (const Eigen::Vector2d& p : tall.outline_W)
    h.tall_building_radius_m = std::max(h.tall_building_radius_m, (p - h.tall_building_center_W).norm());
  h.tall_building_height_m = tall.top_m;
  const double z_low = h.ground_z_m + trajectory.altitude_m[0] - kClearance_m;  // the ring's lowest point, less 3 m
  h.clear_radius_m = clear_radius(*city, h.tall_building_center_W, z_low);
  h.extent_W = {extent_W[0], extent_W[1], extent_W[2], extent_W[3]};
  for (const Building& b : city->buildings) h.buildings.push_back({b.id, b.rects_W, b.height_m, b.top_m});
  city->empty_lots_W = empty_lots(*city, config, extent_W);
}

}  // namespace twinslam::sim::detail

// A real city model -> City: buildings with ids, surface kinds, a ground plane; then details and hints (other files).
#include "twinslam/sim/world/real_city.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>

#include "real_city_parts.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/twin/geo.hpp"

namespace twinslam::sim {
namespace detail {
namespace {

constexpr double kWallMaxNz = 0.3;   // |n_z| below this is a wall (about 17 deg from vertical) [-]
constexpr double kFloorBand_m = 0.3; // a near-horizontal face this close to a building's base is its floor [m]

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  const auto k = static_cast<std::size_t>(std::clamp(q, 0.0, 1.0) * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

// Convex hull (Andrew's monotone chain), counter-clockwise: the footprint outline a loaded building is given.
std::vector<Eigen::Vector2d> convex_hull(std::vector<Eigen::Vector2d> p) {
  std::sort(p.begin(), p.end(),
            [](const auto& a, const auto& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
  std::vector<Eigen::Vector2d> h(2 * p.size());
  std::size_t k = 0;
  auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
  };
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(h[k - 2], h[k - 1], p[i - 1]) <= 0) --k;
    h[k++] = p[i - 1];
  }
  h.resize(std::max<std::size_t>(k, 2) - 1);
  return h;
}

// Buildings in order of first appearance; each building's vertices give its base, top, footprint.
void collect_buildings(const SourceModel& m, City* city, std::vector<int>* building_of_part) {
  std::map<std::string, int> id_of;
  building_of_part->assign(m.parts.size(), kNoBuilding);
  for (std::size_t t = 0; t < m.mesh.num_triangles(); ++t) {
    const int part = m.part_of_triangle[t];
    if (part < 0 || m.parts[part].role != PartRole::kBuilding || (*building_of_part)[part] != kNoBuilding) continue;
    const auto [it, inserted] = id_of.try_emplace(m.parts[part].building, static_cast<int>(city->buildings.size()));
    if (inserted) {
      Building b;
      b.id = it->second;
      b.name = m.parts[part].building;
      city->buildings.push_back(b);
    }
    (*building_of_part)[part] = it->second;
  }
  std::vector<double> lo(city->buildings.size(), 1e300), hi(city->buildings.size(), -1e300);
  std::vector<std::vector<Eigen::Vector2d>> xy(city->buildings.size());
  for (std::size_t t = 0; t < m.mesh.num_triangles(); ++t) {
    const int part = m.part_of_triangle[t];
    const int b = part < 0 ? kNoBuilding : (*building_of_part)[part];
    if (b == kNoBuilding) continue;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& p = m.mesh.p_W[m.mesh.triangles[t][k]];
      lo[b] = std::min(lo[b], p.z());
      hi[b] = std::max(hi[b], p.z());
      xy[b].push_back(p.head<2>());
    }
  }
  for (Building& b : city->buildings) {
    b.base_z_m = lo[b.id];
    b.height_m = b.top_m = hi[b.id] - lo[b.id];
    b.outline_W = convex_hull(xy[b.id]);
    Eigen::Vector2d mn = b.outline_W.front(), mx = mn;
    for (const auto& p : b.outline_W) mn = mn.cwiseMin(p), mx = mx.cwiseMax(p);
    b.rects_W = {Eigen::Vector4d(mn.x(), mn.y(), mx.x(), mx.y())};  // bounding rectangle: hints only
    if (b.top_m > city->buildings[city->tallest_id].top_m) city->tallest_id = b.id;
  }
}

// Every usable triangle with its kind; a building's floor (flat, at its base) is left out.
void add_triangles(const SourceModel& m, const std::vector<int>& building_of_part, City* city) {
  for (std::size_t t = 0; t < m.mesh.num_triangles(); ++t) {
    const int part = m.part_of_triangle[t];
    if (part < 0 || m.mesh.triangle_area(t) < 1e-6) continue;
    const Eigen::Vector3i& tri = m.mesh.triangles[t];
    const Eigen::Vector3d a = m.mesh.p_W[tri[0]], b = m.mesh.p_W[tri[1]], c = m.mesh.p_W[tri[2]];
    const double nz = std::abs(m.mesh.triangle_normal(t).z());
    const int building = building_of_part[part];
    SurfaceKind kind = nz < kWallMaxNz ? SurfaceKind::kFacade : SurfaceKind::kRoof;
    if (m.parts[part].role == PartRole::kTerrain) kind = SurfaceKind::kGround;
    if (building != kNoBuilding && kind == SurfaceKind::kRoof &&
        std::max({a.z(), b.z(), c.z()}) <= city->buildings[building].base_z_m + kFloorBand_m)
      continue;
    city->mesh.add_triangle(a, b, c, kind, building);
  }
}

// 20 m patches over the model's extent plus the margin, just below the lowest terrain (or at the buildings' ground).
void add_ground_plane(const SourceModel& m, const RealCityConfig& config, const Eigen::Vector4d& extent, City* city) {
  std::vector<double> terrain_z, base_z;
  for (std::size_t t = 0; t < m.mesh.num_triangles(); ++t) {
    const int part = m.part_of_triangle[t];
    if (part >= 0 && m.parts[part].role == PartRole::kTerrain)
      for (int k = 0; k < 3; ++k) terrain_z.push_back(m.mesh.p_W[m.mesh.triangles[t][k]].z());
  }
  for (const Building& b : city->buildings) base_z.push_back(b.base_z_m);
  double z = percentile(base_z, 0.1);
  if (!terrain_z.empty()) z = std::min(z, percentile(terrain_z, 0.01) - 0.05);
  const double s = config.ground_patch_m, e0 = extent[0] - config.ground_margin_m,
               n0 = extent[1] - config.ground_margin_m, e1 = extent[2] + config.ground_margin_m,
               n1 = extent[3] + config.ground_margin_m;
  for (double x = e0; x < e1 - 1e-9; x += s)
    for (double y = n0; y < n1 - 1e-9; y += s) {
      const double x1 = std::min(x + s, e1), y1 = std::min(y + s, n1);
      city->mesh.add_quad({x, y, z}, {x1, y, z}, {x1, y1, z}, {x, y1, z}, SurfaceKind::kGround, kNoBuilding);
    }
}

}  // namespace

City convert_source_model(const SourceModel& m, const RealCityConfig& config, Eigen::Vector4d* extent_W) {
  City city;
  city.layout.floor_height_m = config.floor_height_m;
  city.layout.ground_patch_m = config.ground_patch_m;
  std::vector<int> building_of_part;
  collect_buildings(m, &city, &building_of_part);
  add_triangles(m, building_of_part, &city);
  Eigen::Vector3d lo, hi;
  city.mesh.bounds(&lo, &hi);
  *extent_W = Eigen::Vector4d(lo.x(), lo.y(), hi.x(), hi.y());
  add_ground_plane(m, config, *extent_W, &city);
  return city;
}

}  // namespace detail

namespace {

// The model converted in the W of `origin`; InputError naming city.path when it has no building to fly around.
City convert_checked(const Scenario& scenario, const Origin& origin, const RealCityConfig& config,
                     Eigen::Vector4d* extent_W, bool note_rejected) {
  const detail::SourceModel model = detail::load_source_model(scenario, origin, config);
  if (note_rejected && !model.rejected.empty())
    std::cerr << "note: city.path: " << model.rejected.size() << " part(s) not used, first: " << model.rejected.front()
              << "\n";
  if (note_rejected && !model.warnings.empty())
    std::cerr << "note: city.path: " << model.warnings.size() << " quirk(s) accepted, first: " << model.warnings.front()
              << "\n";
  City city = detail::convert_source_model(model, config, extent_W);
  if (city.buildings.empty())
    throw InputError(where(scenario.name, 0, "city.path: " + *scenario.city.path + ": no buildings in the model"));
  return city;
}

}  // namespace

City build_real_city(const Scenario& scenario, const RealCityConfig& config) {
  Eigen::Vector4d extent_W;
  City city = convert_checked(scenario, scenario.origin, config, &extent_W, true);
  detail::add_real_details(config, scenario.seed, &city);
  detail::fill_real_hints(config, scenario.trajectory, extent_W, &city);
  return city;
}

Origin real_city_origin(const Scenario& scenario, const RealCityConfig& config) {
  if (scenario.origin_given) return scenario.origin;
  // The model's centre and ground as seen in the W of the current guess, twice: from a guess far away (the default
  // origin) the model is turned by the difference of the two places' ENU axes, which moves its bounding box's centre.
  Origin origin = scenario.origin;
  for (int pass = 0; pass < 2; ++pass) {
    Eigen::Vector4d extent_W;
    const City city = convert_checked(scenario, origin, config, &extent_W, false);
    std::vector<double> base_z;
    for (const Building& b : city.buildings) base_z.push_back(b.base_z_m);
    std::nth_element(base_z.begin(), base_z.begin() + static_cast<std::ptrdiff_t>(base_z.size() / 2), base_z.end());
    const Eigen::Vector3d centre_W(0.5 * (extent_W[0] + extent_W[2]), 0.5 * (extent_W[1] + extent_W[3]),
                                   base_z[base_z.size() / 2]);
    const Eigen::Vector3d lla = twin::EnuFrame({origin.lat_deg, origin.lon_deg, origin.alt_m}).to_lla(centre_W);
    origin = {lla.x(), lla.y(), lla.z()};
  }
  return origin;
}

City build_world_city(const Scenario& scenario) {
  if (scenario.city.source == "procedural") return build_city(scenario.city, scenario.seed);
  return build_real_city(scenario);
}

}  // namespace twinslam::sim

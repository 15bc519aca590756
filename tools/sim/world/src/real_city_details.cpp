// The procedural city's details (city_details.cpp) on loaded buildings, whose walls run in any direction: floor bands
// on every vertical wall at the 3 m storeys the facade texture draws its window rows on, balconies on the widest wall
// of some buildings, and rooftop boxes on flat roofs. All kDetail with the building id, so the twin drops them and a
// missing building loses them too. Deterministic per seed.
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <tuple>

#include "city_parts.hpp"
#include "real_city_parts.hpp"

namespace twinslam::sim::detail {
namespace {

constexpr double kVerticalNz = 0.1;  // walls this close to vertical get bands [-]

// One planar wall of a building: coplanar, vertex-connected facade triangles.
struct Wall {
  int building = kNoBuilding;
  Eigen::Vector2d n = Eigen::Vector2d::Zero();  // horizontal unit normal (outward for outward-wound sources)
  Eigen::Vector2d t = Eigen::Vector2d::Zero();  // unit tangent along the wall
  double offset = 0;                            // the wall's plane: n . p_W = offset [m]
  std::vector<int> triangles;
  double z0 = 1e300, z1 = -1e300;               // [m, W up]
};

// Extent [s0, s1] along w.t of the wall's cut at height z; false if the plane misses the wall.
bool cut_at(const TriMesh& m, const Wall& w, double z, double* s0, double* s1) {
  *s0 = 1e300, *s1 = -1e300;
  for (const int tri : w.triangles) {
    for (int e = 0; e < 3; ++e) {
      const Eigen::Vector3d& a = m.p_W[m.triangles[tri][e]];
      const Eigen::Vector3d& b = m.p_W[m.triangles[tri][(e + 1) % 3]];
      if ((a.z() - z) * (b.z() - z) > 0 || a.z() == b.z()) continue;
      const Eigen::Vector3d p = a + (b - a) * ((z - a.z()) / (b.z() - a.z()));
      const double s = w.t.dot(p.head<2>());
      *s0 = std::min(*s0, s), *s1 = std::max(*s1, s);
    }
  }
  return *s1 > *s0;
}

// Walls: facade triangles grouped by building, plane (normal within 0.5 deg, offset within 5 cm) and shared vertices.
std::vector<Wall> find_walls(const TriMesh& m) {
  const std::size_t n = m.num_triangles();
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::map<std::tuple<int, long, long, int>, int> first_user;  // (building, angle, offset, vertex) -> triangle
  std::vector<int> eligible;
  for (std::size_t i = 0; i < n; ++i) {
    if (m.kind[i] != SurfaceKind::kFacade || m.building_id[i] == kNoBuilding) continue;
    const Eigen::Vector3d nn = m.normal(i);
    if (std::abs(nn.z()) > kVerticalNz) continue;
    eligible.push_back(static_cast<int>(i));
    const Eigen::Vector2d h = nn.head<2>().normalized();
    const long angle = std::lround(std::atan2(h.y(), h.x()) * 180 / M_PI * 2);
    const long offset = std::lround(h.dot(m.p_W[m.triangles[i][0]].head<2>()) / 0.05);
    for (int k = 0; k < 3; ++k) {
      const auto [it, inserted] =
          first_user.try_emplace({m.building_id[i], angle, offset, m.triangles[i][k]}, static_cast<int>(i));
      if (!inserted) parent[find(static_cast<int>(i))] = find(it->second);
    }
  }
  std::map<int, Wall> walls;
  for (const int i : eligible) {
    const int root = find(i);
    Wall& w = walls[root];
    if (w.triangles.empty()) {
      w.building = m.building_id[root];
      w.n = m.normal(root).head<2>().normalized();
      w.t = Eigen::Vector2d(-w.n.y(), w.n.x());
      w.offset = w.n.dot(m.p_W[m.triangles[root][0]].head<2>());
    }
    w.triangles.push_back(i);
  }
  std::vector<Wall> out;
  for (auto& [root, w] : walls) {
    for (const int tri : w.triangles)
      for (int k = 0; k < 3; ++k) {
        const double z = m.p_W[m.triangles[tri][k]].z();
        w.z0 = std::min(w.z0, z), w.z1 = std::max(w.z1, z);
      }
    out.push_back(std::move(w));
  }
  return out;
}

// Box along a wall: s0..s1 along t, d0..d1 out of the wall's plane along n, z0..z1 (an oriented add_box).
void add_wall_box(TriMesh* mesh, const Wall& w, double s0, double s1, double d0, double d1, double z0, double z1) {
  auto at = [&](double s, double d, double z) {
    const Eigen::Vector2d p = s * w.t + (w.offset + d) * w.n;
    return Eigen::Vector3d(p.x(), p.y(), z);
  };
  const Eigen::Vector3d t(w.t.x(), w.t.y(), 0), n(w.n.x(), w.n.y(), 0), up(0, 0, 1);
  const SurfaceKind k = SurfaceKind::kDetail;
  add_quad_out(mesh, at(s0, d1, z0), at(s1, d1, z0), at(s1, d1, z1), at(s0, d1, z1), n, k, w.building);
  add_quad_out(mesh, at(s0, d0, z0), at(s1, d0, z0), at(s1, d0, z1), at(s0, d0, z1), -n, k, w.building);
  add_quad_out(mesh, at(s1, d0, z0), at(s1, d1, z0), at(s1, d1, z1), at(s1, d0, z1), t, k, w.building);
  add_quad_out(mesh, at(s0, d0, z0), at(s0, d1, z0), at(s0, d1, z1), at(s0, d0, z1), -t, k, w.building);
  add_quad_out(mesh, at(s0, d0, z1), at(s1, d0, z1), at(s1, d1, z1), at(s0, d1, z1), up, k, w.building);
  add_quad_out(mesh, at(s0, d0, z0), at(s1, d0, z0), at(s1, d1, z0), at(s0, d1, z0), -up, k, w.building);
}

// A 0.3 m band 0.15 m proud of the wall at every storey line (absolute multiples of floor_height_m, as the texture's
// window rows), 0.15 m past the wall's ends so bands of neighbouring walls meet at corners.
void add_floor_bands(TriMesh* mesh, const Wall& w, double floor_m) {
  for (double z = std::ceil((w.z0 + 1.5) / floor_m) * floor_m; z < w.z1 - 0.5; z += floor_m) {
    double s0, s1;
    if (!cut_at(*mesh, w, z, &s0, &s1) || s1 - s0 < 1.0) continue;
    add_wall_box(mesh, w, s0 - 0.15, s1 + 0.15, 0.0, 0.15, z - 0.15, z + 0.15);
  }
}

// Balconies (slab and railing, every 6 m) on each storey of a wall, as add_balconies in city_details.cpp.
void add_balconies(TriMesh* mesh, const Wall& w, double floor_m) {
  for (double z = std::ceil((w.z0 + 2.0) / floor_m) * floor_m; z + 1.3 < w.z1; z += floor_m) {
    double s0, s1;
    if (!cut_at(*mesh, w, z + 1.3, &s0, &s1)) continue;
    for (double s = s0 + 1.5; s + 2.4 < s1 - 1.0; s += 6.0) {
      add_wall_box(mesh, w, s, s + 2.4, 0.0, 1.2, z + 0.1, z + 0.3);   // slab
      add_wall_box(mesh, w, s, s + 2.4, 1.15, 1.2, z + 0.3, z + 1.3);  // railing panel
    }
  }
}

bool inside_triangle_xy(const Eigen::Vector2d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                        const Eigen::Vector3d& c) {
  auto side = [&](const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
    return (v.x() - u.x()) * (p.y() - u.y()) - (v.y() - u.y()) * (p.x() - u.x());
  };
  const double d0 = side(a, b), d1 = side(b, c), d2 = side(c, a);
  return (d0 >= 0 && d1 >= 0 && d2 >= 0) || (d0 <= 0 && d1 <= 0 && d2 <= 0);
}

// 1-4 boxes on the building's largest flat roof level, aligned with `w` (its widest wall), 1 m inside the roof edge.
void add_rooftop_boxes(TriMesh* mesh, int building, const Wall& w, Rng* rng) {
  std::map<long, std::vector<int>> levels;  // flat roof triangles by height (10 cm)
  for (std::size_t i = 0; i < mesh->num_triangles(); ++i)
    if (mesh->building_id[i] == building && mesh->kind[i] == SurfaceKind::kRoof && mesh->normal(i).z() > 0.97)
      levels[std::lround(mesh->p_W[mesh->triangles[i][0]].z() / 0.1)].push_back(static_cast<int>(i));
  const std::vector<int>* roof = nullptr;
  double best = 40;  // [m^2] smaller roofs get no boxes
  for (const auto& [z, tris] : levels) {
    double area = 0;
    for (const int t : tris) area += mesh->area(t);
    if (area > best) best = area, roof = &tris;
  }
  if (roof == nullptr) return;
  const std::vector<int> tris = *roof;  // the mesh grows below
  auto on_roof = [&](const Eigen::Vector2d& p) {
    return std::any_of(tris.begin(), tris.end(), [&](int t) {
      const auto& v = mesh->triangles[t];
      return inside_triangle_xy(p, mesh->p_W[v[0]], mesh->p_W[v[1]], mesh->p_W[v[2]]);
    });
  };
  const double z = mesh->p_W[mesh->triangles[tris.front()][0]].z();
  const int count = 1 + rng->integer(4);
  for (int i = 0, tries = 0; i < count && tries < 20; ++tries) {
    const auto& v = mesh->triangles[tris[static_cast<std::size_t>(rng->integer(static_cast<int>(tris.size())))]];
    double u = rng->uniform(), r = rng->uniform();
    if (u + r > 1) u = 1 - u, r = 1 - r;
    const Eigen::Vector3d& a = mesh->p_W[v[0]];
    const Eigen::Vector3d c = a + u * (mesh->p_W[v[1]] - a) + r * (mesh->p_W[v[2]] - a);
    const double sw = rng->uniform(1.0, 3.0), sd = rng->uniform(1.0, 3.0), h = rng->uniform(0.8, 2.5);
    const double s = w.t.dot(c.head<2>()), d = w.n.dot(c.head<2>()) - w.offset;  // box centre in the wall's frame
    bool fits = true;  // every corner 1 m inside the roof
    for (const double ds : {-0.5 * sw - 1, 0.5 * sw + 1})
      for (const double dd : {-0.5 * sd - 1, 0.5 * sd + 1})
        fits = fits && on_roof((s + ds) * w.t + (w.offset + d + dd) * w.n);
    if (!fits) continue;
    Wall box = w;
    box.building = building;
    add_wall_box(mesh, box, s - 0.5 * sw, s + 0.5 * sw, d - 0.5 * sd, d + 0.5 * sd, z, z + h);
    ++i;
  }
}

}  // namespace

void add_real_details(const RealCityConfig& config, std::uint64_t seed, City* city) {
  const std::vector<Wall> walls = find_walls(city->mesh);
  std::vector<const Wall*> widest(city->buildings.size(), nullptr);
  std::vector<double> width(city->buildings.size(), 0);
  for (const Wall& w : walls) {
    double s0, s1;
    if (!cut_at(city->mesh, w, 0.5 * (w.z0 + w.z1), &s0, &s1) || s1 - s0 <= width[w.building]) continue;
    width[w.building] = s1 - s0;
    widest[w.building] = &w;
  }
  for (const Wall& w : walls) add_floor_bands(&city->mesh, w, config.floor_height_m);
  Rng rng(hash64(seed ^ 0x8EA1C17ULL));  // a stream of its own, drawn in building order
  for (const Building& b : city->buildings) {
    const bool balconies = rng.chance(0.35), boxes = rng.chance(0.7);
    if (widest[b.id] == nullptr) continue;
    if (balconies && width[b.id] > 8) add_balconies(&city->mesh, *widest[b.id], config.floor_height_m);
    if (boxes) add_rooftop_boxes(&city->mesh, b.id, *widest[b.id], &rng);
  }
}

}  // namespace twinslam::sim::detail

#include "twinslam/sim/world/twin.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <map>
#include <set>
#include <string>

#include "twinslam/core/error.hpp"
#include "twinslam/sim/world/random.hpp"

namespace twinslam::sim {
namespace {

// Union-find over triangles: planar faces are sets of triangles that share vertices, have the same kind and parallel
// normals (the world generator never shares a vertex between two faces, but a loaded mesh may).
struct Faces {
  std::vector<int> parent;
  explicit Faces(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void unite(int a, int b) { parent[find(a)] = find(b); }
};

void validate(const City& world, const TwinConfig& c) {
  if (!std::isfinite(c.noise_m) || c.noise_m < 0 || c.noise_m > 10)
    throw InputError("twin.noise_m: must be in [0, 10] m, got " + std::to_string(c.noise_m));
  const int max_missing = static_cast<int>(world.buildings.size()) - 1;
  if (c.missing_buildings < 0 || c.missing_buildings > max_missing)
    throw InputError("twin.missing_buildings: must be in [0, " + std::to_string(max_missing) + "], got " +
                     std::to_string(c.missing_buildings));
  const int max_added = static_cast<int>(world.empty_lots_W.size());
  if (c.added_buildings < 0 || c.added_buildings > max_added)
    throw InputError("twin.added_buildings: this city has " + std::to_string(max_added) +
                     " empty lots, got " + std::to_string(c.added_buildings));
  if (!c.offset_m.allFinite()) throw InputError("twin.offset_m: must be finite");
  const int max_shifted = max_missing - c.missing_buildings;
  if (c.shifted_buildings.count < 0 || c.shifted_buildings.count > max_shifted)
    throw InputError("twin.shifted_buildings.count: must be in [0, " + std::to_string(max_shifted) +
                     "] (buildings besides the tallest and the missing ones), got " +
                     std::to_string(c.shifted_buildings.count));
  const double d = c.shifted_buildings.offset_m;
  if (!std::isfinite(d) || d < 0 || d > kMaxBuildingShift_m)
    throw InputError("twin.shifted_buildings.offset_m: must be in [0, " + std::to_string(int(kMaxBuildingShift_m)) +
                     "] m, got " + std::to_string(d));
}

// Seeded Fisher-Yates shuffle with our own Rng (std::shuffle's use of the engine is library-specific).
template <typename T>
void shuffle(std::vector<T>* v, Rng* rng) {
  for (int i = static_cast<int>(v->size()) - 1; i > 0; --i) std::swap((*v)[i], (*v)[rng->integer(i + 1)]);
}

// `ids` in a seeded order: the seen ones (shuffled) before the others (shuffled), so the first N of them hit what
// the flight sees while there are enough. With none seen this is exactly one shuffle of all (the draws of the twins
// made before seen ids existed).
std::vector<int> seen_first(const std::vector<int>& ids, const std::vector<int>& seen_ids, Rng* rng) {
  const std::set<int> seen(seen_ids.begin(), seen_ids.end());
  std::vector<int> first, rest;
  for (const int id : ids) (seen.count(id) ? first : rest).push_back(id);
  shuffle(&first, rng);
  shuffle(&rest, rng);
  first.insert(first.end(), rest.begin(), rest.end());
  return first;
}

// The world's buildings except the tallest and `excluded`, seen ones first (seen_first).
std::vector<int> candidate_order(const City& world, const std::vector<int>& seen_ids, const std::set<int>& excluded,
                                 Rng* rng) {
  std::vector<int> ids;
  for (const auto& b : world.buildings)
    if (b.id != world.tallest_id && !excluded.count(b.id)) ids.push_back(b.id);
  return seen_first(ids, seen_ids, rng);
}

// Horizontal shift [m, W] of each shifted building, from a stream of its own so that twins without shifted
// buildings keep their bytes.
std::map<int, Eigen::Vector3d> choose_shifted(const City& world, const TwinConfig& config, std::uint64_t seed,
                                              const std::vector<int>& seen_ids, const std::set<int>& missing) {
  std::map<int, Eigen::Vector3d> shift_W;
  if (config.shifted_buildings.count == 0) return shift_W;
  Rng rng(hash64(seed ^ 0x5A1F7EDULL));
  std::vector<int> order = candidate_order(world, seen_ids, missing, &rng);
  order.resize(static_cast<std::size_t>(config.shifted_buildings.count));
  std::sort(order.begin(), order.end());
  for (const int id : order) {
    const double angle = 2 * M_PI * rng.uniform();  // [rad] from east, counter-clockwise
    shift_W[id] = config.shifted_buildings.offset_m * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0);
  }
  return shift_W;
}

// The kept world triangles, every planar face moved along its normal by its own N(0, noise_m^2) offset (each face
// gets its own copy of its vertices), the whole twin by config.offset_m and shifted buildings by their shift.
void copy_perturbed(const TriMesh& w, const std::vector<int>& kept, const TwinConfig& config,
                    const std::map<int, Eigen::Vector3d>& shift_W, Rng* rng, TriMesh* out) {
  Faces faces(kept.size());
  std::vector<std::vector<int>> users(w.p_W.size());
  for (std::size_t k = 0; k < kept.size(); ++k)
    for (int c = 0; c < 3; ++c) users[w.triangles[kept[k]][c]].push_back(static_cast<int>(k));
  for (const auto& list : users)
    for (std::size_t a = 1; a < list.size(); ++a) {
      const int i = kept[list[0]], j = kept[list[a]];
      if (w.kind[i] == w.kind[j] && w.normal(i).dot(w.normal(j)) > 0.999) faces.unite(list[0], list[a]);
    }

  std::vector<double> offset(kept.size(), std::nan(""));
  std::map<std::pair<int, int>, int> vertex_of;
  for (std::size_t k = 0; k < kept.size(); ++k) {
    const int root = faces.find(static_cast<int>(k));
    if (std::isnan(offset[root])) offset[root] = config.noise_m * rng->normal();
    const int tri = kept[k];
    const Eigen::Vector3d n = w.normal(tri);
    const auto shift = shift_W.find(w.building_id[tri]);
    Eigen::Vector3i t;
    for (int c = 0; c < 3; ++c) {
      const int v = w.triangles[tri][c];
      auto [it, inserted] = vertex_of.try_emplace({root, v}, static_cast<int>(out->p_W.size()));
      if (inserted) {
        Eigen::Vector3d p = w.p_W[v] + offset[root] * n + config.offset_m;
        if (shift != shift_W.end()) p += shift->second;  // only then: adding a zero would turn -0.0 into +0.0
        out->p_W.push_back(p);
      }
      t[c] = it->second;
    }
    out->triangles.push_back(t);
    out->building_id.push_back(w.building_id[tri]);
    out->kind.push_back(w.kind[tri]);
  }
}

// Twin-only buildings: plain boxes in seeded empty lots, the seen ones first (seen_first).
void add_twin_only_buildings(const City& world, const TwinConfig& config, const std::vector<int>& seen_lots, Rng* rng,
                             Twin* twin) {
  std::vector<int> all(world.empty_lots_W.size());
  std::iota(all.begin(), all.end(), 0);
  const std::vector<int> lots = seen_first(all, seen_lots, rng);
  for (int k = 0; k < config.added_buildings; ++k) {
    const Eigen::Vector4d& lot = world.empty_lots_W[lots[k]];
    const int id = static_cast<int>(world.buildings.size()) + k;
    const double h = world.layout.floor_height_m * (3 + rng->integer(5));
    const double z0 = world.hints.ground_z_m;  // 0 in the procedural city; a loaded city's ground
    const Eigen::Vector3d lo(lot[0] + 3, lot[1] + 3, z0), hi(lot[2] - 3, lot[3] - 3, z0 + h);
    add_box(&twin->mesh, lo + config.offset_m, hi + config.offset_m, SurfaceKind::kFacade, SurfaceKind::kRoof, id);
    twin->added_building_ids.push_back(id);
    const Eigen::Vector2d a = (lo + config.offset_m).head<2>(), b = (hi + config.offset_m).head<2>();
    twin->added_outlines_W.push_back({a, {b.x(), a.y()}, b, {a.x(), b.y()}});
  }
}

}  // namespace

Twin derive_twin(const City& world, const TwinConfig& config, std::uint64_t seed, const TwinCandidates& seen) {
  validate(world, config);
  Rng rng(hash64(seed ^ 0x7417ULL));  // a stream of its own: the twin must not change when the city code draws more
  Twin twin;

  // This draw shares its stream with the faces' noise below: with other candidates the twin's faces differ too.
  const std::vector<int> candidates = candidate_order(world, seen.missing_ids, {}, &rng);
  twin.missing_building_ids.assign(candidates.begin(), candidates.begin() + config.missing_buildings);
  std::sort(twin.missing_building_ids.begin(), twin.missing_building_ids.end());
  const std::set<int> missing(twin.missing_building_ids.begin(), twin.missing_building_ids.end());
  const std::map<int, Eigen::Vector3d> shift_W = choose_shifted(world, config, seed, seen.shifted_ids, missing);
  for (const auto& [id, shift] : shift_W) {
    twin.shifted_building_ids.push_back(id);
    twin.shifted_building_offsets_W.push_back(shift);
  }

  std::vector<int> kept;
  for (std::size_t i = 0; i < world.mesh.num_triangles(); ++i)
    if (world.mesh.kind[i] != SurfaceKind::kDetail && !missing.count(world.mesh.building_id[i]))
      kept.push_back(static_cast<int>(i));
  copy_perturbed(world.mesh, kept, config, shift_W, &rng, &twin.mesh);
  add_twin_only_buildings(world, config, seen.lot_ids, &rng, &twin);
  return twin;
}

}  // namespace twinslam::sim

// Twin-change detection (changes.hpp): per-landmark evidence, then places by clustering the evidence horizontally.
#include "twinslam/twin/changes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <unordered_map>

#include "changes_geometry.hpp"
#include "twinslam/core/error.hpp"

namespace twinslam::twin {
namespace {

struct Evidence {
  Eigen::Vector2d at_W;  // where the disagreement is (the landmark, or where the sight line crosses the twin)
  double t_s = 0;
  bool sight_line = false;
  double value_m = 0;    // distance to the twin (landmark) or depth behind the crossed surface (sight line)
};

const Eigen::Vector3d& vertex(const Mesh& m, int tri, int k) { return m.p_W[m.triangles[tri][k]]; }

// Signed distance to the nearest twin surface within the search radius (+ on the side its normal points to).
double signed_distance(const Mesh& twin, const detail::TriangleGrid& grid, const Eigen::Vector3d& p, double radius) {
  const Eigen::Vector2d r(radius, radius);
  double best = radius, sign = 1;
  for (const int t : grid.near(p.head<2>() - r, p.head<2>() + r)) {
    const Eigen::Vector3d q = closest_point_on_triangle(p, vertex(twin, t, 0), vertex(twin, t, 1), vertex(twin, t, 2));
    const double d = (p - q).norm();
    if (d < best) {
      best = d;
      sign = (p - q).dot(twin.triangle_normal(t)) < 0 ? -1 : 1;
    }
  }
  return sign * best;
}

// The deepest crossing of the line of sight through a twin surface that the landmark lies well behind, if any.
std::optional<Evidence> sight_line_crossing(const Mesh& twin, const detail::TriangleGrid& grid,
                                            const LandmarkSighting& s, const TwinChangeConfig& c) {
  const Eigen::Vector3d d = s.p_W - s.observer_W;
  const double length = d.norm();
  if (length <= c.observer_margin_m + c.min_distance_m) return std::nullopt;
  const Eigen::Vector2d lo = s.p_W.head<2>().cwiseMin(s.observer_W.head<2>());
  const Eigen::Vector2d hi = s.p_W.head<2>().cwiseMax(s.observer_W.head<2>());
  std::optional<Evidence> best;
  for (const int t : grid.near(lo, hi)) {
    const auto f = detail::segment_crosses(s.observer_W, s.p_W, vertex(twin, t, 0), vertex(twin, t, 1), vertex(twin, t, 2));
    if (!f || *f * length < c.observer_margin_m) continue;
    const Eigen::Vector3d n = twin.triangle_normal(t);
    if (std::abs(n.dot(d) / length) < c.min_grazing_cos) continue;  // grazing: noise decides the side
    const Eigen::Vector3d hit = s.observer_W + *f * d;
    const double depth = std::abs((s.p_W - hit).dot(n));  // the landmark's distance behind the crossed plane
    if (depth < c.min_distance_m) continue;                 // on the surface, within the twin's and its own error
    if (!best || depth > best->value_m) best = Evidence{hit.head<2>(), s.t_s, true, depth};
  }
  return best;
}

// Connected groups of evidence closer than `radius` horizontally (union-find over a hash grid of that cell size).
std::vector<std::vector<std::size_t>> cluster(const std::vector<Evidence>& ev, double radius) {
  std::vector<std::size_t> parent(ev.size());
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::unordered_map<long long, std::vector<std::size_t>> cells;
  const auto cell = [radius](double v) { return static_cast<long>(std::floor(v / radius)); };
  const auto key = [](long ix, long iy) { return (static_cast<long long>(ix) << 32) ^ static_cast<unsigned>(iy); };
  for (std::size_t i = 0; i < ev.size(); ++i) cells[key(cell(ev[i].at_W.x()), cell(ev[i].at_W.y()))].push_back(i);
  for (std::size_t i = 0; i < ev.size(); ++i) {
    const long ix = cell(ev[i].at_W.x()), iy = cell(ev[i].at_W.y());
    for (long dx = -1; dx <= 1; ++dx)
      for (long dy = -1; dy <= 1; ++dy) {
        const auto it = cells.find(key(ix + dx, iy + dy));
        if (it == cells.end()) continue;
        for (const std::size_t j : it->second)
          if (j > i && (ev[i].at_W - ev[j].at_W).norm() < radius) parent[find(i)] = find(j);
      }
  }
  std::unordered_map<std::size_t, std::vector<std::size_t>> groups;
  for (std::size_t i = 0; i < ev.size(); ++i) groups[find(i)].push_back(i);
  std::vector<std::vector<std::size_t>> out;
  for (auto& [root, members] : groups) out.push_back(std::move(members));
  return out;
}

// A place from its evidence; nullopt when it is too little, too brief or too small to be a change of the world.
std::optional<TwinChange> place(const std::vector<Evidence>& ev, const std::vector<std::size_t>& members,
                                const TwinChangeConfig& c) {
  if (members.size() < c.min_evidence) return std::nullopt;
  TwinChange change;
  change.first_s = std::numeric_limits<double>::infinity();
  change.last_s = -change.first_s;
  std::vector<Eigen::Vector2d> points;
  double distance_sum = 0, depth_sum = 0;
  for (const std::size_t i : members) {
    const Evidence& e = ev[i];
    points.push_back(e.at_W);
    change.first_s = std::min(change.first_s, e.t_s);
    change.last_s = std::max(change.last_s, e.t_s);
    (e.sight_line ? change.sight_lines : change.landmarks)++;
    (e.sight_line ? depth_sum : distance_sum) += e.value_m;
  }
  if (change.last_s - change.first_s < c.min_span_s) return std::nullopt;
  change.footprint_W = detail::convex_hull(points);
  double extent = 0;
  for (const auto& p : change.footprint_W)
    for (const auto& q : change.footprint_W) extent = std::max(extent, (p - q).norm());
  if (extent < c.min_extent_m) return std::nullopt;
  if (change.landmarks > 0) change.mean_distance_m = distance_sum / static_cast<double>(change.landmarks);
  if (change.sight_lines > 0) change.mean_depth_m = depth_sum / static_cast<double>(change.sight_lines);
  const double share = static_cast<double>(change.landmarks) / static_cast<double>(members.size());
  change.kind = share >= 0.8 ? "missing" : share <= 0.2 ? "added" : "moved";
  return change;
}

}  // namespace

void TwinChangeConfig::validate() const {
  const auto positive = [](double v, const char* key) {
    if (!(v > 0) || !std::isfinite(v)) throw UsageError(std::string("twin changes: ") + key + " must be > 0");
  };
  positive(min_distance_m, "min_distance_m");
  positive(search_radius_m, "search_radius_m");
  positive(cluster_radius_m, "cluster_radius_m");
  if (!(search_radius_m > min_distance_m)) throw UsageError("twin changes: search_radius_m must exceed min_distance_m");
  if (!(min_quality >= 0 && min_quality <= 1)) throw UsageError("twin changes: min_quality must be in [0, 1]");
  if (!(observer_margin_m >= 0) || !(min_grazing_cos >= 0 && min_grazing_cos < 1) || !(min_span_s >= 0) ||
      !(min_extent_m >= 0) || min_evidence == 0) {
    throw UsageError("twin changes: observer_margin_m, min_span_s, min_extent_m >= 0, min_grazing_cos in [0, 1), "
                     "min_evidence >= 1");
  }
}

TwinChanges find_twin_changes(const Mesh& twin_W, const std::vector<LandmarkSighting>& sightings,
                              const TwinChangeConfig& config) {
  config.validate();
  if (twin_W.triangles.empty()) throw InputError("twin changes: the twin has no triangles to compare landmarks with");
  const detail::TriangleGrid grid(twin_W, 4.0);
  TwinChanges out;
  std::vector<Evidence> evidence;
  for (const LandmarkSighting& s : sightings) {
    if (!s.p_W.allFinite() || !s.observer_W.allFinite() || !(s.quality >= config.min_quality)) continue;
    ++out.landmarks_used;
    const double d = signed_distance(twin_W, grid, s.p_W, config.search_radius_m);
    if (std::abs(d) >= config.min_distance_m) {
      evidence.push_back({s.p_W.head<2>(), s.t_s, false, d});
      ++out.unexplained;
    }
    if (const auto crossing = sight_line_crossing(twin_W, grid, s, config)) {
      evidence.push_back(*crossing);
      ++out.sight_lines;
    }
  }
  for (const auto& members : cluster(evidence, config.cluster_radius_m)) {
    if (auto c = place(evidence, members, config)) out.places.push_back(std::move(*c));
  }
  std::sort(out.places.begin(), out.places.end(), [](const TwinChange& a, const TwinChange& b) {
    return a.landmarks + a.sight_lines > b.landmarks + b.sight_lines;
  });
  return out;
}

}  // namespace twinslam::twin

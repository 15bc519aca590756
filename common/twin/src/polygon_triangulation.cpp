// Ear clipping with hole bridging (D. Eberly, "Triangulation by Ear Clipping", 2002), in the polygon's plane.
#include "twinslam/twin/polygon_triangulation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

namespace twinslam::twin {
namespace {

struct V {
  Eigen::Vector2d p;
  int id;  // index into the caller's points
};
using Ring = std::vector<V>;

// Twice the signed area of (a, b, c): > 0 when counter-clockwise.
double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

double signed_area2(const Ring& r) {
  double s = 0.0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Eigen::Vector2d& a = r[i].p;
    const Eigen::Vector2d& b = r[(i + 1) % r.size()].p;
    s += a.x() * b.y() - b.x() * a.y();
  }
  return s;
}

// Drops vertices that repeat their predecessor (closing vertex included): zero-length edges break the angle tests.
Ring drop_repeats(const Ring& r, double eps) {
  Ring out;
  for (const V& v : r)
    if (out.empty() || (v.p - out.back().p).norm() > eps) out.push_back(v);
  while (out.size() > 1 && (out.front().p - out.back().p).norm() <= eps) out.pop_back();
  return out;
}

// Whether direction d leaves vertex p into the polygon's interior wedge (CCW polygon: from next-p round to prev-p).
bool in_wedge(const Eigen::Vector2d& prev, const Eigen::Vector2d& p, const Eigen::Vector2d& next,
              const Eigen::Vector2d& d) {
  auto angle = [](const Eigen::Vector2d& v) { return std::atan2(v.y(), v.x()); };
  auto wrap = [](double a) { return a < 0 ? a + 2 * M_PI : a; };
  const double a_next = angle(next - p);
  const double sweep = wrap(angle(prev - p) - a_next);
  const double rel = wrap(angle(d) - a_next);
  return rel > 0.0 && rel < sweep;
}

// Splices a clockwise hole into the counter-clockwise outer ring through a bridge from the hole's rightmost vertex M
// to a mutually visible outer vertex P: outer[..P], hole[M..M], P, outer[P+1..].
void bridge_hole(Ring& outer, const Ring& hole, double eps) {
  std::size_t mi = 0;
  for (std::size_t i = 1; i < hole.size(); ++i)
    if (hole[i].p.x() > hole[mi].p.x()) mi = i;
  const Eigen::Vector2d M = hole[mi].p;
  const std::size_t n = outer.size();
  // Nearest crossing of the ray M + t (1, 0), t >= 0, with an outer edge; P = that edge's endpoint further right.
  double best_x = std::numeric_limits<double>::infinity();
  std::size_t pi = n;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& a = outer[i].p;
    const Eigen::Vector2d& b = outer[(i + 1) % n].p;
    if ((a.y() > M.y()) == (b.y() > M.y()) && a.y() != M.y() && b.y() != M.y()) continue;
    if (a.y() == b.y()) continue;  // on the ray: its endpoints are found through the neighbouring edges
    const double x = a.x() + (M.y() - a.y()) / (b.y() - a.y()) * (b.x() - a.x());
    if (x >= M.x() - eps && x < best_x) {
      best_x = x;
      if (a.y() == M.y()) pi = i;  // the ray hits a vertex: that vertex is P
      else if (b.y() == M.y()) pi = (i + 1) % n;
      else pi = a.x() > b.x() ? i : (i + 1) % n;
    }
  }
  if (pi == n) {  // no crossing (hole not inside the outer ring): bridge to the nearest outer vertex
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n; ++i)
      if ((outer[i].p - M).squaredNorm() < best) best = (outer[i].p - M).squaredNorm(), pi = i;
  }
  const Eigen::Vector2d I(best_x, M.y());
  Eigen::Vector2d P = outer[pi].p;
  // A reflex outer vertex inside triangle (M, I, P) would block the view of P: take the one closest in angle to the ray.
  if (std::isfinite(best_x) && (P - I).norm() > eps) {
    const bool ccw = cross(M, I, P) > 0;
    double best_angle = std::numeric_limits<double>::infinity(), best_dist = best_angle;
    for (std::size_t j = 0; j < n; ++j) {
      const Eigen::Vector2d& q = outer[j].p;
      if (cross(outer[(j + n - 1) % n].p, q, outer[(j + 1) % n].p) > 0) continue;  // convex: cannot block
      const double s1 = cross(M, I, q), s2 = cross(I, P, q), s3 = cross(P, M, q);
      const bool inside = ccw ? (s1 >= 0 && s2 >= 0 && s3 >= 0) : (s1 <= 0 && s2 <= 0 && s3 <= 0);
      if (!inside || (q - M).norm() <= eps) continue;
      const double ang = std::atan2(std::abs(q.y() - M.y()), q.x() - M.x()), dist = (q - M).norm();
      if (ang < best_angle - 1e-12 || (ang <= best_angle + 1e-12 && dist < best_dist)) {
        best_angle = ang, best_dist = dist, pi = j, P = q;
      }
    }
  }
  // P may appear twice after earlier bridges: use the copy whose interior wedge looks at M.
  for (std::size_t j = 0; j < n; ++j)
    if ((outer[j].p - P).norm() <= eps && in_wedge(outer[(j + n - 1) % n].p, outer[j].p, outer[(j + 1) % n].p, M - P)) {
      pi = j;
      break;
    }
  Ring merged(outer.begin(), outer.begin() + static_cast<std::ptrdiff_t>(pi) + 1);
  for (std::size_t k = 0; k <= hole.size(); ++k) merged.push_back(hole[(mi + k) % hole.size()]);
  merged.push_back(outer[pi]);
  merged.insert(merged.end(), outer.begin() + static_cast<std::ptrdiff_t>(pi) + 1, outer.end());
  outer = std::move(merged);
}

void ear_clip(const Ring& poly, double eps_area, std::vector<Eigen::Vector3i>& out) {
  const std::size_t n = poly.size();
  std::vector<std::size_t> prev(n), next(n);
  for (std::size_t i = 0; i < n; ++i) prev[i] = (i + n - 1) % n, next[i] = (i + 1) % n;
  auto emit = [&](std::size_t a, std::size_t b, std::size_t c) {
    if (cross(poly[a].p, poly[b].p, poly[c].p) > eps_area) out.emplace_back(poly[a].id, poly[b].id, poly[c].id);
  };
  auto is_ear = [&](std::size_t b) {
    const std::size_t a = prev[b], c = next[b];
    const Eigen::Vector2d &pa = poly[a].p, &pb = poly[b].p, &pc = poly[c].p;
    if (cross(pa, pb, pc) <= eps_area) return false;
    for (std::size_t j = next[c]; j != a; j = next[j]) {
      const Eigen::Vector2d& q = poly[j].p;
      if (q == pa || q == pb || q == pc) continue;  // bridge duplicates of the ear's own corners
      if (cross(poly[prev[j]].p, q, poly[next[j]].p) > eps_area) continue;  // only reflex vertices can intrude
      if (cross(pa, pb, q) >= 0 && cross(pb, pc, q) >= 0 && cross(pc, pa, q) >= 0) return false;
    }
    return true;
  };
  std::size_t remaining = n, cur = 0;
  while (remaining > 3) {
    std::size_t pick = n;
    for (std::size_t k = 0, v = cur; k < remaining; ++k, v = next[v]) {
      const double c = cross(poly[prev[v]].p, poly[v].p, poly[next[v]].p);
      const bool straight = std::abs(c) <= eps_area && (poly[v].p - poly[prev[v]].p).dot(poly[next[v]].p - poly[v].p) >= 0;
      if (straight || is_ear(v)) {
        pick = v;
        break;
      }
    }
    if (pick == n) {  // rounding left no clean ear (self-touching input): clip the most convex corner
      double best = -std::numeric_limits<double>::infinity();
      for (std::size_t k = 0, v = cur; k < remaining; ++k, v = next[v]) {
        const double c = cross(poly[prev[v]].p, poly[v].p, poly[next[v]].p);
        if (c > best) best = c, pick = v;
      }
    }
    emit(prev[pick], pick, next[pick]);
    next[prev[pick]] = next[pick];
    prev[next[pick]] = prev[pick];
    cur = next[pick];
    --remaining;
  }
  emit(prev[cur], cur, next[cur]);
}

}  // namespace

Eigen::Vector3d newell_normal(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& ring) {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < ring.size(); ++i) n += points[ring[i]].cross(points[ring[(i + 1) % ring.size()]]);
  return n;
}

std::vector<Eigen::Vector3i> triangulate_polygon(const std::vector<Eigen::Vector3d>& points,
                                                 const std::vector<std::vector<int>>& rings) {
  std::vector<Eigen::Vector3i> tris;
  if (rings.empty() || rings[0].size() < 3) return tris;
  for (const auto& ring : rings)
    for (int id : ring)
      if (id < 0 || static_cast<std::size_t>(id) >= points.size()) return tris;
  // Work relative to the outer ring's centroid: projected CRS coordinates (1e5 m) would cost digits in the crosses.
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (int id : rings[0]) centroid += points[id];
  centroid /= static_cast<double>(rings[0].size());
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < rings[0].size(); ++i)
    normal += (points[rings[0][i]] - centroid).cross(points[rings[0][(i + 1) % rings[0].size()]] - centroid);
  double extent = 0.0;
  for (int id : rings[0]) extent = std::max(extent, (points[id] - centroid).norm());
  if (extent <= 0.0 || normal.norm() <= 1e-12 * extent * extent) return tris;
  normal.normalize();
  // Right-handed plane basis (u, v, normal): the outer ring is counter-clockwise in (u, v).
  const Eigen::Vector3d u = normal.unitOrthogonal(), v = normal.cross(u);
  const double eps = 1e-9 * extent, eps_area = 1e-12 * extent * extent;
  auto project = [&](const std::vector<int>& ring) {
    Ring r;
    for (int id : ring) r.push_back({Eigen::Vector2d((points[id] - centroid).dot(u), (points[id] - centroid).dot(v)), id});
    return drop_repeats(r, eps);
  };
  Ring outer = project(rings[0]);
  if (outer.size() < 3 || signed_area2(outer) <= eps_area) return tris;
  std::vector<Ring> holes;
  for (std::size_t h = 1; h < rings.size(); ++h) {
    Ring hole = project(rings[h]);
    if (hole.size() < 3 || std::abs(signed_area2(hole)) <= eps_area) continue;
    if (signed_area2(hole) > 0) std::reverse(hole.begin(), hole.end());  // holes run clockwise
    holes.push_back(std::move(hole));
  }
  // Rightmost holes first, so each bridge goes to the outer ring or to a hole already merged (Eberly).
  auto max_x = [](const Ring& r) {
    double m = -std::numeric_limits<double>::infinity();
    for (const V& q : r) m = std::max(m, q.p.x());
    return m;
  };
  std::sort(holes.begin(), holes.end(), [&](const Ring& a, const Ring& b) { return max_x(a) > max_x(b); });
  for (const Ring& hole : holes) bridge_hole(outer, hole, eps);
  ear_clip(outer, eps_area, tris);
  return tris;
}

}  // namespace twinslam::twin

#include "twinslam/sim/world/signal_tracer.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>  // cross

namespace twinslam::sim {

namespace {

constexpr double kMaxFacadeNormalZ = 0.25;  // within ~14 deg of vertical: walls reflect, sloped roofs do not
constexpr double kSelfHit_m = 0.05;          // start offset: the float BVH must not re-hit the surface we leave
constexpr double kSky_m = 1e5;               // a ray that clears the city over this distance has left it
constexpr double kMinIncidenceCos = 1e-6;    // s·n floor: keeps the reflection point h / (s·n) away finite
constexpr int kMaxCellsPerAxis = 4096;       // a stray far-away triangle must not blow the grid up

// Grid cell of coordinate v along one axis, clamped to the grid (callers reject windows entirely outside it).
int cell_index(double v, double origin, double cell_m, int n) {
  return static_cast<int>(std::clamp(std::floor((v - origin) / cell_m), 0.0, n - 1.0));  // clamp first: no int overflow
}

}  // namespace

SignalTracer::SignalTracer(const EmbreeScene& scene, SignalTracerConfig config) : scene_(scene), config_(config) {
  const TriMesh& mesh = scene.mesh();
  for (std::size_t i = 0; i < mesh.num_triangles(); ++i) {
    if (mesh.kind[i] != SurfaceKind::kFacade || mesh.area(i) < config_.min_facade_area_m2) continue;
    const Eigen::Vector3d n = mesh.normal(i);
    if (std::abs(n.z()) > kMaxFacadeNormalZ) continue;
    const auto& t = mesh.triangles[i];
    Facade f;
    f.n_W = n;
    f.a_W = mesh.p_W[t[0]];
    const Eigen::Vector2d lo = f.a_W.head<2>().cwiseMin(mesh.p_W[t[1]].head<2>()).cwiseMin(mesh.p_W[t[2]].head<2>());
    const Eigen::Vector2d hi = f.a_W.head<2>().cwiseMax(mesh.p_W[t[1]].head<2>()).cwiseMax(mesh.p_W[t[2]].head<2>());
    f.box_xy << lo, hi;
    f.triangle = static_cast<std::uint32_t>(i);
    facades_.push_back(f);
  }
  build_grid();
}

void SignalTracer::build_grid() {
  if (facades_.empty()) return;
  Eigen::Vector2d lo = facades_[0].box_xy.head<2>(), hi = facades_[0].box_xy.tail<2>();
  for (const Facade& f : facades_) {
    lo = lo.cwiseMin(f.box_xy.head<2>());
    hi = hi.cwiseMax(f.box_xy.tail<2>());
  }
  grid_origin_xy_ = lo;
  cell_m_ = std::max(config_.grid_cell_m, (hi - lo).maxCoeff() / (kMaxCellsPerAxis - 1));
  nx_ = static_cast<int>((hi.x() - lo.x()) / cell_m_) + 1;
  ny_ = static_cast<int>((hi.y() - lo.y()) / cell_m_) + 1;
  const auto cell = [&](double v, double o, int n) { return cell_index(v, o, cell_m_, n); };
  // Two passes (count, then fill) give a compact CSR layout: one allocation, cache-friendly cell scans.
  cell_start_.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<std::uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
    for (std::uint32_t k = 0; k < facades_.size(); ++k) {
      Facade& f = facades_[k];
      f.cell_x0 = cell(f.box_xy[0], lo.x(), nx_);
      f.cell_y0 = cell(f.box_xy[1], lo.y(), ny_);
      const int x1 = cell(f.box_xy[2], lo.x(), nx_), y1 = cell(f.box_xy[3], lo.y(), ny_);
      for (int iy = f.cell_y0; iy <= y1; ++iy)
        for (int ix = f.cell_x0; ix <= x1; ++ix) {
          const std::size_t c = static_cast<std::size_t>(iy) * nx_ + ix;
          if (pass == 0) ++cell_start_[c + 1];
          else cell_items_[fill[c]++] = k;
        }
    }
    if (pass == 0) {
      for (std::size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
      cell_items_.resize(cell_start_.back());
    }
  }
}

SignalPath SignalTracer::trace(const Eigen::Vector3d& p_W, const Eigen::Vector3d& to_satellite_W,
                               bool also_with_line_of_sight) const {
  SignalPath path;
  RayHit hit;
  if (!scene_.intersect(p_W, to_satellite_W, kSelfHit_m, kSky_m, &hit)) {
    path.line_of_sight = true;
    if (!also_with_line_of_sight) return path;
  }
  // Candidates come sorted by extra path, so the first clear one is the shortest bounce and costs the fewest rays.
  for (const Bounce& b : mirror_bounces(p_W, to_satellite_W)) {
    if (!bounce_is_clear(p_W, to_satellite_W, b)) continue;
    path.reflected = true;
    path.extra_path_m = b.extra_path_m;
    path.reflection_point_W = b.point_W;
    path.building = scene_.mesh().building_id[facades_[b.facade].triangle];
    break;
  }
  return path;
}

std::vector<SignalTracer::Bounce> SignalTracer::mirror_bounces(const Eigen::Vector3d& p_W,
                                                                const Eigen::Vector3d& s_W) const {
  std::vector<Bounce> bounces;
  if (facades_.empty()) return bounces;
  const double r = config_.max_reflection_distance_m;
  const auto cell = [&](double v, double o, int n) { return cell_index(v, o, cell_m_, n); };
  const Eigen::Vector2d lo = p_W.head<2>().array() - r, hi = p_W.head<2>().array() + r;
  const Eigen::Vector2d far = grid_origin_xy_ + cell_m_ * Eigen::Vector2d(nx_, ny_);
  if (hi.x() < grid_origin_xy_.x() || hi.y() < grid_origin_xy_.y() || lo.x() > far.x() || lo.y() > far.y())
    return bounces;
  const int qx0 = cell(lo.x(), grid_origin_xy_.x(), nx_), qx1 = cell(hi.x(), grid_origin_xy_.x(), nx_);
  const int qy0 = cell(lo.y(), grid_origin_xy_.y(), ny_), qy1 = cell(hi.y(), grid_origin_xy_.y(), ny_);
  for (int iy = qy0; iy <= qy1; ++iy)
    for (int ix = qx0; ix <= qx1; ++ix) {
      const std::size_t c = static_cast<std::size_t>(iy) * nx_ + ix;
      for (std::uint32_t i = cell_start_[c]; i < cell_start_[c + 1]; ++i) {
        const Facade& f = facades_[cell_items_[i]];
        // A facade spanning several cells is seen only in the first cell of its box inside the query window.
        if (ix != std::max(f.cell_x0, qx0) || iy != std::max(f.cell_y0, qy0)) continue;
        const double sn = s_W.dot(f.n_W);  // > 0: the satellite shines on the wall's outer side
        const double h = (p_W - f.a_W).dot(f.n_W);  // > 0: the receiver stands in front of the wall
        if (sn <= kMinIncidenceCos || h <= kSelfHit_m) continue;
        const Eigen::Vector2d gap = (f.box_xy.head<2>() - p_W.head<2>()).cwiseMax(p_W.head<2>() - f.box_xy.tail<2>());
        if (gap.cwiseMax(0.0).norm() > r) continue;
        // Mirror image p' = p - 2 h n; the line p' + t s meets the wall plane at t = h / (s·n).
        const Eigen::Vector3d x_W = p_W - 2 * h * f.n_W + (h / sn) * s_W;
        if (!inside_triangle(f.triangle, x_W, f.n_W)) continue;
        bounces.push_back({2 * h * sn, cell_items_[i], x_W});
      }
    }
  std::sort(bounces.begin(), bounces.end(),
            [](const Bounce& a, const Bounce& b) { return a.extra_path_m < b.extra_path_m; });
  return bounces;
}

bool SignalTracer::inside_triangle(std::uint32_t triangle, const Eigen::Vector3d& x_W,
                                   const Eigen::Vector3d& n_W) const {
  // x lies in the plane; it is inside when it is left of every counter-clockwise edge (seen along -n). The small
  // negative tolerance keeps points on the shared diagonal of a quad from falling between its two triangles.
  const TriMesh& mesh = scene_.mesh();
  const auto& t = mesh.triangles[triangle];
  constexpr double kEdgeTolerance_m2 = 1e-6;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d& a = mesh.p_W[t[k]];
    const Eigen::Vector3d& b = mesh.p_W[t[(k + 1) % 3]];
    if (!((b - a).cross(x_W - a).dot(n_W) >= -kEdgeTolerance_m2)) return false;  // NaN is outside too
  }
  return true;
}

bool SignalTracer::bounce_is_clear(const Eigen::Vector3d& p_W, const Eigen::Vector3d& s_W, const Bounce& b) const {
  RayHit hit;
  // Leg receiver -> wall: anything closer than the wall itself blocks it (a receiver within 10 cm has no room for
  // an obstacle, and its ray interval would be empty).
  const Eigen::Vector3d to_wall = b.point_W - p_W;
  const double d = to_wall.norm();
  if (d > 2 * kSelfHit_m && scene_.intersect(p_W, to_wall / d, kSelfHit_m, d - kSelfHit_m, &hit)) return false;
  // Leg wall -> satellite, started just in front of the wall so the wall itself is not hit.
  const Eigen::Vector3d start_W = b.point_W + kSelfHit_m * facades_[b.facade].n_W;
  return !scene_.intersect(start_W, s_W, 0.0, kSky_m, &hit);
}

}  // namespace twinslam::sim

// Street grid, blocks, lots and building shells of the procedural city; details come from city_details.cpp.
#include <algorithm>
#include <cmath>

#include "city_parts.hpp"
#include "twinslam/core/error.hpp"

namespace twinslam::sim {
namespace {

using detail::add_quad_out;

// Counter-clockwise rectangle outline.
std::vector<Eigen::Vector2d> rect_outline(const Eigen::Vector4d& r) {
  return {{r[0], r[1]}, {r[2], r[1]}, {r[2], r[3]}, {r[0], r[3]}};
}

// L-shape: the rectangle r with the quadrant of size cut_e x cut_n at corner k (0..3 in rect_outline order) removed.
void make_l_shape(const Eigen::Vector4d& r, int k, double cut_e, double cut_n, Building* b) {
  const auto corners = rect_outline(r);
  for (int i = 0; i < 4; ++i) {
    if (i != k) {
      b->outline_W.push_back(corners[i]);
      continue;
    }
    const Eigen::Vector2d p = corners[i];
    const Eigen::Vector2d prev = corners[(i + 3) % 4], next = corners[(i + 1) % 4];
    auto step = [&](const Eigen::Vector2d& towards) {  // move from p towards a neighbour by the cut on that axis
      const Eigen::Vector2d d = (towards - p).normalized();
      return Eigen::Vector2d(p + d * (std::abs(d.x()) > 0.5 ? cut_e : cut_n));
    };
    const Eigen::Vector2d a = step(prev), c = step(next);
    b->outline_W.insert(b->outline_W.end(), {a, Eigen::Vector2d(a + c - p), c});
  }
  const Eigen::Vector2d p = corners[k];
  const bool top = p.y() == r[3], right = p.x() == r[2];
  // Full-width strip away from the cut, and the partial strip beside it.
  b->rects_W.emplace_back(r[0], top ? r[1] : r[1] + cut_n, r[2], top ? r[3] - cut_n : r[3]);
  b->rects_W.emplace_back(right ? r[0] : r[0] + cut_e, top ? r[3] - cut_n : r[1], right ? r[2] - cut_e : r[2],
                          top ? r[3] : r[1] + cut_n);
}

// Gabled roof over rectangle r from eave height h with ridge rise [m]; ridge along the longer side.
void add_gable(TriMesh* mesh, const Eigen::Vector4d& r, double h, double rise, int id) {
  const bool along_e = (r[2] - r[0]) >= (r[3] - r[1]);
  const double x0 = r[0], y0 = r[1], x1 = r[2], y1 = r[3];
  if (along_e) {
    const double ym = 0.5 * (y0 + y1);
    add_quad_out(mesh, {x0, y0, h}, {x1, y0, h}, {x1, ym, h + rise}, {x0, ym, h + rise}, {0, -1, 1},
                 SurfaceKind::kRoof, id);
    add_quad_out(mesh, {x0, y1, h}, {x1, y1, h}, {x1, ym, h + rise}, {x0, ym, h + rise}, {0, 1, 1},
                 SurfaceKind::kRoof, id);
    mesh->add_triangle({x0, y1, h}, {x0, ym, h + rise}, {x0, y0, h}, SurfaceKind::kFacade, id);
    mesh->add_triangle({x1, y0, h}, {x1, ym, h + rise}, {x1, y1, h}, SurfaceKind::kFacade, id);
  } else {
    const double xm = 0.5 * (x0 + x1);
    add_quad_out(mesh, {x0, y0, h}, {x0, y1, h}, {xm, y1, h + rise}, {xm, y0, h + rise}, {-1, 0, 1},
                 SurfaceKind::kRoof, id);
    add_quad_out(mesh, {x1, y0, h}, {x1, y1, h}, {xm, y1, h + rise}, {xm, y0, h + rise}, {1, 0, 1},
                 SurfaceKind::kRoof, id);
    mesh->add_triangle({x0, y0, h}, {xm, y0, h + rise}, {x1, y0, h}, SurfaceKind::kFacade, id);
    mesh->add_triangle({x1, y1, h}, {xm, y1, h + rise}, {x0, y1, h}, SurfaceKind::kFacade, id);
  }
}

Eigen::Vector4d inset(const Eigen::Vector4d& r, double d) { return {r[0] + d, r[1] + d, r[2] - d, r[3] - d}; }

class CityBuilder {
 public:
  CityBuilder(const CityConfig& config, std::uint64_t seed, const CityLayout& layout)
      : config_(config), layout_(layout), rng_(seed), block_seed_(hash64(seed ^ 0xB10C5ULL)) {
    city_.layout = layout;
  }

  City build() {
    const double half = 0.5 * config_.size_m;
    const double pitch = layout_.block_size_m + layout_.street_width_m;
    int n = std::max(1, static_cast<int>(std::floor(config_.size_m / pitch)));
    if (n % 2 == 0) --n;  // odd count: the centre block sits at the origin and holds the tower
    const int centre = n / 2;
    add_ground(half);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        const Eigen::Vector2d c((i - centre) * pitch, (j - centre) * pitch);
        const Eigen::Vector4d block(c.x() - 0.5 * layout_.block_size_m, c.y() - 0.5 * layout_.block_size_m,
                                    c.x() + 0.5 * layout_.block_size_m, c.y() + 0.5 * layout_.block_size_m);
        if (i == centre && j == centre) {
          add_tower(c);
          continue;
        }
        add_street_furniture(block, half);
        if (config_.blocks == "identical") {
          // Every block from the same draws, so its buildings, roofs, bands and balconies repeat at each block
          // pitch; the street furniture around it stays the main stream's (cars and trees differ, as in a real
          // street of identical blocks).
          const Rng main = rng_;
          rng_ = Rng(block_seed_);
          add_block(block);
          rng_ = main;
        } else {
          add_block(block);
        }
      }
    }
    SceneHints& h = city_.hints;
    const Building& tower = city_.buildings[city_.tallest_id];
    h.tall_building_center_W = Eigen::Vector2d::Zero();
    h.tall_building_radius_m = (tower.outline_W[0] - tower.outline_W[2]).norm() / 2;
    h.tall_building_height_m = tower.height_m;
    h.ground_z_m = 0;
    h.extent_W = {-half, -half, half, half};
    add_street_hints(n, centre, pitch);
    return std::move(city_);
  }

 private:
  // What a `streets` flight plans with: the street centrelines between the n x n blocks, every footprint, the parks
  // and how high the street furniture reaches. Read from what was built; draws nothing.
  void add_street_hints(int n, int centre, double pitch) {
    SceneHints& h = city_.hints;
    for (int k = 0; k + 1 < n; ++k) h.streets.east_m.push_back((k - centre + 0.5) * pitch);
    h.streets.north_m = h.streets.east_m;
    h.streets.width_m = layout_.street_width_m;
    for (const Building& b : city_.buildings) h.buildings.push_back({b.id, b.rects_W, b.height_m, b.top_m});
    const TriMesh& m = city_.mesh;
    for (std::size_t i = 0; i < m.num_triangles(); ++i) {
      if (m.building_id[i] != kNoBuilding || m.kind[i] != SurfaceKind::kDetail) continue;
      for (int c = 0; c < 3; ++c) h.furniture_top_m = std::max(h.furniture_top_m, m.p_W[m.triangles[i][c]].z());
    }
  }

  void add_ground(double half) {
    const double s = layout_.ground_patch_m;
    for (double x = -half; x < half - 1e-9; x += s) {
      for (double y = -half; y < half - 1e-9; y += s) {
        const double x1 = std::min(x + s, half), y1 = std::min(y + s, half);
        city_.mesh.add_quad({x, y, 0}, {x1, y, 0}, {x1, y1, 0}, {x, y1, 0}, SurfaceKind::kGround, kNoBuilding);
      }
    }
  }

  Building& new_building() {
    Building b;
    b.id = static_cast<int>(city_.buildings.size());
    city_.buildings.push_back(b);
    return city_.buildings.back();
  }

  void add_tower(const Eigen::Vector2d& c) {
    Building& b = new_building();
    const double hs = 14.0;  // 28 m x 28 m footprint
    const Eigen::Vector4d r(c.x() - hs, c.y() - hs, c.x() + hs, c.y() + hs);
    b.outline_W = rect_outline(r);
    b.rects_W = {r};
    b.height_m = config_.height_m[1];
    add_prism(&city_.mesh, b.outline_W, b.rects_W, 0, b.height_m, SurfaceKind::kFacade, SurfaceKind::kRoof, b.id);
    const Eigen::Vector4d pent = inset(r, 8.0);  // penthouse: a roof structure the twin keeps
    add_box(&city_.mesh, {pent[0], pent[1], b.height_m}, {pent[2], pent[3], b.height_m + 4}, SurfaceKind::kFacade,
            SurfaceKind::kRoof, b.id);
    b.top_m = b.height_m + 4;
    detail::add_floor_bands(&city_.mesh, b, layout_.floor_height_m);
    detail::add_rooftop_boxes(&city_.mesh, inset(r, 1.0), b.height_m, b.id, &rng_);
    city_.tallest_id = b.id;
  }

  void add_block(const Eigen::Vector4d& block) {
    const bool identical = config_.blocks == "identical";  // no parks: a street of identical blocks throughout
    if (!identical && rng_.chance(0.12)) {  // park: grass and trees, no building
      const int trees = 8 + rng_.integer(14);
      for (int k = 0; k < trees; ++k)
        detail::add_tree(&city_.mesh, {rng_.uniform(block[0] + 3, block[2] - 3), rng_.uniform(block[1] + 3, block[3] - 3)},
                         &rng_);
      city_.empty_lots_W.push_back(block);
      city_.hints.open_areas_W.push_back(block);
      return;
    }
    std::vector<Eigen::Vector4d> lots;
    const double mx = 0.5 * (block[0] + block[2]), my = 0.5 * (block[1] + block[3]);
    switch (rng_.integer(3)) {
      case 0: lots = {block}; break;
      case 1:
        if (rng_.chance(0.5)) lots = {{block[0], block[1], mx, block[3]}, {mx, block[1], block[2], block[3]}};
        else lots = {{block[0], block[1], block[2], my}, {block[0], my, block[2], block[3]}};
        break;
      default:
        lots = {{block[0], block[1], mx, my}, {mx, block[1], block[2], my}, {block[0], my, mx, block[3]},
                {mx, my, block[2], block[3]}};
    }
    for (const auto& lot : lots) {
      if (rng_.chance(0.08)) {  // parking lot
        for (double x = lot[0] + 4; x < lot[2] - 4; x += 3.0)
          if (rng_.chance(0.6)) detail::add_car(&city_.mesh, {x, 0.5 * (lot[1] + lot[3])}, false, &rng_);
        city_.empty_lots_W.push_back(lot);
        continue;
      }
      add_building(lot);
    }
  }

  void add_building(const Eigen::Vector4d& lot) {
    Building& b = new_building();
    const Eigen::Vector4d r = inset(lot, rng_.uniform(1.5, 4.0));
    const double w = r[2] - r[0], d = r[3] - r[1];
    const bool l_shape = w > 14 && d > 14 && rng_.chance(0.3);
    if (l_shape) {
      make_l_shape(r, rng_.integer(4), w * rng_.uniform(0.35, 0.6), d * rng_.uniform(0.35, 0.6), &b);
    } else {
      b.outline_W = rect_outline(r);
      b.rects_W = {r};
    }
    const double h_min = config_.height_m[0], h_cap = h_min + 0.6 * (config_.height_m[1] - h_min);
    // Floors snap to whole storeys so window rows and floor bands line up with the roof.
    const double raw = h_min + (h_cap - h_min) * std::pow(rng_.uniform(), 1.5);
    b.height_m = std::max(layout_.floor_height_m, std::round(raw / layout_.floor_height_m) * layout_.floor_height_m);
    b.top_m = b.height_m;
    const bool gable = !l_shape && b.height_m < 20 && rng_.chance(0.4);
    add_prism(&city_.mesh, b.outline_W, gable ? std::vector<Eigen::Vector4d>{} : b.rects_W, 0, b.height_m,
              SurfaceKind::kFacade, SurfaceKind::kRoof, b.id);
    if (gable) {
      const double rise = rng_.uniform(2.5, 5.0);
      add_gable(&city_.mesh, r, b.height_m, rise, b.id);
      b.top_m += rise;
    } else {
      const Eigen::Vector4d& main = b.rects_W.front();
      if ((main[2] - main[0]) * (main[3] - main[1]) > 300 && rng_.chance(0.35)) {
        const Eigen::Vector4d pent = inset(main, 0.25 * std::min(main[2] - main[0], main[3] - main[1]));
        add_box(&city_.mesh, {pent[0], pent[1], b.height_m}, {pent[2], pent[3], b.height_m + 3},
                SurfaceKind::kFacade, SurfaceKind::kRoof, b.id);
        b.top_m += 3;
      }
      if (rng_.chance(0.7)) detail::add_rooftop_boxes(&city_.mesh, main, b.height_m, b.id, &rng_);
    }
    if (rng_.chance(0.6)) detail::add_floor_bands(&city_.mesh, b, layout_.floor_height_m);
    if (rng_.chance(0.35)) detail::add_balconies(&city_.mesh, b, layout_.floor_height_m, &rng_);
  }

  // Trees 1.5 m and parked cars 3.6 m into the street along each block edge; the ring around the tower stays clear
  // so the loops trajectory has room.
  void add_street_furniture(const Eigen::Vector4d& block, double half) {
    const double clear = 0.5 * layout_.block_size_m + layout_.street_width_m;
    auto free = [&](const Eigen::Vector2d& p) {
      return (std::abs(p.x()) > clear || std::abs(p.y()) > clear) && std::abs(p.x()) < half - 1 &&
             std::abs(p.y()) < half - 1;
    };
    for (int side = 0; side < 4; ++side) {
      const bool horizontal = side < 2;  // south/north edges run east
      for (double s = 4; s < layout_.block_size_m - 4; s += 6.0) {
        for (const double off : {1.5, 3.6}) {
          Eigen::Vector2d p;
          if (horizontal) p = {block[0] + s, side == 0 ? block[1] - off : block[3] + off};
          else p = {side == 2 ? block[0] - off : block[2] + off, block[1] + s};
          if (!free(p)) continue;
          if (off < 2 && rng_.chance(0.3)) detail::add_tree(&city_.mesh, p, &rng_);
          if (off > 2 && rng_.chance(0.3)) detail::add_car(&city_.mesh, p, horizontal, &rng_);
        }
      }
    }
  }

  const CityConfig& config_;
  CityLayout layout_;
  Rng rng_;
  std::uint64_t block_seed_;  // the stream every block draws from when config_.blocks is "identical"
  City city_;
};

}  // namespace

City build_city(const CityConfig& config, std::uint64_t seed, const CityLayout& layout) {
  if (config.source != "procedural")
    throw InputError("city.source: build_city makes procedural cities only, got '" + config.source + "'");
  if (!(config.size_m >= 60.0 && config.size_m <= 20000.0))
    throw InputError("city.size_m: must be in [60, 20000] m, got " + std::to_string(config.size_m));
  if (!(config.height_m[0] >= 3.0 && config.height_m[1] > config.height_m[0] + 3.0 && config.height_m[1] < 1000.0))
    throw InputError("city.height_m: need 3 <= min < max - 3 < 1000 m");
  if (config.blocks != "varied" && config.blocks != "identical")
    throw InputError("city.blocks: must be varied or identical, got '" + config.blocks + "'");
  return CityBuilder(config, seed, layout).build();
}

}  // namespace twinslam::sim

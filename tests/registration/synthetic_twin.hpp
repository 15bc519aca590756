#pragma once
// A small synthetic city for the registration tests: a ground plane and four box buildings around a centre far from
// W's origin (so the pivot matters), straddling tile borders (e = 1200, n = 800 with 50 m tiles). The twin is an
// area-uniform jittered sampling of the surfaces with exact normals; the "estimator's" landmarks are fresh samples of
// the same surfaces with Gaussian noise, plus outliers, seen through a wrong T_WL.
#include <cmath>
#include <map>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "twinslam/registration/preprocess.hpp"
#include "twinslam/registration/twin_index.hpp"

namespace twinslam::registration::test {

struct Rect {  // origin + s u + t v, s, t in [0, 1]
  Eigen::Vector3d origin, u, v;
  Eigen::Vector3d normal() const { return u.cross(v).normalized(); }
  double area() const { return u.cross(v).norm(); }
};

struct PointSet {
  std::vector<Eigen::Vector3d> p_W, n_W;
};

inline const Eigen::Vector3d kCentre{1210.0, 810.0, 0.0};

// Ground 100 m x 100 m plus boxes (dx, dy, width, depth, height) relative to kCentre.
inline std::vector<Rect> city_surfaces() {
  const Eigen::Vector3d X = Eigen::Vector3d::UnitX(), Y = Eigen::Vector3d::UnitY(), Z = Eigen::Vector3d::UnitZ();
  std::vector<Rect> r{{kCentre + Eigen::Vector3d(-50, -50, 0), 100 * X, 100 * Y}};
  const double boxes[4][5] = {
      {-30, -25, 20, 15, 25}, {15, -20, 18, 22, 35}, {-20, 20, 25, 18, 20}, {25, 25, 15, 15, 45}};
  for (const auto& b : boxes) {
    const Eigen::Vector3d o = kCentre + Eigen::Vector3d(b[0], b[1], 0);
    const Eigen::Vector3d w = b[2] * X, d = b[3] * Y, h = b[4] * Z;
    r.push_back({o, h, w});      // south wall, normal -y
    r.push_back({o + w, h, d});  // east wall, +x... (h x d = -x: orientation is irrelevant for point-to-plane)
    r.push_back({o + d, w, h});  // north wall
    r.push_back({o, d, h});      // west wall
    r.push_back({o + h, w, d});  // roof
  }
  return r;
}

// Jittered grid of spacing `spacing` on each rectangle (deterministic for a seed).
inline PointSet sample_grid(const std::vector<Rect>& rects, double spacing, unsigned seed = 1) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(0.0, 1.0);
  PointSet out;
  for (const Rect& r : rects) {
    const int nu = std::max(1, static_cast<int>(r.u.norm() / spacing)),
              nv = std::max(1, static_cast<int>(r.v.norm() / spacing));
    for (int i = 0; i < nu; ++i) {
      for (int j = 0; j < nv; ++j) {
        const double s = (i + jitter(rng)) / nu, t = (j + jitter(rng)) / nv;
        out.p_W.push_back(r.origin + s * r.u + t * r.v);
        out.n_W.push_back(r.normal());
      }
    }
  }
  return out;
}

// `count` points area-uniform over the rectangles, Gaussian noise `noise_m` per coordinate.
inline std::vector<Eigen::Vector3d> sample_noisy(const std::vector<Rect>& rects, int count, double noise_m,
                                                 unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<double> areas;
  for (const Rect& r : rects) areas.push_back(r.area());
  std::discrete_distribution<int> pick(areas.begin(), areas.end());
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, noise_m);
  std::vector<Eigen::Vector3d> out;
  for (int k = 0; k < count; ++k) {
    const Rect& r = rects[static_cast<std::size_t>(pick(rng))];
    const double s = uni(rng), t = uni(rng);
    const Eigen::Vector3d e(noise(rng), noise(rng), noise(rng));
    out.push_back(r.origin + s * r.u + t * r.v + e);
  }
  return out;
}

// Outliers: uniform in the city's box (mostly far from any surface; some land near one, as bad triangulations do).
inline std::vector<Eigen::Vector3d> sample_outliers(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> xy(-50.0, 50.0), z(0.0, 45.0);
  std::vector<Eigen::Vector3d> out;
  for (int k = 0; k < count; ++k) out.push_back(kCentre + Eigen::Vector3d(xy(rng), xy(rng), z(rng)));
  return out;
}

// Splits a point set into 50 m tiles and adds them to the index.
inline std::map<twin::TileKey, PointSet> split_tiles(const PointSet& set, double tile = 50.0) {
  std::map<twin::TileKey, PointSet> tiles;
  for (std::size_t i = 0; i < set.p_W.size(); ++i) {
    const twin::TileKey k{static_cast<int>(std::floor(set.p_W[i].x() / tile)),
                          static_cast<int>(std::floor(set.p_W[i].y() / tile))};
    tiles[k].p_W.push_back(set.p_W[i]);
    tiles[k].n_W.push_back(set.n_W[i]);
  }
  return tiles;
}

inline TwinTileIndex make_index(const PointSet& set) {
  TwinTileIndex index(50.0);
  for (const auto& [key, t] : split_tiles(set)) index.add_tile(key, t.p_W, t.n_W);
  return index;
}

// dT about `pivot`: rotation `deg` about axis, then translation.
inline Eigen::Isometry3d offset_about(const Eigen::Vector3d& pivot, const Eigen::Vector3d& axis, double deg,
                                      const Eigen::Vector3d& t) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(deg * M_PI / 180.0, axis.normalized()).toRotationMatrix();
  T.translation() = pivot + t - T.linear() * pivot;
  return T;
}

// The estimator's view: true landmarks p_W (T_WL_true = identity, so p_L = p_W), guess T_WL = error, keyframe body
// at `body_W`. Registration should return correction = error^-1.
inline SourceInput make_source(const std::vector<Eigen::Vector3d>& p_true_W, const Eigen::Isometry3d& error,
                               const Eigen::Vector3d& body_W) {
  SourceInput in;
  for (const auto& p : p_true_W) in.landmarks.push_back({p, 1.0});
  in.T_WL = error;
  in.T_LB = Eigen::Isometry3d::Identity();
  in.T_LB.translation() = body_W;
  return in;
}

}  // namespace twinslam::registration::test

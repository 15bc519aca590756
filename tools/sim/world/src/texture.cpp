#include "twinslam/sim/world/texture.hpp"

#include <algorithm>
#include <cmath>

#include "twinslam/sim/world/random.hpp"

namespace twinslam::sim {
namespace {

// Hash of an integer lattice cell to [0, 1): one mix of the packed (i, j, salt) key; this runs several times per
// pixel, so it is kept to a single hash64.
float cell(std::int64_t i, std::int64_t j, std::uint64_t salt) {
  const std::uint64_t key = (static_cast<std::uint64_t>(i) * 0x9E3779B97F4A7C15ULL) ^
                            (static_cast<std::uint64_t>(j) * 0xC2B2AE3D27D4EB4FULL) ^ (salt * 0x165667B19E3779F9ULL);
  return static_cast<float>(hash64(key) >> 40) * 0x1.0p-24f;
}

// floor() as an integer without a libm call (the x86-64 baseline has no SSE4.1 round instruction).
inline std::int64_t ifloor(double x) {
  const auto i = static_cast<std::int64_t>(x);
  return i - (x < static_cast<double>(i));
}

// Bilinear value noise in [0, 1) with smoothstep weights.
float value_noise(double s, double t, std::uint64_t salt) {
  const std::int64_t i = ifloor(s), j = ifloor(t);
  double a = s - static_cast<double>(i), b = t - static_cast<double>(j);
  a = a * a * (3 - 2 * a);
  b = b * b * (3 - 2 * b);
  const float v00 = cell(i, j, salt), v10 = cell(i + 1, j, salt), v01 = cell(i, j + 1, salt),
              v11 = cell(i + 1, j + 1, salt);
  return static_cast<float>((v00 * (1 - a) + v10 * a) * (1 - b) + (v01 * (1 - a) + v11 * a) * b);
}

// Contrast kept for a pattern of period `period_m` seen at `footprint_m` per pixel: 1 above 4 px, 0 below 2 px.
float keep(double period_m, double footprint_m) {
  const double px = period_m / std::max(footprint_m, 1e-6);
  return static_cast<float>(std::clamp((px - 2.0) / 2.0, 0.0, 1.0));
}

// Grid of slabs/tiles: per-cell tone with dark joints; the mean is blended in when the cells get too small.
float tiles(double s, double t, double size_s, double size_t, double joint, float lo, float hi, std::uint64_t salt,
            double footprint_m) {
  const double cs = s / size_s, ct = t / size_t;
  const std::int64_t is = ifloor(cs), it = ifloor(ct);
  const double fs = cs - static_cast<double>(is), ft = ct - static_cast<double>(it);
  float v = lo + (hi - lo) * cell(is, it, salt);
  if (fs < joint / size_s || ft < joint / size_t) v *= 0.55f;
  const float mean = 0.5f * (lo + hi) * 0.95f;
  return mean + keep(std::min(size_s, size_t), footprint_m) * (v - mean);
}

}  // namespace

float albedo(const Eigen::Vector3d& p, const Eigen::Vector3d& n, SurfaceKind kind, int building, double footprint_m) {
  // Planar texture coordinates from the dominant normal axis (the city is axis-aligned; slopes use their plan view).
  const Eigen::Vector3d a = n.cwiseAbs();
  double s, t;
  if (a.z() >= a.x() && a.z() >= a.y()) s = p.x(), t = p.y();
  else if (a.x() >= a.y()) s = p.y(), t = p.z();
  else s = p.x(), t = p.z();
  const float grain = value_noise(s * 4.0, t * 4.0, 11) - 0.5f;  // fine surface grain, 0.25 m
  const float grain_keep = keep(0.5, footprint_m);
  float v = 0.4f;
  switch (kind) {
    case SurfaceKind::kGround: {
      // Paving slabs under a slowly varying wear pattern.
      v = tiles(s, t, 2.0, 2.0, 0.08, 0.22f, 0.48f, 21, footprint_m);
      v *= 0.75f + 0.5f * value_noise(s / 15.0, t / 15.0, 22);
      break;
    }
    case SurfaceKind::kFacade: {
      const std::uint64_t b = static_cast<std::uint64_t>(building + 1);
      const float wall = 0.32f + 0.3f * cell(building, 0, 31);
      const double cs = s / 3.0, ct = t / 3.0;  // one window per 3 m bay and 3 m storey
      const std::int64_t is = ifloor(cs), it = ifloor(ct);
      const double fs = cs - static_cast<double>(is), ft = ct - static_cast<double>(it);
      const bool window = fs > 0.22 && fs < 0.78 && ft > 0.3 && ft < 0.82;
      const float glass = 0.05f + 0.3f * cell(is, it, 32 + b);
      const float mean = 0.71f * wall + 0.29f * 0.2f;
      v = mean + keep(3.0, footprint_m) * ((window ? glass : wall) - mean);
      break;
    }
    case SurfaceKind::kRoof:
      v = a.z() > 0.95 ? tiles(s, t, 1.2, 1.2, 0.06, 0.3f, 0.6f, 41, footprint_m)
                       : tiles(s, t, 0.5, 0.35, 0.05, 0.18f, 0.42f, 42, footprint_m);
      break;
    case SurfaceKind::kDetail:
      v = tiles(s, t, 0.6, 0.6, 0.0, 0.25f, 0.6f, 51 + static_cast<std::uint64_t>(building + 1), footprint_m);
      break;
  }
  v += 0.12f * grain_keep * grain;
  return std::clamp(v, 0.0f, 0.72f);
}

float car_albedo(const Eigen::Vector3d& p_V, const Eigen::Vector3d& n_V, int part, float paint, double footprint_m) {
  // Parts and sizes as traffic.cpp builds them: body 0.25-1.0 m high, cabin 1.0 m up to 1.42-1.55 m from x = -0.7 l
  // to 0.4 l (l = half the length, 2.1-2.4 m), wheels. Thresholds in absolute metres fit every car of that range.
  if (part == 2) return 0.06f;  // tyres
  const double x = p_V.x(), y = std::abs(p_V.y()), z = p_V.z();
  const Eigen::Vector3d a = n_V.cwiseAbs();
  float detail = paint;
  double size_m = 1.0;  // how large the pattern is, for fading it out at a distance
  if (part == 1) {      // cabin: glass all round between the pillars, painted roof
    if (a.y() > 0.7) {
      if (x > -1.45 && x < 0.75 && std::abs(x + 0.35) > 0.07 && z > 1.06 && z < 1.36) detail = 0.1f;
    } else if (a.x() > 0.7) {
      if (y < 0.68 && z > 1.06 && z < 1.37) detail = n_V.x() > 0 ? 0.12f : 0.09f;
    }
  } else if (a.x() > 0.7) {  // body front and back: bumper, lights, grille
    size_m = 0.3;
    if (z < 0.45) detail = 0.1f;
    else if (n_V.x() > 0 && y > 0.5 && y < 0.8 && z > 0.65 && z < 0.85) detail = 0.7f;   // headlights
    else if (n_V.x() > 0 && y < 0.35 && z > 0.5 && z < 0.8) detail = 0.08f;             // grille
    else if (n_V.x() < 0 && y > 0.55 && y < 0.85 && z > 0.7 && z < 0.9) detail = 0.22f; // tail lights
  } else if (a.y() > 0.7) {  // body sides: dark sill, a door gap
    size_m = 0.3;
    if (z < 0.42) detail = 0.1f;
    else if (std::abs(x + 0.35) < 0.03 || std::abs(x - 0.75) < 0.03) detail = 0.5f * paint;
  }
  float v = paint + keep(size_m, footprint_m) * (detail - paint);
  const double s = a.z() > 0.7 ? x : a.x() > 0.7 ? p_V.y() : x;
  const float grain = value_noise(s * 6.0, z * 6.0, 61) - 0.5f;  // paint and dirt, 0.17 m
  v += 0.06f * keep(0.35, footprint_m) * grain;
  return std::clamp(v, 0.0f, 0.72f);
}

}  // namespace twinslam::sim

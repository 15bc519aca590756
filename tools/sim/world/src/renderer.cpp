#include "twinslam/sim/world/renderer.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <thread>

#include <embree3/rtcore.h>

#include "twinslam/core/error.hpp"
#include "twinslam/sim/world/random.hpp"
#include "twinslam/sim/world/texture.hpp"

namespace twinslam::sim {
namespace {

bool same(const CameraIntrinsics& a, const CameraIntrinsics& b) {
  return a.distortion == b.distortion && a.width == b.width && a.height == b.height && a.fu == b.fu && a.fv == b.fv &&
         a.cu == b.cu && a.cv == b.cv && a.coefficients == b.coefficients;
}

// Approximately Gaussian pixel noise from a hash (Irwin-Hall sum of four uniforms, unit variance): order-free, so
// threads cannot change it.
float pixel_noise(std::uint64_t seed, std::uint64_t pixel) {
  const std::uint64_t h = hash64(seed * 0x100000001B3ULL ^ hash64(pixel));
  float sum = 0;
  for (int k = 0; k < 4; ++k) sum += static_cast<float>((h >> (16 * k)) & 0xFFFF) * (1.0f / 65536.0f);
  return (sum - 2.0f) * 1.7320508f;  // sqrt(12 / 4)
}

// Sky where nothing is hit: brighter towards the horizon; a flat distant-ground grey below it.
float background(const Eigen::Vector3d& d_W) {
  if (d_W.z() < 0) return 110.0f;
  return static_cast<float>(240.0 - 35.0 * d_W.z());
}

}  // namespace

Renderer::Renderer(const TriMesh& world, const RenderConfig& config) : scene_(world), config_(config) {
  if (config_.threads < 1 || config_.threads > 64) throw InputError("render: threads must be in [1, 64]");
  if (!(config_.noise_sigma >= 0) || !(config_.ambient >= 0 && config_.ambient <= 1) || !(config_.max_range_m > 0) ||
      !(config_.sun_W.norm() > 0))
    throw InputError("render: noise_sigma >= 0, ambient in [0, 1], max_range_m > 0 and a nonzero sun direction");
  config_.sun_W.normalize();
}

std::shared_ptr<const std::vector<Eigen::Vector3f>> Renderer::bearings(const CameraModel& cam) const {
  std::lock_guard<std::mutex> lock(cache_mutex_);
  if (cached_bearings_ && same(cached_intrinsics_, cam.intrinsics())) return cached_bearings_;
  auto f = std::make_shared<std::vector<Eigen::Vector3f>>(static_cast<std::size_t>(cam.width()) * cam.height());
  for (int v = 0; v < cam.height(); ++v) {
    for (int u = 0; u < cam.width(); ++u) {
      Eigen::Vector3d f_C;
      (*f)[static_cast<std::size_t>(v) * cam.width() + u] =
          cam.unproject(Eigen::Vector2d(u, v), &f_C) ? Eigen::Vector3f(f_C.normalized().cast<float>())
                                                     : Eigen::Vector3f::Constant(std::nanf(""));
    }
  }
  cached_intrinsics_ = cam.intrinsics();
  cached_bearings_ = f;
  return f;
}

cv::Mat Renderer::render(const Eigen::Isometry3d& T_WC, const CameraModel& cam, std::uint64_t seed) const {
  const auto f_C = bearings(cam);
  cv::Mat image(cam.height(), cam.width(), CV_8UC1, cv::Scalar(0));
  const int n = std::min(config_.threads, (cam.height() + 3) / 4);
  std::vector<std::thread> workers;
  std::atomic<int> next_tile_row{0};
  for (int k = 1; k < n; ++k)
    workers.emplace_back([&] { render_rows(T_WC, cam, *f_C, seed, &next_tile_row, &image); });
  render_rows(T_WC, cam, *f_C, seed, &next_tile_row, &image);
  for (auto& w : workers) w.join();
  return image;
}

void Renderer::render_rows(const Eigen::Isometry3d& T_WC, const CameraModel& cam,
                           const std::vector<Eigen::Vector3f>& f_C, std::uint64_t seed, std::atomic<int>* next_tile_row,
                           cv::Mat* image) const {
  // Rays go to Embree in 4 x 4 pixel packets (rtcIntersect16, coherent flag): neighbouring primary rays traverse
  // the same BVH nodes, which measured about 2x faster than one rtcIntersect1 per pixel (bench/sim_render).
  // Threads take the next free row of tiles (dynamic: on a shared machine a statically split thread would straggle).
  constexpr int kTile = 4;
  const Eigen::Matrix3f R_WC = T_WC.linear().cast<float>();
  const Eigen::Vector3d c_W = T_WC.translation();
  const double pixel_angle = 1.0 / std::max(cam.intrinsics().fu, 1e-9);  // [rad per px] near the image centre
  const TriMesh& mesh = scene_.mesh();
  const int w = cam.width(), h = cam.height();
  auto* scene = static_cast<RTCScene>(scene_.rtc_scene());
  alignas(64) RTCRayHit16 rh;
  alignas(64) int valid[16];
  // Every lane holds a well-formed ray, active or not: Embree's 8-wide (AVX2) coherent kernels assert on the lanes of
  // a 16-ray packet beyond the active mask (a machine without AVX-512 aborted in rtcOccluded16 on uninitialized lanes).
  const auto reset_lanes = [](auto& ray) {
    for (int i = 0; i < 16; ++i) {
      ray.org_x[i] = ray.org_y[i] = ray.org_z[i] = 0.0f;
      ray.dir_x[i] = ray.dir_y[i] = 0.0f;
      ray.dir_z[i] = 1.0f;
      ray.tnear[i] = ray.tfar[i] = ray.time[i] = 0.0f;
      ray.mask[i] = 0xFFFFFFFF;
      ray.id[i] = static_cast<unsigned>(i);
      ray.flags[i] = 0;
    }
  };
  for (int v0 = kTile * (*next_tile_row)++; v0 < h; v0 = kTile * (*next_tile_row)++) {
    for (int u0 = 0; u0 < w; u0 += kTile) {
      bool any = false;
      reset_lanes(rh.ray);
      for (int i = 0; i < 16; ++i) {
        const int u = u0 + i % kTile, v = v0 + i / kTile;
        valid[i] = 0;
        if (u >= w || v >= h) continue;
        const Eigen::Vector3f& f = f_C[static_cast<std::size_t>(v) * w + u];
        if (std::isnan(f.x())) continue;
        const Eigen::Vector3f d = R_WC * f;
        valid[i] = -1;
        any = true;
        rh.ray.org_x[i] = static_cast<float>(c_W.x());
        rh.ray.org_y[i] = static_cast<float>(c_W.y());
        rh.ray.org_z[i] = static_cast<float>(c_W.z());
        rh.ray.dir_x[i] = d.x();
        rh.ray.dir_y[i] = d.y();
        rh.ray.dir_z[i] = d.z();
        rh.ray.tnear[i] = 0.0f;
        rh.ray.tfar[i] = static_cast<float>(config_.max_range_m);
        rh.ray.time[i] = 0.0f;
        rh.ray.mask[i] = 0xFFFFFFFF;
        rh.ray.id[i] = static_cast<unsigned>(i);
        rh.ray.flags[i] = 0;
        rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
      }
      if (!any) continue;
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
      rtcIntersect16(valid, scene, &context, &rh);

      // Hit points, normals and sun angles; then one shadow packet towards the sun for the sunlit ones.
      Eigen::Vector3d p_W[16], n_W[16], d_W[16];
      double sun_cos[16];
      alignas(64) int lit[16];
      alignas(64) RTCRay16 shadow;
      reset_lanes(shadow);
      bool any_lit = false;
      for (int i = 0; i < 16; ++i) {
        lit[i] = 0;
        if (!valid[i]) continue;
        d_W[i] = Eigen::Vector3d(rh.ray.dir_x[i], rh.ray.dir_y[i], rh.ray.dir_z[i]);
        if (rh.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) continue;
        p_W[i] = c_W + static_cast<double>(rh.ray.tfar[i]) * d_W[i];
        n_W[i] = Eigen::Vector3d(rh.hit.Ng_x[i], rh.hit.Ng_y[i], rh.hit.Ng_z[i]).normalized();
        if (n_W[i].dot(d_W[i]) > 0) n_W[i] = -n_W[i];  // face the camera: walls are lit from the side we see
        sun_cos[i] = n_W[i].dot(config_.sun_W);
        if (sun_cos[i] <= 0 || !config_.shadows) continue;
        lit[i] = -1;
        any_lit = true;
        const Eigen::Vector3d o = p_W[i] + 1e-3 * n_W[i];  // leave the surface we start on
        shadow.org_x[i] = static_cast<float>(o.x());
        shadow.org_y[i] = static_cast<float>(o.y());
        shadow.org_z[i] = static_cast<float>(o.z());
        shadow.dir_x[i] = static_cast<float>(config_.sun_W.x());
        shadow.dir_y[i] = static_cast<float>(config_.sun_W.y());
        shadow.dir_z[i] = static_cast<float>(config_.sun_W.z());
        shadow.tnear[i] = 0.0f;
        shadow.tfar[i] = static_cast<float>(config_.max_range_m);
        shadow.time[i] = 0.0f;
        shadow.mask[i] = 0xFFFFFFFF;
        shadow.id[i] = static_cast<unsigned>(i);
        shadow.flags[i] = 0;
      }
      if (any_lit) rtcOccluded16(lit, scene, &context, &shadow);  // occluded lanes get tfar = -inf

      for (int i = 0; i < 16; ++i) {
        if (!valid[i]) continue;
        const int u = u0 + i % kTile, v = v0 + i / kTile;
        const std::size_t idx = static_cast<std::size_t>(v) * w + u;
        float value;
        if (rh.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID) {
          const std::uint32_t tri = rh.hit.primID[i];
          // Pixel footprint grows with distance and with grazing incidence.
          const double footprint = rh.ray.tfar[i] * pixel_angle / std::max(std::abs(n_W[i].dot(d_W[i])), 0.2);
          const float a = albedo(p_W[i], n_W[i], mesh.kind[tri], mesh.building_id[tri], footprint);
          const bool sunlit = sun_cos[i] > 0 && (!config_.shadows || shadow.tfar[i] >= 0);
          const double light = config_.ambient + (1 - config_.ambient) * (sunlit ? sun_cos[i] : 0.0);
          value = static_cast<float>(255.0 * a * light);
        } else {
          value = background(d_W[i]);
        }
        value += static_cast<float>(config_.noise_sigma) * pixel_noise(seed, idx);
        image->ptr<std::uint8_t>(v)[u] = static_cast<std::uint8_t>(std::clamp(value + 0.5f, 0.0f, 255.0f));
      }
    }
  }
}

std::optional<double> Renderer::raycast(const Eigen::Vector3d& origin_W, const Eigen::Vector3d& dir_W) const {
  RayHit hit;
  if (!scene_.intersect(origin_W, dir_W.normalized(), 0.0, config_.max_range_m, &hit)) return std::nullopt;
  return hit.t_m;
}

bool Renderer::visible(const Eigen::Vector3d& p_W, const Eigen::Vector3d& c_W, double tolerance_m) const {
  const Eigen::Vector3d delta = p_W - c_W;
  const double range = delta.norm();
  if (range <= tolerance_m) return true;
  RayHit hit;
  return !scene_.intersect(c_W, delta / range, 0.0, range - tolerance_m, &hit);
}

}  // namespace twinslam::sim

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
#include "twinslam/sim/world/traffic.hpp"

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

// A sphere that holds a car during a frame and, with shadows, the part of the world its shadow can fall on: shadowed
// points lie below the car along the sun's rays, down to the ground (z = 0: cars drive on the procedural city's flat
// streets), within the sphere swept that far along -sun. A sun too low for that bound: a sphere round the world.
struct CarSphere {
  Eigen::Vector3d centre_W;
  double radius_m;
};
CarSphere car_sphere(const Traffic& traffic, std::size_t k, double t0_s, double t1_s, const RenderConfig& config) {
  auto [c, r] = traffic.bounding_sphere(k, t0_s, t1_s);
  if (config.shadows) {
    if (config.sun_W.z() < 0.05) return {c, 1e9};
    const double reach = (c.z() + r) / config.sun_W.z();  // along -sun from the sphere's top to the ground
    c -= 0.5 * reach * config.sun_W;
    r += 0.5 * reach;
  }
  return {c, r};
}

// Whether a ray from within delta_m of c_W, along a direction within theta_rad of a cone (axis_W, half_rad), can
// meet a sphere.
bool cone_meets_sphere(const Eigen::Vector3d& axis_W, double half_rad, const Eigen::Vector3d& c_W, double delta_m,
                       double theta_rad, const CarSphere& s) {
  const Eigen::Vector3d d = s.centre_W - c_W;
  const double L = d.norm(), r = s.radius_m + delta_m;
  if (L <= r) return true;
  const double angle = std::acos(std::clamp(axis_W.dot(d) / L, -1.0, 1.0));
  return angle <= half_rad + theta_rad + std::asin(r / L) + 1e-6;
}

}  // namespace

Renderer::Renderer(const TriMesh& world, const RenderConfig& config) : scene_(world), config_(config) {
  if (config_.threads < 1 || config_.threads > 64) throw InputError("render: threads must be in [1, 64]");
  if (!(config_.noise_sigma >= 0) || !(config_.ambient >= 0 && config_.ambient <= 1) || !(config_.max_range_m > 0) ||
      !(config_.sun_W.norm() > 0))
    throw InputError("render: noise_sigma >= 0, ambient in [0, 1], max_range_m > 0 and a nonzero sun direction");
  config_.sun_W.normalize();
}

std::shared_ptr<const Renderer::CameraRays> Renderer::bearings(const CameraModel& cam) const {
  std::lock_guard<std::mutex> lock(cache_mutex_);
  if (cached_bearings_ && same(cached_intrinsics_, cam.intrinsics())) return cached_bearings_;
  auto rays = std::make_shared<CameraRays>();
  std::vector<Eigen::Vector3f>& f = rays->f_C;
  f.resize(static_cast<std::size_t>(cam.width()) * cam.height());
  for (int v = 0; v < cam.height(); ++v) {
    for (int u = 0; u < cam.width(); ++u) {
      Eigen::Vector3d f_C;
      f[static_cast<std::size_t>(v) * cam.width() + u] =
          cam.unproject(Eigen::Vector2d(u, v), &f_C) ? Eigen::Vector3f(f_C.normalized().cast<float>())
                                                     : Eigen::Vector3f::Constant(std::nanf(""));
    }
  }
  // The cones: axis along the mean bearing, half-angle to the farthest one (plus a little for float rounding).
  const auto cone = [&](int u0, int v0, int u1, int v1) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int v = v0; v < v1; ++v)
      for (int u = u0; u < u1; ++u)
        if (const Eigen::Vector3f& b = f[static_cast<std::size_t>(v) * cam.width() + u]; !std::isnan(b.x()))
          sum += b.cast<double>();
    Cone c;
    if (sum.norm() < 1e-9) return c;  // no ray (or, beyond 180 deg, no useful axis: half-angle pi)
    c.axis_C = sum.normalized();
    c.half_rad = 0;
    for (int v = v0; v < v1; ++v)
      for (int u = u0; u < u1; ++u)
        if (const Eigen::Vector3f& b = f[static_cast<std::size_t>(v) * cam.width() + u]; !std::isnan(b.x()))
          c.half_rad = std::max(c.half_rad, std::acos(std::clamp(c.axis_C.dot(b.cast<double>()), -1.0, 1.0)));
    c.half_rad += 1e-5;
    return c;
  };
  rays->image = cone(0, 0, cam.width(), cam.height());
  if (rays->image.half_rad < 0) rays->image.half_rad = M_PI;  // rays all round: the whole sphere
  rays->blocks_x = (cam.width() + kBlock - 1) / kBlock;
  for (int v0 = 0; v0 < cam.height(); v0 += kBlock)
    for (int u0 = 0; u0 < cam.width(); u0 += kBlock)
      rays->blocks.push_back(cone(u0, v0, std::min(u0 + kBlock, cam.width()), std::min(v0 + kBlock, cam.height())));
  cached_intrinsics_ = cam.intrinsics();
  cached_bearings_ = rays;
  return rays;
}

cv::Mat Renderer::render(const Eigen::Isometry3d& T_WC, const CameraModel& cam, std::uint64_t seed) const {
  FrameCapture frame;
  frame.T_WC = [&T_WC](double) { return T_WC; };
  return render(frame, cam, seed);
}

int Renderer::subexposures(const FrameCapture& frame, const CameraModel& cam, const std::vector<Eigen::Vector3f>& f_C,
                           const TrafficSnapshot* cars, double* motion_px) const {
  // The pixel motion during the exposure, measured on a 7 x 5 grid of probe rays: each probe's surface point (static,
  // or moving with its car; a point 1 km out where the ray meets nothing) projected at the start and the end of its
  // row's exposure.
  *motion_px = 0;
  const double exposure = frame.shutter.exposure_s;
  if (!(exposure > 0)) return 1;
  const int w = cam.width(), h = cam.height();
  for (int a = 0; a < 7; ++a) {
    for (int b = 0; b < 5; ++b) {
      const int u = (2 * a + 1) * w / 14, v = (2 * b + 1) * h / 10;
      const Eigen::Vector3f& f = f_C[static_cast<std::size_t>(v) * w + u];
      if (std::isnan(f.x())) continue;
      const double t_v = frame.t_s + frame.shutter.row_offset_s(v, h);
      const Eigen::Isometry3d T_WC = frame.T_WC(t_v);
      const Eigen::Vector3d d_W = T_WC.linear() * f.cast<double>();
      RayHit hit;
      double range = 1000.0;
      if (scene_.intersect(T_WC.translation(), d_W, 0.0, config_.max_range_m, &hit)) range = hit.t_m;
      CarHit car;
      const bool on_car = cars && cars->intersect(T_WC.translation(), d_W, t_v, range, &car);
      if (on_car) range = car.t_m;
      const Eigen::Vector3d p_W = T_WC.translation() + range * d_W;
      Eigen::Vector2d uv[2];
      bool ok = true;
      for (int end = 0; end < 2 && ok; ++end) {
        const double t = t_v + (end == 0 ? -0.5 : 0.5) * exposure;
        const Eigen::Vector3d p = on_car ? Eigen::Vector3d(frame.traffic->T_WV(car.car, t) * car.p_V) : p_W;
        ok = cam.project(frame.T_WC(t).inverse() * p, &uv[end]) == ProjectionStatus::kOk;
      }
      if (ok) *motion_px = std::max(*motion_px, (uv[1] - uv[0]).norm());
    }
  }
  return static_cast<int>(
      std::clamp<double>(std::ceil(*motion_px / config_.blur_step_px), 1.0, config_.max_subexposures));
}

cv::Mat Renderer::render(const FrameCapture& frame, const CameraModel& cam, std::uint64_t seed,
                         RenderInfo* info) const {
  const auto rays = bearings(cam);
  const std::vector<Eigen::Vector3f>& f_C = rays->f_C;
  const int h = cam.height();
  const Shutter& shutter = frame.shutter;
  // The cars over the whole frame (from the first row's exposure start to the last row's exposure end) that the
  // camera may see then, or their shadows.
  std::unique_ptr<TrafficSnapshot> cars;
  if (frame.traffic && !frame.traffic->empty()) {
    const double t0 = frame.t_s + shutter.row_offset_s(0, h) - 0.5 * shutter.exposure_s;
    const double t1 = frame.t_s + shutter.row_offset_s(h - 1, h) + 0.5 * shutter.exposure_s;
    std::vector<std::size_t> seen;
    const Eigen::Isometry3d T_mid = frame.T_WC(frame.t_s);
    double delta = 0, theta = 0;  // how far the camera moves and turns from T_mid within the frame
    for (const double t : {t0, t1}) {
      const Eigen::Isometry3d T = frame.T_WC(t);
      delta = std::max(delta, (T.translation() - T_mid.translation()).norm());
      theta = std::max(theta, Eigen::AngleAxisd(T_mid.linear().transpose() * T.linear()).angle());
    }
    for (std::size_t k = 0; k < frame.traffic->size(); ++k) {
      const CarSphere s = car_sphere(*frame.traffic, k, t0, t1, config_);
      if (!config_.cull_cars ||
          cone_meets_sphere(T_mid.linear() * rays->image.axis_C, rays->image.half_rad, T_mid.translation(),
                            2 * delta + 0.02, 2 * theta + 1e-3, s))
        seen.push_back(k);
    }
    cars = frame.traffic->snapshot(t0, t1, &seen);
  }
  RenderInfo done;
  done.subexposures = subexposures(frame, cam, f_C, cars.get(), &done.motion_px);
  if (info) *info = done;

  // Sub-exposure k of row v is taken at t_v + ((k + 0.5) / K - 0.5) * exposure: the middles of K equal parts.
  RowPoses poses;
  const int K = done.subexposures;
  poses.subexposures = K;
  poses.R_WC.resize(static_cast<std::size_t>(K) * h);
  poses.c_W.resize(poses.R_WC.size());
  poses.time.resize(poses.R_WC.size(), 0.0f);
  for (int k = 0; k < K; ++k) {
    const double dt = K == 1 ? 0.0 : ((k + 0.5) / K - 0.5) * shutter.exposure_s;
    for (int v = 0; v < h; ++v) {
      const std::size_t i = static_cast<std::size_t>(k) * h + v;
      const double t = frame.t_s + shutter.row_offset_s(v, h) + dt;
      if (v > 0 && shutter.line_time_s == 0) {  // global shutter: one pose for all rows
        poses.R_WC[i] = poses.R_WC[i - 1];
        poses.c_W[i] = poses.c_W[i - 1];
      } else {
        const Eigen::Isometry3d T_WC = frame.T_WC(t);
        poses.R_WC[i] = T_WC.linear().cast<float>();
        poses.c_W[i] = T_WC.translation();
      }
      if (cars) poses.time[i] = cars->ray_time(t);
    }
  }

  const std::vector<std::uint8_t> blocks =
      cars ? car_blocks(poses, *rays, *cars, cam) : std::vector<std::uint8_t>();
  cv::Mat image(h, cam.width(), CV_8UC1, cv::Scalar(0));
  const int n = std::min(config_.threads, (h + 3) / 4);
  std::vector<std::thread> workers;
  std::atomic<int> next_tile_row{0};
  for (int k = 1; k < n; ++k)
    workers.emplace_back([&] { render_rows(poses, cars.get(), blocks, cam, *rays, seed, &next_tile_row, &image); });
  render_rows(poses, cars.get(), blocks, cam, *rays, seed, &next_tile_row, &image);
  for (auto& w : workers) w.join();
  return image;
}

std::vector<std::uint8_t> Renderer::car_blocks(const RowPoses& poses, const CameraRays& rays,
                                               const TrafficSnapshot& cars, const CameraModel& cam) const {
  const int h = cam.height(), K = poses.subexposures;
  const int blocks = static_cast<int>(rays.blocks.size()), rows = (h + kBlock - 1) / kBlock;
  std::vector<CarSphere> spheres;
  for (const std::size_t k : cars.cars())
    spheres.push_back(car_sphere(cars.traffic(), k, cars.t0_s(), cars.t1_s(), config_));
  std::vector<std::uint8_t> flags(static_cast<std::size_t>(K) * blocks, config_.cull_cars ? 0 : 1);
  if (!config_.cull_cars) return flags;
  for (int k = 0; k < K; ++k) {
    for (int by = 0; by < rows; ++by) {
      // The block row's rays leave from within delta of its first row's camera, turned by at most theta from it.
      const std::size_t first = static_cast<std::size_t>(k) * h + by * kBlock;
      const Eigen::Matrix3d R0 = poses.R_WC[first].cast<double>();
      const Eigen::Vector3d& c0 = poses.c_W[first];
      double delta = 0, theta = 0;
      for (int v = by * kBlock + 1; v < std::min(h, (by + 1) * kBlock); ++v) {
        const std::size_t i = static_cast<std::size_t>(k) * h + v;
        delta = std::max(delta, (poses.c_W[i] - c0).norm());
        theta = std::max(theta, Eigen::AngleAxisd(R0.transpose() * poses.R_WC[i].cast<double>()).angle());
      }
      for (int bx = 0; bx < rays.blocks_x; ++bx) {
        const Cone& cone = rays.blocks[static_cast<std::size_t>(by) * rays.blocks_x + bx];
        if (cone.half_rad < 0) continue;
        const Eigen::Vector3d axis_W = R0 * cone.axis_C;
        for (const CarSphere& s : spheres) {
          if (!cone_meets_sphere(axis_W, cone.half_rad, c0, delta + 1e-3, theta + 1e-4, s)) continue;
          flags[static_cast<std::size_t>(k) * blocks + by * rays.blocks_x + bx] = 1;
          break;
        }
      }
    }
  }
  return flags;
}

void Renderer::render_rows(const RowPoses& poses, const TrafficSnapshot* cars,
                           const std::vector<std::uint8_t>& car_blocks, const CameraModel& cam, const CameraRays& rays,
                           std::uint64_t seed, std::atomic<int>* next_tile_row, cv::Mat* image) const {
  // Rays go to Embree in 4 x 4 pixel packets (rtcIntersect16, coherent flag): neighbouring primary rays traverse
  // the same BVH nodes, which measured about 2x faster than one rtcIntersect1 per pixel (bench/sim_render).
  // Threads take the next free row of tiles (dynamic: on a shared machine a statically split thread would straggle).
  // Each lane has its own row's camera (rolling shutter); the cars' packet follows the world's with the lanes' times,
  // and its hits win where they are nearer. Sub-exposures are summed per pixel in a fixed order, so the image does not
  // depend on the threads.
  constexpr int kTile = 4;
  const double pixel_angle = 1.0 / std::max(cam.intrinsics().fu, 1e-9);  // [rad per px] near the image centre
  const TriMesh& mesh = scene_.mesh();
  const int w = cam.width(), h = cam.height();
  const int K = poses.subexposures;
  const std::vector<Eigen::Vector3f>& f_C = rays.f_C;
  const std::size_t blocks = rays.blocks.size();
  auto* scene = static_cast<RTCScene>(scene_.rtc_scene());
  auto* car_scene = cars ? static_cast<RTCScene>(cars->rtc_scene()) : nullptr;
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
      float sum[16] = {};
      bool any = false;
      for (int k = 0; k < K; ++k) {
        any = false;
        reset_lanes(rh.ray);
        Eigen::Vector3d c_W[16];
        for (int i = 0; i < 16; ++i) {
          const int u = u0 + i % kTile, v = v0 + i / kTile;
          valid[i] = 0;
          if (u >= w || v >= h) continue;
          const Eigen::Vector3f& f = f_C[static_cast<std::size_t>(v) * w + u];
          if (std::isnan(f.x())) continue;
          const std::size_t row = static_cast<std::size_t>(k) * h + v;
          c_W[i] = poses.c_W[row];
          const Eigen::Vector3f d = poses.R_WC[row] * f;
          valid[i] = -1;
          any = true;
          rh.ray.org_x[i] = static_cast<float>(c_W[i].x());
          rh.ray.org_y[i] = static_cast<float>(c_W[i].y());
          rh.ray.org_z[i] = static_cast<float>(c_W[i].z());
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
        if (!any) break;
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        rtcIntersect16(valid, scene, &context, &rh);
        // The cars: Embree only takes a hit nearer than the world's (tfar), so a shorter tfar marks a car.
        bool car_hit[16] = {};
        const bool near_cars =
            car_scene && car_blocks[k * blocks + static_cast<std::size_t>(v0 / kBlock) * rays.blocks_x + u0 / kBlock];
        if (near_cars) {
          float world_t[16];
          for (int i = 0; i < 16; ++i) {
            world_t[i] = rh.ray.tfar[i];
            if (valid[i]) rh.ray.time[i] = poses.time[static_cast<std::size_t>(k) * h + v0 + i / kTile];
          }
          rtcIntersect16(valid, car_scene, &context, &rh);
          for (int i = 0; i < 16; ++i) car_hit[i] = valid[i] && rh.ray.tfar[i] < world_t[i];
        }

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
          p_W[i] = c_W[i] + static_cast<double>(rh.ray.tfar[i]) * d_W[i];
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
        if (any_lit) {
          rtcOccluded16(lit, scene, &context, &shadow);  // occluded lanes get tfar = -inf
          if (near_cars) {  // the cars' shadows, on the lanes the world leaves in the sun
            alignas(64) int open[16];
            bool any_open = false;
            for (int i = 0; i < 16; ++i) {
              open[i] = lit[i] && shadow.tfar[i] >= 0 ? -1 : 0;
              any_open = any_open || open[i];
              shadow.time[i] = rh.ray.time[i];
            }
            if (any_open) rtcOccluded16(open, car_scene, &context, &shadow);
          }
        }

        for (int i = 0; i < 16; ++i) {
          if (!valid[i]) continue;
          float value;
          if (rh.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID) {
            const std::uint32_t tri = rh.hit.primID[i];
            // Pixel footprint grows with distance and with grazing incidence.
            const double footprint = rh.ray.tfar[i] * pixel_angle / std::max(std::abs(n_W[i].dot(d_W[i])), 0.2);
            float a;
            if (car_hit[i]) {
              CarHit car;
              cars->local_hit(tri, rh.hit.u[i], rh.hit.v[i], &car);
              a = car_albedo(car.p_V, car.n_V, car.part, cars->traffic().paint(car.car), footprint);
            } else {
              a = albedo(p_W[i], n_W[i], mesh.kind[tri], mesh.building_id[tri], footprint);
            }
            const bool sunlit = sun_cos[i] > 0 && (!config_.shadows || shadow.tfar[i] >= 0);
            const double light = config_.ambient + (1 - config_.ambient) * (sunlit ? sun_cos[i] : 0.0);
            value = static_cast<float>(255.0 * a * light);
          } else {
            value = background(d_W[i]);
          }
          sum[i] += value;
        }
      }
      if (!any) continue;
      for (int i = 0; i < 16; ++i) {
        if (!valid[i]) continue;
        const int u = u0 + i % kTile, v = v0 + i / kTile;
        const std::size_t idx = static_cast<std::size_t>(v) * w + u;
        float value = sum[i] / static_cast<float>(K);
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

#pragma once
// Grayscale camera images of the world (issue 3, item 5).
//
// Why ray casting (Embree 3) and not a z-buffer rasterizer: a rasterizer projects vertices and draws straight edges
// between them, which is only right for a pinhole camera; a 120-190 deg fisheye bends every edge and cannot even
// project points behind the image plane, so it would need re-meshing into small triangles or a cube-map resampling
// step. Casting one ray per pixel along the camera model's own unprojected bearing is exact for any model (the same
// CameraModel the tracker and estimator use), and Embree's BVH keeps it at >= 20 fps on two CPU cores (see
// bench/sim_render). The same BVH answers the ray casts and visibility tests the ideal feature tracks need.
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "twinslam/camera/camera_model.hpp"
#include "twinslam/sim/world/embree_scene.hpp"

namespace twinslam::sim {

struct RenderConfig {
  int threads = 2;                                           // worker threads per frame (std::thread)
  double noise_sigma = 2.0;                                  // sensor noise std dev [grey levels]
  Eigen::Vector3d sun_W = Eigen::Vector3d(0.5, 0.3, 0.81);   // direction towards the sun (normalized inside) [W]
  double ambient = 0.45;                                     // light on surfaces facing away from the sun [0, 1]
  bool shadows = true;                                       // cast shadows (one more ray per sunlit pixel)
  double max_range_m = 5000;                                 // rays end here [m]
};

class Renderer {
 public:
  // Builds the BVH of `world` (copied). Throws InputError for an invalid config.
  explicit Renderer(const TriMesh& world, const RenderConfig& config = {});

  // The image of camera `cam` at pose T_WC (camera C: x right, y down, z forward): CV_8UC1, cam.width() x
  // cam.height(). Pixels outside the model's domain are 0. `seed` drives the sensor noise only (use one per frame);
  // the same inputs give bit-identical images for any thread count.
  cv::Mat render(const Eigen::Isometry3d& T_WC, const CameraModel& cam, std::uint64_t seed) const;

  // Distance [m] along dir_W (normalized inside) to the first surface, or nothing.
  std::optional<double> raycast(const Eigen::Vector3d& origin_W, const Eigen::Vector3d& dir_W) const;

  // True if nothing lies between the camera centre c_W and the surface point p_W (depth test with tolerance_m).
  bool visible(const Eigen::Vector3d& p_W, const Eigen::Vector3d& c_W, double tolerance_m = 0.05) const;

  const EmbreeScene& scene() const { return scene_; }

 private:
  // Unit bearings f_C of every pixel centre for the last camera (NaN where the model has no ray); the fisheye
  // unprojection is an iterative solve, so it is done once per camera, not per frame.
  std::shared_ptr<const std::vector<Eigen::Vector3f>> bearings(const CameraModel& cam) const;
  void render_rows(const Eigen::Isometry3d& T_WC, const CameraModel& cam, const std::vector<Eigen::Vector3f>& f_C,
                   std::uint64_t seed, std::atomic<int>* next_tile_row, cv::Mat* image) const;

  EmbreeScene scene_;
  RenderConfig config_;
  mutable std::mutex cache_mutex_;
  mutable CameraIntrinsics cached_intrinsics_;
  mutable std::shared_ptr<const std::vector<Eigen::Vector3f>> cached_bearings_;
};

}  // namespace twinslam::sim

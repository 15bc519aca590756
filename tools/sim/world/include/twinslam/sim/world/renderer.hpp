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
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "twinslam/camera/camera_model.hpp"
#include "twinslam/sim/world/embree_scene.hpp"

namespace twinslam::sim {

class Traffic;
class TrafficSnapshot;

struct RenderConfig {
  int threads = 2;                                           // worker threads per frame (std::thread)
  double noise_sigma = 2.0;                                  // sensor noise std dev [grey levels]
  Eigen::Vector3d sun_W = Eigen::Vector3d(0.5, 0.3, 0.81);   // direction towards the sun (normalized inside) [W]
  double ambient = 0.45;                                     // light on surfaces facing away from the sun [0, 1]
  bool shadows = true;                                       // cast shadows (one more ray per sunlit pixel)
  double max_range_m = 5000;                                 // rays end here [m]
  // Motion blur: a frame is rendered as ceil(motion / blur_step_px) sub-exposures, at most max_subexposures, averaged,
  // motion the largest pixel motion during the exposure: one pass while nothing moves blur_step_px (as in most frames
  // of a drone at a few m/s with a few ms of exposure; nearby things at the image's sides move most), sub-exposures
  // at most blur_step_px apart otherwise (until max_subexposures).
  double blur_step_px = 0.5;                                 // [px]
  int max_subexposures = 8;
  // Cars are traced only in the 32 x 32 pixel blocks where one (or its shadow) may be, from bounding spheres and the
  // cones of the blocks' rays; false traces every block (the same image, slower: for tests).
  bool cull_cars = true;
};

// When each row of an image is exposed. The image's time t is the middle of the exposure of its middle row
// (height - 1) / 2; row v is exposed during [t_v - exposure_s / 2, t_v + exposure_s / 2] with
// t_v = t + (v - (height - 1) / 2) * line_time_s. All zero: a global shutter with an instantaneous exposure.
struct Shutter {
  double line_time_s = 0;                                    // rolling shutter: time between successive rows [s]
  double exposure_s = 0;                                     // exposure of each row [s]
  double row_offset_s(double v, int height) const { return (v - 0.5 * (height - 1)) * line_time_s; }
};

// One frame as the camera takes it: where the camera is while its rows are exposed, and what moves meanwhile.
struct FrameCapture {
  double t_s = 0;                                            // the image's time (see Shutter) [s]
  std::function<Eigen::Isometry3d(double t_s)> T_WC;         // camera pose at any time near t_s
  Shutter shutter;
  const Traffic* traffic = nullptr;                          // moving cars, or none
};

// What render() did: sub-exposures averaged and the largest pixel motion it measured during the exposure.
struct RenderInfo {
  int subexposures = 1;
  double motion_px = 0;
};

class Renderer {
 public:
  // Builds the BVH of `world` (copied). Throws InputError for an invalid config.
  explicit Renderer(const TriMesh& world, const RenderConfig& config = {});

  // The image of camera `cam` at pose T_WC (camera C: x right, y down, z forward): CV_8UC1, cam.width() x
  // cam.height(). Pixels outside the model's domain are 0. `seed` drives the sensor noise only (use one per frame);
  // the same inputs give bit-identical images for any thread count.
  cv::Mat render(const Eigen::Isometry3d& T_WC, const CameraModel& cam, std::uint64_t seed) const;

  // The image of a frame with rolling shutter, motion blur and moving cars: row v is rendered from the camera pose at
  // its own time t_v; with an exposure the pixel averages sub-exposures at poses spread over it (their number from the
  // pixel motion, RenderConfig), the cars are where they are at each ray's time, and the noise is added once, after
  // averaging. T_WC is called on the calling thread only (once per row and sub-exposure, and for a few probe rays).
  // Shutter all zero and no cars: exactly render(frame.T_WC(frame.t_s), cam, seed).
  cv::Mat render(const FrameCapture& frame, const CameraModel& cam, std::uint64_t seed,
                 RenderInfo* info = nullptr) const;

  // Distance [m] along dir_W (normalized inside) to the first surface, or nothing.
  std::optional<double> raycast(const Eigen::Vector3d& origin_W, const Eigen::Vector3d& dir_W) const;

  // True if nothing lies between the camera centre c_W and the surface point p_W (depth test with tolerance_m).
  bool visible(const Eigen::Vector3d& p_W, const Eigen::Vector3d& c_W, double tolerance_m = 0.05) const;

  const EmbreeScene& scene() const { return scene_; }

 private:
  // A cone that holds rays (unit axis, half-angle; half < 0 when it holds none).
  struct Cone {
    Eigen::Vector3d axis_C = Eigen::Vector3d::UnitZ();
    double half_rad = -1;
  };
  // Unit bearings f_C of every pixel centre for the last camera (NaN where the model has no ray), and the cones of
  // the whole image's and of every 32 x 32 pixel block's bearings; the fisheye unprojection is an iterative solve, so
  // this is done once per camera, not per frame.
  struct CameraRays {
    std::vector<Eigen::Vector3f> f_C;
    Cone image;
    std::vector<Cone> blocks;  // row-major, blocks_x per row
    int blocks_x = 0;
  };
  static constexpr int kBlock = 32;
  std::shared_ptr<const CameraRays> bearings(const CameraModel& cam) const;
  // The camera of every row and sub-exposure: [k * height + v].
  struct RowPoses {
    int subexposures = 1;
    std::vector<Eigen::Matrix3f> R_WC;
    std::vector<Eigen::Vector3d> c_W;
    std::vector<float> time;  // the cars' ray time
  };
  int subexposures(const FrameCapture& frame, const CameraModel& cam, const std::vector<Eigen::Vector3f>& f_C,
                   const TrafficSnapshot* cars, double* motion_px) const;
  // Where cars may be seen: per sub-exposure k and block, [k * blocks + b] != 0.
  std::vector<std::uint8_t> car_blocks(const RowPoses& poses, const CameraRays& rays, const TrafficSnapshot& cars,
                                       const CameraModel& cam) const;
  void render_rows(const RowPoses& poses, const TrafficSnapshot* cars, const std::vector<std::uint8_t>& car_blocks,
                   const CameraModel& cam, const CameraRays& rays, std::uint64_t seed,
                   std::atomic<int>* next_tile_row, cv::Mat* image) const;

  EmbreeScene scene_;
  RenderConfig config_;
  mutable std::mutex cache_mutex_;
  mutable CameraIntrinsics cached_intrinsics_;
  mutable std::shared_ptr<const CameraRays> cached_bearings_;
};

}  // namespace twinslam::sim

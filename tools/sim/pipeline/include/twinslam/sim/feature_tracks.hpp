#pragma once
// Ideal feature tracks (sim --features): world surface points visible in each frame, depth-tested against the
// world (not the twin), with their exact and noisy pixels — what a perfect frontend would deliver.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <vector>

#include <Eigen/Geometry>

#include "twinslam/camera/camera_model.hpp"
#include "twinslam/sim/world/renderer.hpp"

namespace twinslam::sim {

struct FeatureTrackConfig {
  int landmarks = 20000;           // surface points sampled area-uniformly over the world
  double pixel_sigma = 0.5;        // noise of u_noisy, v_noisy [px]
  double max_range_m = 120;        // farther points are not tracked [m]
  int max_per_frame = 250;         // keep the nearest ones beyond this (a frontend's budget)
  double border_px = 4;            // keep away from the image edge [px]
  // Points on each moving car (FrameCapture::traffic), area-uniform over its body, ids after the static landmarks
  // (static count + car * landmarks_per_car + j): what a real tracker would follow on a car, outliers to a static map.
  int landmarks_per_car = 6;
};

class FeatureTrackWriter {
 public:
  // Opens DIR/mav0/cam0/features.csv and writes its header.
  FeatureTrackWriter(const std::filesystem::path& file, std::vector<Eigen::Vector3d> landmarks_W,
                     FeatureTrackConfig config, std::uint64_t seed);
  // Appends the rows of one frame; returns the number of features written.
  int add_frame(std::int64_t stamp_ns, const Eigen::Isometry3d& T_WC, const CameraModel& camera,
                const Renderer& world);
  // The same for a frame with a rolling shutter and moving cars (renderer.hpp): a landmark's pixel is where it is seen
  // at the time of the row it lands on (a fixed point on the row: the camera and, for a car's landmark, the car where
  // they are at that row's time), at the middle of the exposure; occluded by the world and by the cars at that time.
  // stamp_ns is what the rows are stamped with (the frame's time is frame.t_s).
  int add_frame(std::int64_t stamp_ns, const FrameCapture& frame, const CameraModel& camera, const Renderer& world);

 private:
  std::ofstream out_;
  std::vector<Eigen::Vector3d> landmarks_W_;
  const Traffic* car_landmarks_of_ = nullptr;                  // the traffic car_landmarks_V_ were sampled on
  std::vector<std::vector<Eigen::Vector3d>> car_landmarks_V_;  // per car, in its frame V
  FeatureTrackConfig config_;
  std::uint64_t seed_;
};

}  // namespace twinslam::sim

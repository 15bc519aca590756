#pragma once
// The ideal tracks FeatureTrackWriter writes for one frame, read back (test_imperfect_camera, test_traffic).
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include "twinslam/sim/feature_tracks.hpp"
#include "twinslam/sim/world/renderer.hpp"

namespace twinslam::sim::testing {

// The tracks FeatureTrackWriter writes for one frame: id -> (u, v).
inline std::map<std::size_t, Eigen::Vector2d> tracks_of(const std::vector<Eigen::Vector3d>& landmarks_W,
                                                 const FrameCapture& frame, const CameraModel& cam,
                                                 const Renderer& world, std::string* text = nullptr,
                                                 const FeatureTrackConfig& config = {}) {
  const auto file = std::filesystem::temp_directory_path() /
                    ("twinslam_tracks_" + std::to_string(::getpid()) + "_" +
                     ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".csv");
  {
    FeatureTrackWriter writer(file, landmarks_W, config, 5);
    writer.add_frame(1000, frame, cam, world);
  }
  std::ifstream in(file);
  std::stringstream all;
  all << in.rdbuf();
  if (text) *text = all.str();
  std::map<std::size_t, Eigen::Vector2d> out;
  std::istringstream lines(all.str());
  std::string line;
  while (std::getline(lines, line)) {
    if (line.empty() || line[0] == '#') continue;
    long long stamp;
    std::size_t id;
    double u, v, un, vn;
    EXPECT_EQ(std::sscanf(line.c_str(), "%lld,%zu,%lf,%lf,%lf,%lf", &stamp, &id, &u, &v, &un, &vn), 6);
    out[id] = {u, v};
  }
  std::filesystem::remove(file);
  return out;
}

}  // namespace twinslam::sim::testing

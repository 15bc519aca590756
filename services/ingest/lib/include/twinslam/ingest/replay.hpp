#pragma once
// The order in which a dataset is published: one time-ordered list over all streams. At equal stamps IMU comes
// before GNSS and images, so a consumer holding a frame already has the IMU sample taken at the same instant.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "twinslam/ingest/dataset.hpp"
#include "twinslam/ingest/features.hpp"

namespace twinslam::ingest {

// Camera frames are either images or (with --features) ideal feature tracks, never both.
enum class Stream : int { Imu = 0, Gnss = 1, Image = 2, Features = 3 };

struct ReplayEvent {
  std::int64_t stamp_ns;
  Stream stream;
  std::size_t index;  // into the dataset's vector for that stream
};

// With `features`, its frames replace the images as the camera stream.
std::vector<ReplayEvent> replay_order(const Dataset& ds, const std::vector<FeatureFrameRecord>* features = nullptr);

// Loads an image as 8-bit single channel (colour is converted to grey). Throws InputError naming the file when it
// cannot be decoded or has another depth.
cv::Mat load_mono8(const std::filesystem::path& file);

}  // namespace twinslam::ingest

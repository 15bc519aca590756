#include "twinslam/ingest/replay.hpp"

#include <algorithm>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "twinslam/core/error.hpp"

namespace twinslam::ingest {

std::vector<ReplayEvent> replay_order(const Dataset& ds, const std::vector<FeatureFrameRecord>* features) {
  std::vector<ReplayEvent> events;
  events.reserve(ds.imu.size() + ds.images.size() + ds.gnss.size());
  for (std::size_t i = 0; i < ds.imu.size(); ++i) events.push_back({ds.imu[i].stamp_ns, Stream::Imu, i});
  for (std::size_t i = 0; i < ds.gnss.size(); ++i) events.push_back({ds.gnss[i].stamp_ns, Stream::Gnss, i});
  if (features != nullptr) {
    for (std::size_t i = 0; i < features->size(); ++i) events.push_back({(*features)[i].stamp_ns, Stream::Features, i});
  } else {
    for (std::size_t i = 0; i < ds.images.size(); ++i) events.push_back({ds.images[i].stamp_ns, Stream::Image, i});
  }
  // Each stream is already strictly increasing; a stable sort by (stamp, stream) keeps that order.
  std::stable_sort(events.begin(), events.end(), [](const ReplayEvent& a, const ReplayEvent& b) {
    return a.stamp_ns != b.stamp_ns ? a.stamp_ns < b.stamp_ns : a.stream < b.stream;
  });
  return events;
}

cv::Mat load_mono8(const std::filesystem::path& file) {
  cv::Mat image = cv::imread(file.string(), cv::IMREAD_UNCHANGED);
  if (image.empty()) throw InputError(file.string() + ": cannot decode image");
  if (image.depth() != CV_8U) throw InputError(file.string() + ": not an 8-bit image");
  if (image.channels() == 3) {
    cv::cvtColor(image, image, cv::COLOR_BGR2GRAY);
  } else if (image.channels() == 4) {
    cv::cvtColor(image, image, cv::COLOR_BGRA2GRAY);
  } else if (image.channels() != 1) {
    throw InputError(file.string() + ": unsupported channel count " + std::to_string(image.channels()));
  }
  return image;
}

}  // namespace twinslam::ingest

#include "tracking_handler.hpp"

#include <algorithm>

#include <opencv2/core/mat.hpp>
#include <spdlog/spdlog.h>

#include "twinslam/camera/camera_model.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/dds/convert.hpp"
#include "twinslam/tracking/gyro_rotation.hpp"

namespace twinslam::tracking {
namespace {

constexpr double kMaxGyro_radps = 1e3;  // no gyro measures beyond this (as the estimator's add_imu)

// A sample the gyro prediction can use: finite (imu_samples.hpp refuses a sample with any non-finite reading), the
// gyro within what a gyro measures.
bool usable(const imu::ImuSample& s) {
  return s.gyro_B.allFinite() && s.accel_B.allFinite() && s.gyro_B.norm() <= kMaxGyro_radps;
}

}  // namespace

TrackingHandler::TrackingHandler(dds::Counters& counters, const TrackingNodeOptions& options)
    : counters_(counters),
      options_(options),
      frontend_(std::shared_ptr<const CameraModel>(make_camera(options_.camera.intrinsics)), options_.frontend) {}

bool TrackingHandler::matches_camera(const msg::Image& m) const {
  // Compared as unsigned 64-bit: a width or height beyond int must not wrap into the camera's.
  const auto& in = options_.camera.intrinsics;
  const std::uint64_t w = m.width(), h = m.height(), step = m.step();
  return m.encoding() == "mono8" && w == static_cast<std::uint64_t>(in.width) &&
         h == static_cast<std::uint64_t>(in.height) && step >= w && m.data().size() >= step * h;
}

std::optional<msg::FeatureFrame> TrackingHandler::handle(const msg::Image& m, std::vector<imu::ImuSample>&& new_imu) {
  // A NaN or impossible gyro sample made gyro_rotation_C throw on the worker thread, which ended the service
  // (found by fuzz_dds_tracking): refused here, counted, and the prediction bridges the gap as for a missing sample.
  for (const imu::ImuSample& s : new_imu) {
    if (usable(s)) {
      imu_.push_back(s);
    } else {
      counters_.add("imu_rejected");
    }
  }
  if (!matches_camera(m)) {
    counters_.add("images_rejected");
    spdlog::warn("image {}: {} {}x{} does not match the camera ({}x{} mono8); skipped", m.stamp_ns(), m.encoding(),
                 m.width(), m.height(), options_.camera.intrinsics.width, options_.camera.intrinsics.height);
    return std::nullopt;
  }
  const int w = options_.camera.intrinsics.width, h = options_.camera.intrinsics.height;
  const cv::Mat image(h, w, CV_8UC1, const_cast<uint8_t*>(m.data().data()), m.step());
  std::optional<Eigen::Matrix3d> R_prev_curr_C;
  if (last_frame_ns_ >= 0) {
    R_prev_curr_C = gyro_rotation_C(imu_, last_frame_ns_, m.stamp_ns(), options_.camera.T_BC.linear());
  }
  // Keep only the IMU needed from this frame on (one sample before it, for interpolation).
  const auto keep =
      std::find_if(imu_.begin(), imu_.end(), [&](const imu::ImuSample& s) { return s.stamp_ns >= m.stamp_ns(); });
  imu_.erase(imu_.begin(), keep == imu_.begin() ? imu_.begin() : keep - 1);
  last_frame_ns_ = m.stamp_ns();
  FrameResult result;
  try {
    result = frontend_.track(m.stamp_ns(), image, R_prev_curr_C ? &*R_prev_curr_C : nullptr);
  } catch (const InputError& e) {  // e.g. a stamp not after the previous one: skip the frame, keep serving
    counters_.add("images_rejected");
    spdlog::warn("image {}: {}", m.stamp_ns(), e.what());
    return std::nullopt;
  }
  msg::FeatureFrame out;
  out.vehicle_id(m.vehicle_id());
  out.camera_id(m.camera_id());
  out.stamp_ns(m.stamp_ns());
  out.seq(seq_++);
  out.tracking_ms(result.timing.total_ms);
  out.features().reserve(result.features.size());
  for (const auto& f : result.features) {
    msg::Feature mf;
    mf.id(f.id);
    mf.u(static_cast<float>(f.uv.x()));
    mf.v(static_cast<float>(f.uv.y()));
    mf.bearing_C(dds::to_msg(f.bearing_C));
    mf.track_length(f.track_length);
    out.features().push_back(mf);
  }
  counters_.add("frames_out");
  return out;
}

}  // namespace twinslam::tracking

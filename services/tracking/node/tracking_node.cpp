#include "tracking_node.hpp"

#include <algorithm>

#include <opencv2/core/mat.hpp>
#include <spdlog/spdlog.h>

#include "twinslam/camera/camera_model.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/dds/convert.hpp"
#include "twinslam/tracking/gyro_rotation.hpp"

namespace twinslam::tracking {

TrackingNode::TrackingNode(dds::Node& node, dds::Counters& counters, TrackingNodeOptions options)
    : node_(node),
      counters_(counters),
      options_(std::move(options)),
      frontend_(std::shared_ptr<const CameraModel>(make_camera(options_.camera.intrinsics)), options_.frontend),
      features_(node.writer<msg::FeatureFrame>(dds::topics::kFeatures)),
      ack_(node.writer<msg::FrameAck>(dds::topics::kFrameAck)),
      worker_(options_.imu_wait, [this](const msg::Image& image, std::vector<imu::ImuSample>&& imu) {
        process(image, std::move(imu));
      }) {
  node.subscribe<msg::Imu>(dds::topics::kImu, [this](const msg::Imu& m) {
    if (m.vehicle_id() != node_.config().vehicle_id) return;
    counters_.add("imu_in");
    if (!worker_.push_imu({m.stamp_ns(), dds::from_msg(m.gyro_radps()), dds::from_msg(m.accel_mps2())})) {
      counters_.add("imu_rejected");  // not after the previous sample
    }
  });
  node.subscribe<msg::Image>(dds::topics::kImage, [this](const msg::Image& m) {
    if (m.vehicle_id() != node_.config().vehicle_id) return;
    counters_.add("images_in");
    worker_.push_frame(std::make_shared<const msg::Image>(m), m.stamp_ns());
  });
}

void TrackingNode::process(const msg::Image& m, std::vector<imu::ImuSample>&& new_imu) {
  imu_.insert(imu_.end(), new_imu.begin(), new_imu.end());
  const int w = static_cast<int>(m.width()), h = static_cast<int>(m.height());
  if (m.encoding() != "mono8" || m.step() < m.width() || m.data().size() < static_cast<std::size_t>(m.step()) * h ||
      w != options_.camera.intrinsics.width || h != options_.camera.intrinsics.height) {
    counters_.add("images_rejected");
    spdlog::warn("image {}: {} {}x{} does not match the camera ({}x{} mono8); skipped", m.stamp_ns(), m.encoding(), w,
                 h, options_.camera.intrinsics.width, options_.camera.intrinsics.height);
  } else {
    const cv::Mat image(h, w, CV_8UC1, const_cast<uint8_t*>(m.data().data()), m.step());
    std::optional<Eigen::Matrix3d> R_prev_curr_C;
    if (last_frame_ns_ >= 0) {
      R_prev_curr_C = gyro_rotation_C(imu_, last_frame_ns_, m.stamp_ns(), options_.camera.T_BC.linear());
    }
    // Keep only the IMU needed from this frame on (one sample before it, for interpolation).
    const auto keep = std::find_if(imu_.begin(), imu_.end(),
                                   [&](const imu::ImuSample& s) { return s.stamp_ns >= m.stamp_ns(); });
    imu_.erase(imu_.begin(), keep == imu_.begin() ? imu_.begin() : keep - 1);
    last_frame_ns_ = m.stamp_ns();
    FrameResult result;
    try {
      result = frontend_.track(m.stamp_ns(), image, R_prev_curr_C ? &*R_prev_curr_C : nullptr);
    } catch (const InputError& e) {  // e.g. a stamp not after the previous one: skip the frame, keep serving
      counters_.add("images_rejected");
      spdlog::warn("image {}: {}", m.stamp_ns(), e.what());
      send_ack(m);
      return;
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
    features_.publish(out);
    counters_.add("frames_out");
  }
  send_ack(m);
}

void TrackingNode::send_ack(const msg::Image& m) {
  ack_.publish(dds::frame_ack(m.vehicle_id(), "tracking", m.stamp_ns(), m.seq()));
}

}  // namespace twinslam::tracking

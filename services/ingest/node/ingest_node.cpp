#include "ingest_node.hpp"

#include "ack_book.hpp"

#include <cmath>
#include <stdexcept>
#include <thread>

#include <spdlog/spdlog.h>

#include "twinslam/core/error.hpp"
#include "twinslam/dds/convert.hpp"
#include "twinslam/core/shutdown.hpp"
#include "twinslam/ingest/replay.hpp"

namespace twinslam::ingest {
using Clock = std::chrono::steady_clock;

class IngestNode::Impl {
 public:
  Impl(dds::Node& node, const Dataset& ds, IngestOptions opt, const FeatureReplay* features)
      : node_(node),
        ds_(ds),
        opt_(std::move(opt)),
        features_(features),
        heartbeat_(node, counters_),
        acks_(node.config().vehicle_id) {
    if (features_ != nullptr) {
      camera_ = make_camera(features_->camera.intrinsics);
      features_w_ = node.writer<msg::FeatureFrame>(dds::topics::kFeatures, dds::writer_profile(dds::QosFamily::Sensor,
                                                                                               node.config().replay));
    }
    imu_ = node.writer<msg::Imu>(dds::topics::kImu);
    image_ = node.writer<msg::Image>(dds::topics::kImage);
    gnss_ = node.writer<msg::GnssFix>(dds::topics::kGnss);
    node.subscribe<msg::FrameAck>(dds::topics::kFrameAck, [this](const msg::FrameAck& ack) { acks_.on_ack(ack); });
    heartbeat_.set_state(msg::SVC_READY);
  }

  void close_readers() { node_.close_readers(); }

  bool run() {
    if (!wait_for_readers()) return false;
    heartbeat_.set_state(msg::SVC_RUNNING);
    const auto plan = plan_faults(replay_order(ds_, features_ == nullptr ? nullptr : &features_->frames), opt_.faults);
    if (opt_.faults.any()) spdlog::warn("injecting sensor faults: {}", describe_plan(plan));
    const std::int64_t t0 = plan.front().event.stamp_ns;
    const auto wall0 = Clock::now();
    // The log's clock meets the sensor clock here: fault scripts place wall-clock events on the flight with it.
    spdlog::info("replay starts at sensor stamp {} ns ({})", t0, opt_.realtime ? "realtime" : "lockstep");
    std::int64_t pending_frame = -1;  // stamp of the last frame sent and not yet acknowledged
    for (const auto& [ev, action, fault] : plan) {
      if (shutdown_requested()) return false;
      if (fault != nullptr) counters_.add(std::string("fault_") + fault);
      if (action == FaultAction::kDrop) continue;  // never sent, so never waited for
      if (opt_.realtime) {
        const auto due = wall0 + std::chrono::nanoseconds(static_cast<std::int64_t>((ev.stamp_ns - t0) / opt_.speed));
        while (Clock::now() < due && !shutdown_requested()) {
          std::this_thread::sleep_for(std::min<Clock::duration>(due - Clock::now(), std::chrono::milliseconds(20)));
        }
      } else if (is_frame(ev) && pending_frame >= 0) {
        wait_for_acks(pending_frame);
      }
      publish(ev, action);
      if (action == FaultAction::kTwice) publish(ev, action);
      if (is_frame(ev)) pending_frame = ev.stamp_ns;
    }
    if (!opt_.realtime) {
      if (pending_frame >= 0) wait_for_acks(pending_frame);
    }
    heartbeat_.set_state(msg::SVC_DONE);
    spdlog::info("published {} IMU, {} images, {} feature frames, {} GNSS", counters_.get("imu_out"),
                 counters_.get("images_out"), counters_.get("feature_frames_out"), counters_.get("gnss_out"));
    return true;
  }

 private:
  static bool is_frame(const ReplayEvent& ev) { return ev.stream == Stream::Image || ev.stream == Stream::Features; }

  bool wait_for_readers() {
    const auto deadline = Clock::now() + opt_.start_timeout;
    auto ready = [this] {
      const int frame_readers = features_ != nullptr ? features_w_.matched_readers() : image_.matched_readers();
      if (imu_.matched_readers() < opt_.wait_readers.imu || frame_readers < opt_.wait_readers.image ||
          (!ds_.gnss.empty() && gnss_.matched_readers() < opt_.wait_readers.gnss)) {
        return false;
      }
      return acks_.all_ready(opt_.ack_from);
    };
    if (!opt_.ack_from.empty()) {
      // A service is ready once it announced READY: its readers and its ack writer exist by then.
      node_.subscribe<msg::Heartbeat>(dds::topics::kHeartbeat,
                                      [this](const msg::Heartbeat& hb) { acks_.on_heartbeat(hb); });
    }
    while (!ready()) {
      if (shutdown_requested()) return false;
      if (Clock::now() > deadline) throw std::runtime_error(start_timeout_message());
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return true;
  }

  // What the start-up still waited for: matched readers of each stream against those awaited, and the services not
  // heard announcing READY (a secured peer whose DDS-Security handshake never completed shows up here).
  std::string start_timeout_message() const {
    const int frames = features_ != nullptr ? features_w_.matched_readers() : image_.matched_readers();
    const auto count = [](int matched, int wanted) { return std::to_string(matched) + "/" + std::to_string(wanted); };
    std::string text = "no consumer ready within " + std::to_string(opt_.start_timeout.count()) +
                       " ms (matched readers: imu " + count(imu_.matched_readers(), opt_.wait_readers.imu) +
                       ", frames " + count(frames, opt_.wait_readers.image) + ", gnss " +
                       count(gnss_.matched_readers(), ds_.gnss.empty() ? 0 : opt_.wait_readers.gnss);
    std::string missing;
    for (const auto& s : acks_.not_ready(opt_.ack_from)) missing += (missing.empty() ? "" : ", ") + s;
    return text + (missing.empty() ? ")" : "; no READY heard from " + missing + ")");
  }

  // Lockstep: every reliable reader holds everything sent so far (at most one frame in flight, so a burst never
  // overflows the shared-memory segment), and every service in ack_from has finished frame `stamp`.
  void wait_for_acks(std::int64_t stamp) {
    if (!imu_.wait_acknowledged(opt_.ack_timeout) || !image_.wait_acknowledged(opt_.ack_timeout) ||
        !gnss_.wait_acknowledged(opt_.ack_timeout) ||
        (features_ != nullptr && !features_w_.wait_acknowledged(opt_.ack_timeout))) {
      throw std::runtime_error("readers did not acknowledge the samples before frame " + std::to_string(stamp));
    }
    const auto deadline = Clock::now() + opt_.ack_timeout;
    while (true) {
      if (acks_.all_acked(opt_.ack_from, stamp)) return;
      if (shutdown_requested()) return;
      if (Clock::now() > deadline) {
        throw std::runtime_error("frame " + std::to_string(stamp) + " not acknowledged within " +
                                 std::to_string(opt_.ack_timeout.count()) + " ms");
      }
      std::this_thread::sleep_for(std::chrono::microseconds(100));
    }
  }

  void publish(const ReplayEvent& ev, FaultAction action) {
    const std::string& vehicle = node_.config().vehicle_id;
    bool ok = true;
    switch (ev.stream) {
      case Stream::Imu: {
        const auto& r = ds_.imu[ev.index];
        msg::Imu m;
        m.vehicle_id(vehicle);
        m.stamp_ns(r.stamp_ns);
        m.seq(imu_seq_++);
        const double bad = action == FaultAction::kNan ? std::nan("") : INFINITY;
        const bool broken = action == FaultAction::kNan || action == FaultAction::kInf;
        m.gyro_radps(dds::to_msg(broken ? Eigen::Vector3d::Constant(bad) : r.gyro_radps));
        m.accel_mps2(dds::to_msg(broken ? Eigen::Vector3d::Constant(bad) : r.accel_mps2));
        ok = imu_.publish(m);
        counters_.add("imu_out");
        break;
      }
      case Stream::Image: {
        const auto& r = ds_.images[ev.index];
        cv::Mat img = load_mono8(r.file);
        if (action == FaultAction::kBlack) img.setTo(0);
        if (action == FaultAction::kSaturated) img.setTo(255);
        msg::Image m;
        m.vehicle_id(vehicle);
        m.camera_id(opt_.camera_id);
        m.stamp_ns(r.stamp_ns);
        m.seq(image_seq_++);
        m.width(static_cast<uint32_t>(img.cols));
        m.height(static_cast<uint32_t>(img.rows));
        m.step(static_cast<uint32_t>(img.cols));
        m.encoding("mono8");
        m.data().resize(static_cast<std::size_t>(img.cols) * img.rows);
        for (int y = 0; y < img.rows; ++y) {
          std::copy_n(img.ptr<uint8_t>(y), img.cols, m.data().data() + static_cast<std::size_t>(y) * img.cols);
        }
        ok = image_.publish(m);
        counters_.add("images_out");
        break;
      }
      case Stream::Features: {
        msg::FeatureFrame m = feature_message(features_->frames[ev.index]);
        // A black or saturated frame has no texture: a tracker finds no features in it.
        if (action == FaultAction::kBlack || action == FaultAction::kSaturated) m.features().clear();
        ok = features_w_.publish(m);
        counters_.add("feature_frames_out");
        break;
      }
      case Stream::Gnss: {
        const auto& r = ds_.gnss[ev.index];
        msg::GnssFix m;
        m.vehicle_id(vehicle);
        m.stamp_ns(r.stamp_ns);
        m.seq(gnss_seq_++);
        m.latitude_deg(r.latitude_deg);
        m.longitude_deg(r.longitude_deg + (action == FaultAction::kGnssShift ? east_deg(r, opt_.faults) : 0.0));
        m.altitude_m(r.altitude_m);
        m.covariance_enu_m2().fill(0.0);
        m.covariance_enu_m2()[0] = r.std_east_m * r.std_east_m;
        m.covariance_enu_m2()[4] = r.std_north_m * r.std_north_m;
        m.covariance_enu_m2()[8] = r.std_up_m * r.std_up_m;
        m.num_satellites(static_cast<uint16_t>(r.num_satellites));
        ok = gnss_.publish(m);
        counters_.add("gnss_out");
        break;
      }
    }
    if (!ok) {
      // Live: a full history is the consumer's loss, reported; lockstep: a writer blocked for 30 s is a stall.
      counters_.add("publish_failed");
      if (!opt_.realtime) throw std::runtime_error("publishing blocked: a reader stopped taking samples");
    }
  }

  // gnss_jump: east_m metres east as degrees of longitude (a sphere: the jump's size, not survey accuracy, matters).
  static double east_deg(const GnssRecord& r, const FaultConfig& faults) {
    constexpr double kEarthRadius = 6378137.0;  // [m]
    return faults.gnss_jump.east_m / (kEarthRadius * std::cos(r.latitude_deg * M_PI / 180.0)) * 180.0 / M_PI;
  }

  msg::FeatureFrame feature_message(const FeatureFrameRecord& r) {
    msg::FeatureFrame m;
    m.vehicle_id(node_.config().vehicle_id);
    m.camera_id(opt_.camera_id);
    m.stamp_ns(r.stamp_ns);
    m.seq(feature_seq_++);
    m.tracking_ms(0.0);
    m.features().reserve(r.features.size());
    for (const auto& o : r.features) {
      Eigen::Vector3d f_C;
      if (!camera_->unproject(Eigen::Vector2d(o.u, o.v), &f_C)) {
        counters_.add("features_unprojectable");
        continue;
      }
      msg::Feature f;
      f.id(o.landmark_id);
      f.u(static_cast<float>(o.u));
      f.v(static_cast<float>(o.v));
      f.bearing_C(dds::to_msg(f_C));
      f.track_length(o.track_length);
      m.features().push_back(f);
    }
    return m;
  }

  dds::Node& node_;
  const Dataset& ds_;
  IngestOptions opt_;
  const FeatureReplay* features_;
  std::unique_ptr<CameraModel> camera_;
  dds::Writer<msg::FeatureFrame> features_w_;
  dds::Counters counters_;
  dds::HeartbeatPublisher heartbeat_;
  dds::Writer<msg::Imu> imu_;
  dds::Writer<msg::Image> image_;
  dds::Writer<msg::GnssFix> gnss_;
  AckBook acks_;
  unsigned long long imu_seq_ = 0, image_seq_ = 0, gnss_seq_ = 0, feature_seq_ = 0;
};

WaitReaders parse_wait_readers(const std::string& text, int fallback) {
  WaitReaders w{fallback, fallback, 0};
  if (text.empty()) return w;
  auto number = [&](const std::string& s) {
    try {
      std::size_t used = 0;
      const int n = std::stoi(s, &used);
      if (used == s.size() && n >= 0) return n;
    } catch (const std::exception&) {
    }
    throw UsageError("--wait-readers: '" + text + "' is not N or imu=N,image=N,gnss=N");
  };
  if (text.find('=') == std::string::npos) {
    w.imu = w.image = number(text);
    return w;
  }
  w = {};
  std::size_t start = 0;
  while (start < text.size()) {
    const auto end = std::min(text.find(',', start), text.size());
    const std::string item = text.substr(start, end - start);
    const auto eq = item.find('=');
    const std::string key = item.substr(0, eq);
    const int n = number(eq == std::string::npos ? "" : item.substr(eq + 1));
    if (key == "imu") w.imu = n;
    else if (key == "image") w.image = n;
    else if (key == "gnss") w.gnss = n;
    else throw UsageError("--wait-readers: unknown stream '" + key + "'");
    start = end + 1;
  }
  return w;
}

IngestNode::IngestNode(dds::Node& node, const Dataset& dataset, IngestOptions options, const FeatureReplay* features)
    : impl_(new Impl(node, dataset, std::move(options), features)) {}
IngestNode::~IngestNode() {
  // The FrameAck and Heartbeat callbacks capture the Impl and belong to the node, which outlives this object: close
  // them (waiting for any running one) first. Without this, the acks and heartbeats other services still send while
  // they shut down reached a deleted Impl (ingest exited with signal 11 after a complete city-long run).
  impl_->close_readers();
  delete impl_;
}
bool IngestNode::run() { return impl_->run(); }

}  // namespace twinslam::ingest

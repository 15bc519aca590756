#pragma once
// A worker thread that processes camera frames in arrival order, each once the IMU stream has reached the frame's
// stamp (so everything integrated up to the frame is complete), or after `max_wait` if the IMU lags or has ended;
// and that hands over "side inputs" — global measurements such as a map registration or a GNSS fix — in sensor-time
// order relative to the frames: with each frame, every side input received so far whose stamp is at or before the
// frame's, sorted by stamp. A side input stamped in the past (a registration answering an older keyframe) goes with
// the next frame.
//
// Determinism in lockstep replay: frames, IMU and GNSS come from one replaying source in stamp order, acknowledged
// before the next frame is sent, so what is queued at each frame is fixed. A reply computed by another service (a
// registration for keyframe K) is not: expect_side(K) holds the next frames until a side input stamped K arrives, or
// `timeout` passes (then it is counted in expectations_timed_out()). Used by the tracking and estimator services, whose
// inputs arrive on separate topics with no order between them.
#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace twinslam {

struct NoSideInput {};

// Imu must have an `std::int64_t stamp_ns` member.
template <class Frame, class Imu, class Side = NoSideInput>
class SensorWorker {
 public:
  // handler(frame, imu, side): `imu` holds the samples received since the previous frame was handed over, `side` the
  // side inputs due with this frame (see above), in stamp order (arrival order among equal stamps).
  using Handler = std::function<void(const Frame&, std::vector<Imu>&&, std::vector<Side>&&)>;
  using FrameHandler = std::function<void(const Frame&, std::vector<Imu>&&)>;

  SensorWorker(std::chrono::milliseconds max_wait, Handler handler)
      : max_wait_(max_wait), handler_(std::move(handler)), thread_([this] { run(); }) {}
  // Without side inputs.
  SensorWorker(std::chrono::milliseconds max_wait, FrameHandler handler)
      : SensorWorker(max_wait, Handler([h = std::move(handler)](const Frame& f, std::vector<Imu>&& imu,
                                                                std::vector<Side>&&) { h(f, std::move(imu)); })) {}

  ~SensorWorker() {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
    }
    wake_.notify_one();
    thread_.join();
  }
  SensorWorker(const SensorWorker&) = delete;
  SensorWorker& operator=(const SensorWorker&) = delete;

  // False (sample dropped) if its stamp is not after the previous sample's.
  bool push_imu(const Imu& sample) {
    std::lock_guard lock(mutex_);
    if (sample.stamp_ns <= last_imu_ns_) return false;
    last_imu_ns_ = sample.stamp_ns;
    imu_.push_back(sample);
    wake_.notify_one();
    return true;
  }

  void push_frame(std::shared_ptr<const Frame> frame, std::int64_t stamp_ns) {
    std::lock_guard lock(mutex_);
    pending_.push_back({std::move(frame), stamp_ns, std::chrono::steady_clock::now()});
    wake_.notify_one();
  }

  void push_side(std::int64_t stamp_ns, Side side) {
    std::lock_guard lock(mutex_);
    side_.emplace(stamp_ns, std::move(side));  // multimap: stamp order, arrival order among equal stamps
    expected_.erase(stamp_ns);
    wake_.notify_one();
  }

  // Holds the frames not yet handed over until a side input stamped `stamp_ns` arrives, or `timeout` passes. Call it
  // from the handler (the worker thread) right after publishing what the side input will answer.
  void expect_side(std::int64_t stamp_ns, std::chrono::milliseconds timeout) {
    std::lock_guard lock(mutex_);
    if (side_.count(stamp_ns) == 0) expected_[stamp_ns] = std::chrono::steady_clock::now() + timeout;
  }

  unsigned long long expectations_timed_out() const {
    std::lock_guard lock(mutex_);
    return timed_out_;
  }

 private:
  struct Pending {
    std::shared_ptr<const Frame> frame;
    std::int64_t stamp_ns;
    std::chrono::steady_clock::time_point arrived;
  };

  // With the lock held: true while an expected side input may still come (expired expectations are dropped).
  bool awaiting_side(std::chrono::steady_clock::time_point now) {
    for (auto it = expected_.begin(); it != expected_.end();) {
      if (now < it->second) return true;
      ++timed_out_;
      it = expected_.erase(it);
    }
    return false;
  }

  void run() {
    std::unique_lock lock(mutex_);
    while (!stop_) {
      if (pending_.empty()) {
        wake_.wait(lock);
        continue;
      }
      const Pending& front = pending_.front();
      const auto now = std::chrono::steady_clock::now();
      if ((last_imu_ns_ < front.stamp_ns && now - front.arrived < max_wait_) || awaiting_side(now)) {
        wake_.wait_for(lock, std::chrono::milliseconds(10));
        continue;
      }
      const auto frame = front.frame;
      const std::int64_t stamp = front.stamp_ns;
      pending_.pop_front();
      std::vector<Imu> imu;
      imu.swap(imu_);
      std::vector<Side> side;
      const auto due_end = side_.upper_bound(stamp);
      for (auto it = side_.begin(); it != due_end; ++it) side.push_back(std::move(it->second));
      side_.erase(side_.begin(), due_end);
      lock.unlock();
      handler_(*frame, std::move(imu), std::move(side));
      lock.lock();
    }
  }

  std::chrono::milliseconds max_wait_;
  Handler handler_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Pending> pending_;
  std::vector<Imu> imu_;
  std::multimap<std::int64_t, Side> side_;
  std::map<std::int64_t, std::chrono::steady_clock::time_point> expected_;  // stamp -> deadline
  unsigned long long timed_out_ = 0;
  std::int64_t last_imu_ns_ = INT64_MIN;
  bool stop_ = false;
  std::thread thread_;  // last: starts after every member above is constructed
};

// The tracking service's worker: frames and IMU only.
template <class Frame, class Imu>
using ImuGatedWorker = SensorWorker<Frame, Imu, NoSideInput>;

}  // namespace twinslam

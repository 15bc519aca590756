#pragma once
// A worker thread that processes camera frames in arrival order, each once the IMU stream has reached the frame's
// stamp (so everything integrated up to the frame is complete), or after `max_wait` if the IMU lags or has ended.
// Deterministic whenever the IMU covers the frame, and never stuck at the end of a dataset. Used by the tracking
// and estimator services, whose frames and IMU arrive on separate topics with no order between them.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace twinslam {

// Imu must have an `std::int64_t stamp_ns` member.
template <class Frame, class Imu>
class ImuGatedWorker {
 public:
  // handler(frame, imu): `imu` holds the samples received since the previous frame was handed over.
  using Handler = std::function<void(const Frame&, std::vector<Imu>&&)>;

  ImuGatedWorker(std::chrono::milliseconds max_wait, Handler handler)
      : max_wait_(max_wait), handler_(std::move(handler)), thread_([this] { run(); }) {}

  ~ImuGatedWorker() {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
    }
    wake_.notify_one();
    thread_.join();
  }
  ImuGatedWorker(const ImuGatedWorker&) = delete;
  ImuGatedWorker& operator=(const ImuGatedWorker&) = delete;

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

 private:
  struct Pending {
    std::shared_ptr<const Frame> frame;
    std::int64_t stamp_ns;
    std::chrono::steady_clock::time_point arrived;
  };

  void run() {
    std::unique_lock lock(mutex_);
    while (!stop_) {
      if (pending_.empty()) {
        wake_.wait(lock);
        continue;
      }
      const Pending& front = pending_.front();
      if (last_imu_ns_ < front.stamp_ns && std::chrono::steady_clock::now() - front.arrived < max_wait_) {
        wake_.wait_for(lock, std::chrono::milliseconds(10));
        continue;
      }
      const auto frame = front.frame;
      pending_.pop_front();
      std::vector<Imu> imu;
      imu.swap(imu_);
      lock.unlock();
      handler_(*frame, std::move(imu));
      lock.lock();
    }
  }

  std::chrono::milliseconds max_wait_;
  Handler handler_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Pending> pending_;
  std::vector<Imu> imu_;
  std::int64_t last_imu_ns_ = INT64_MIN;
  bool stop_ = false;
  std::thread thread_;  // last: starts after every member above is constructed
};

}  // namespace twinslam

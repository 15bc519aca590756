// SensorWorker (common/core): frames wait for the IMU, side inputs (global measurements) reach the handler in stamp
// order relative to the frames, and expect_side() makes the order independent of when a reply arrives.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "twinslam/core/sensor_worker.hpp"

namespace twinslam {
namespace {

using namespace std::chrono_literals;

struct Imu {
  std::int64_t stamp_ns;
};
struct Frame {
  std::int64_t stamp_ns;
};
struct Side {
  std::int64_t stamp_ns;
  std::string what;
};

// What the handler saw, as one line per frame: "f<stamp> [side stamps]".
class Log {
 public:
  void add(const std::string& s) {
    std::lock_guard lock(m_);
    lines_.push_back(s);
  }
  std::vector<std::string> lines() {
    std::lock_guard lock(m_);
    return lines_;
  }

 private:
  std::mutex m_;
  std::vector<std::string> lines_;
};

void wait_frames(Log& log, std::size_t n) {
  for (int i = 0; i < 500 && log.lines().size() < n; ++i) std::this_thread::sleep_for(5ms);
}

TEST(SensorWorker, SideInputsComeWithTheFirstFrameAtOrAfterTheirStamp) {
  Log log;
  SensorWorker<Frame, Imu, Side> w(1000ms, [&](const Frame& f, std::vector<Imu>&&, std::vector<Side>&& side) {
    std::string line = "f" + std::to_string(f.stamp_ns);
    for (const auto& s : side) line += " " + s.what;
    log.add(line);
  });
  // Side inputs out of stamp order, before and after their frames' IMU; a late one (stamp 5) after frame 20.
  w.push_side(25, {25, "g25"});
  w.push_side(15, {15, "g15"});
  w.push_side(10, {10, "g10"});
  for (std::int64_t t : {10, 20}) w.push_frame(std::make_shared<const Frame>(Frame{t}), t);
  w.push_imu({20});
  wait_frames(log, 2);
  w.push_side(5, {5, "r5"});
  w.push_frame(std::make_shared<const Frame>(Frame{30}), 30);
  w.push_imu({30});
  wait_frames(log, 3);
  EXPECT_EQ(log.lines(), (std::vector<std::string>{"f10 g10", "f20 g15", "f30 r5 g25"}));
}

TEST(SensorWorker, ExpectedReplyKeepsTheOrderWhateverItsLatency) {
  // A "registration" answers each even frame after a random delay; with expect_side the handler sees it with the
  // very next frame every time, for every delay pattern.
  for (unsigned seed = 0; seed < 4; ++seed) {
    Log log;
    std::mt19937 rng(seed);
    std::vector<std::thread> replies;
    SensorWorker<Frame, Imu, Side>* worker = nullptr;
    std::mutex replies_m;
    SensorWorker<Frame, Imu, Side> w(1000ms, [&](const Frame& f, std::vector<Imu>&&, std::vector<Side>&& side) {
      std::string line = "f" + std::to_string(f.stamp_ns);
      for (const auto& s : side) line += " " + s.what;
      log.add(line);
      if (f.stamp_ns % 20 == 0) {
        worker->expect_side(f.stamp_ns, 2000ms);
        const int delay_ms = std::uniform_int_distribution<int>(0, 30)(rng);
        std::lock_guard lock(replies_m);
        replies.emplace_back([&, t = f.stamp_ns, delay_ms] {
          std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
          worker->push_side(t, {t, "r" + std::to_string(t)});
        });
      }
    });
    worker = &w;
    for (std::int64_t t = 10; t <= 80; t += 10) {
      w.push_imu({t});
      w.push_frame(std::make_shared<const Frame>(Frame{t}), t);
    }
    wait_frames(log, 8);
    {
      std::lock_guard lock(replies_m);
      for (auto& r : replies) r.join();
    }
    EXPECT_EQ(log.lines(), (std::vector<std::string>{"f10", "f20", "f30 r20", "f40", "f50 r40", "f60", "f70 r60",
                                                     "f80"}))
        << "seed " << seed;
    EXPECT_EQ(w.expectations_timed_out(), 0u);
  }
}

TEST(SensorWorker, AnExpectedReplyThatNeverComesTimesOutAndIsCounted) {
  Log log;
  SensorWorker<Frame, Imu, Side>* worker = nullptr;
  SensorWorker<Frame, Imu, Side> w(1000ms, [&](const Frame& f, std::vector<Imu>&&, std::vector<Side>&&) {
    log.add("f" + std::to_string(f.stamp_ns));
    if (f.stamp_ns == 10) worker->expect_side(10, 50ms);
  });
  worker = &w;
  for (std::int64_t t : {10, 20}) {
    w.push_imu({t});
    w.push_frame(std::make_shared<const Frame>(Frame{t}), t);
  }
  wait_frames(log, 2);
  EXPECT_EQ(log.lines().size(), 2u);
  EXPECT_EQ(w.expectations_timed_out(), 1u);
}

TEST(SensorWorker, FramesWaitForTheImuUpToMaxWait) {
  Log log;
  ImuGatedWorker<Frame, Imu> w(100ms, [&](const Frame& f, std::vector<Imu>&& imu) {
    log.add("f" + std::to_string(f.stamp_ns) + " imu" + std::to_string(imu.size()));
  });
  w.push_frame(std::make_shared<const Frame>(Frame{30}), 30);
  w.push_imu({10});
  std::this_thread::sleep_for(20ms);
  EXPECT_TRUE(log.lines().empty());  // IMU has not reached 30 yet
  w.push_imu({30});
  wait_frames(log, 1);
  EXPECT_EQ(log.lines(), (std::vector<std::string>{"f30 imu2"}));
  EXPECT_FALSE(w.push_imu({30}));  // not after the previous sample
}

}  // namespace
}  // namespace twinslam

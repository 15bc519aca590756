// Sensor fault injection (faults.hpp): which events each fault touches and how, and its config's errors.
#include <gtest/gtest.h>

#include <algorithm>

#include "twinslam/core/error.hpp"
#include "twinslam/ingest/faults.hpp"
#include "twinslam/ingest/ingest_config.hpp"

namespace twinslam::ingest {
namespace {

constexpr std::int64_t kT0 = 1'000'000'000'000;
constexpr std::int64_t kMs = 1'000'000;

// 3 s of IMU at 200 Hz, frames at 20 Hz, GNSS at 5 Hz, in replay order (stamps equal: IMU first).
std::vector<ReplayEvent> stream() {
  std::vector<ReplayEvent> events;
  for (std::int64_t t = 0; t <= 3000 * kMs; t += 5 * kMs) {
    events.push_back({kT0 + t, Stream::Imu, static_cast<std::size_t>(t / (5 * kMs))});
    if (t % (200 * kMs) == 0) events.push_back({kT0 + t, Stream::Gnss, static_cast<std::size_t>(t / (200 * kMs))});
    if (t % (50 * kMs) == 0) events.push_back({kT0 + t, Stream::Features, static_cast<std::size_t>(t / (50 * kMs))});
  }
  return events;
}

std::size_t count(const std::vector<PlannedEvent>& plan, FaultAction action, Stream stream) {
  return static_cast<std::size_t>(std::count_if(plan.begin(), plan.end(), [&](const PlannedEvent& p) {
    return p.action == action && p.event.stream == stream;
  }));
}

TEST(IngestFaults, NoFaultsPublishEverythingInOrder) {
  const auto events = stream();
  const auto plan = plan_faults(events, FaultConfig{});
  ASSERT_EQ(plan.size(), events.size());
  for (std::size_t i = 0; i < plan.size(); ++i) {
    EXPECT_EQ(plan[i].event.stamp_ns, events[i].stamp_ns);
    EXPECT_EQ(plan[i].action, FaultAction::kPublish);
  }
  EXPECT_FALSE(FaultConfig{}.any());
  EXPECT_EQ(describe_plan(plan), "");
}

TEST(IngestFaults, EachWindowTouchesOnlyItsStreamAndItsTime) {
  FaultConfig c;
  c.imu_gap = {1.0, 0.5};        // [1.0, 1.5) s: 100 IMU samples
  c.imu_nan = {2.0, 0.05};       // 10 samples
  c.frame_drop = {0.5, 0.2};     // 4 frames
  c.frame_black = {2.5, 0.1};    // 2 frames
  c.gnss_jump = {1.0, 1.0, 50};  // 5 fixes
  const auto plan = plan_faults(stream(), c);
  EXPECT_EQ(count(plan, FaultAction::kDrop, Stream::Imu), 100u);
  EXPECT_EQ(count(plan, FaultAction::kNan, Stream::Imu), 10u);
  EXPECT_EQ(count(plan, FaultAction::kDrop, Stream::Features), 4u);
  EXPECT_EQ(count(plan, FaultAction::kBlack, Stream::Features), 2u);
  EXPECT_EQ(count(plan, FaultAction::kGnssShift, Stream::Gnss), 5u);
  EXPECT_EQ(count(plan, FaultAction::kDrop, Stream::Gnss), 0u);
  for (const PlannedEvent& p : plan) {
    const double t = 1e-9 * static_cast<double>(p.event.stamp_ns - kT0);
    if (p.action == FaultAction::kDrop && p.event.stream == Stream::Imu) {
      EXPECT_TRUE(t >= 1.0 && t < 1.5) << t;
    }
  }
  EXPECT_EQ(describe_plan(plan),
            "frame_black 2 frames, frame_drop 4 frames, gnss_jump 5 GNSS fixes, imu_gap 100 IMU samples, "
            "imu_nan 10 IMU samples");
}

TEST(IngestFaults, OutOfOrderSwapsConsecutiveImuSamplesAndDuplicatesRepeat) {
  FaultConfig c;
  c.imu_out_of_order = {1.0, 0.1};  // 20 samples: 10 swapped pairs
  c.imu_duplicate = {2.0, 0.1};
  const auto plan = plan_faults(stream(), c);
  int decreasing = 0;
  std::int64_t last_imu = -1;
  for (const PlannedEvent& p : plan) {
    if (p.event.stream != Stream::Imu) continue;
    if (p.event.stamp_ns < last_imu) ++decreasing;
    last_imu = p.event.stamp_ns;
  }
  EXPECT_EQ(decreasing, 10);
  EXPECT_EQ(count(plan, FaultAction::kTwice, Stream::Imu), 20u);
  EXPECT_EQ(plan.size(), stream().size());  // nothing lost by the reordering
}

TEST(IngestFaults, ConfigReadsTheFaultsSectionAndNamesBadKeys) {
  const IngestConfig c = parse_ingest_config(
      "faults:\n  imu_gap: {at_s: 12, duration_s: 2}\n  gnss_jump: {at_s: 3, duration_s: 5, east_m: -20}\n",
      "ingest.yaml");
  EXPECT_TRUE(c.faults.any());
  EXPECT_DOUBLE_EQ(c.faults.imu_gap.at_s, 12.0);
  EXPECT_DOUBLE_EQ(c.faults.imu_gap.duration_s, 2.0);
  EXPECT_DOUBLE_EQ(c.faults.gnss_jump.east_m, -20.0);
  EXPECT_FALSE(c.faults.frame_drop.enabled());
  try {
    parse_ingest_config("faults:\n  frame_drop: {at_s: 1}\n", "ingest.yaml");
    FAIL() << "a window without a duration was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("ingest.yaml"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("faults.frame_drop.duration_s"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_ingest_config("faults:\n  imu_lag: {at_s: 1, duration_s: 1}\n", "ingest.yaml"), InputError);
}

}  // namespace
}  // namespace twinslam::ingest

// The impairment of one direction of the drone-edge link: what the fault scripts rely on when they say "10 % loss,
// 100 ms delay".
#include <gtest/gtest.h>

#include <cmath>

#include "twinslam/core/error.hpp"
#include "twinslam/netem/impairment.hpp"

namespace {
using twinslam::netem::DelayLine;
using twinslam::netem::NetemConfig;
using namespace std::chrono_literals;

DelayLine::Packet packet_of(std::size_t bytes, std::uint8_t tag) { return DelayLine::Packet(bytes, tag); }

TEST(NetemDelayLine, EveryPacketLeavesAfterTheDelayAndNotBefore) {
  NetemConfig config;
  config.delay_ms = 100.0;
  DelayLine line(config, 1);
  const auto t0 = DelayLine::Clock::time_point{} + 1s;
  ASSERT_TRUE(line.offer(packet_of(100, 1), t0));
  ASSERT_TRUE(line.offer(packet_of(100, 2), t0 + 10ms));
  EXPECT_TRUE(line.release(t0 + 99ms).empty());
  ASSERT_EQ(line.next_due(), t0 + 100ms);
  const auto first = line.release(t0 + 100ms);
  ASSERT_EQ(first.size(), 1u);
  EXPECT_EQ(first[0][0], 1);
  EXPECT_TRUE(line.release(t0 + 109ms).empty());
  EXPECT_EQ(line.release(t0 + 110ms).size(), 1u);
  EXPECT_FALSE(line.next_due().has_value());
  EXPECT_EQ(line.counts().packets_out, 2u);
  EXPECT_EQ(line.counts().bytes_out, 200u);
}

TEST(NetemDelayLine, TheLossShareIsTheConfiguredOneAndTheSameSeedDropsTheSamePackets) {
  NetemConfig config;
  config.loss_pct = 10.0;
  config.seed = 7;
  DelayLine a(config, 1), b(config, 1), other_direction(config, 2);
  const int n = 20000;
  int same = 0, same_as_other = 0;
  for (int i = 0; i < n; ++i) {
    const auto now = DelayLine::Clock::time_point{} + std::chrono::microseconds(i);
    const bool kept_a = a.offer(packet_of(10, 0), now);
    same += kept_a == b.offer(packet_of(10, 0), now);
    same_as_other += kept_a == other_direction.offer(packet_of(10, 0), now);
  }
  // Binomial(20000, 0.1): sd = 42 packets; 5 sd around 2000.
  EXPECT_NEAR(static_cast<double>(a.counts().lost), 0.1 * n, 5 * std::sqrt(n * 0.1 * 0.9));
  EXPECT_EQ(same, n);
  EXPECT_LT(same_as_other, n);  // the two directions draw independently
  EXPECT_EQ(a.counts().packets_in, static_cast<std::uint64_t>(n));
}

TEST(NetemDelayLine, JitterNeverReordersPacketsAndStaysWithinItsBounds) {
  NetemConfig config;
  config.delay_ms = 100.0;
  config.jitter_ms = 50.0;
  DelayLine line(config, 1);
  const auto t0 = DelayLine::Clock::time_point{} + 1s;
  for (int i = 0; i < 200; ++i) ASSERT_TRUE(line.offer(packet_of(4, static_cast<std::uint8_t>(i)), t0 + i * 1ms));
  EXPECT_TRUE(line.release(t0 + 49ms).empty());  // nothing before arrival + delay - jitter
  std::vector<DelayLine::Packet> out;
  for (auto t = t0; t <= t0 + 400ms; t += 1ms) {
    for (auto& p : line.release(t)) out.push_back(std::move(p));
  }
  ASSERT_EQ(out.size(), 200u);  // all out by the last arrival + delay + jitter
  for (std::size_t i = 0; i < out.size(); ++i) EXPECT_EQ(out[i][0], static_cast<std::uint8_t>(i));
}

TEST(NetemDelayLine, AFullQueueDropsAndCountsInsteadOfGrowing) {
  NetemConfig config;
  config.delay_ms = 1000.0;
  config.queue_limit_bytes = 10'000;
  DelayLine line(config, 1);
  const auto t0 = DelayLine::Clock::time_point{} + 1s;
  int kept = 0;
  for (int i = 0; i < 50; ++i) kept += line.offer(packet_of(1000, 0), t0);
  EXPECT_EQ(kept, 10);
  EXPECT_EQ(line.counts().overflowed, 40u);
  EXPECT_LE(line.queued_bytes(), 10'000u);
  line.release(t0 + 1s);
  EXPECT_EQ(line.queued_bytes(), 0u);
  EXPECT_TRUE(line.offer(packet_of(1000, 0), t0 + 1s));
}

TEST(NetemDelayLine, OutOfRangeSettingsAreRefusedNamingTheOption) {
  const auto message = [](NetemConfig config) {
    try {
      config.validate();
    } catch (const twinslam::UsageError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  NetemConfig loss;
  loss.loss_pct = 100.0;
  EXPECT_NE(message(loss).find("--loss"), std::string::npos);
  NetemConfig nan_delay;
  nan_delay.delay_ms = std::nan("");
  EXPECT_NE(message(nan_delay).find("--delay"), std::string::npos);
  NetemConfig jitter;
  jitter.delay_ms = 10.0;
  jitter.jitter_ms = 20.0;
  EXPECT_NE(message(jitter).find("--jitter"), std::string::npos);
  EXPECT_EQ(message(NetemConfig{}), "accepted");
}

}  // namespace

// Missing camera frames told from the stamps (frame_gap.hpp), as the estimator reports ODOM_FAULT_FRAME_GAP.
#include <gtest/gtest.h>

#include "twinslam/estimator/frame_gap.hpp"

namespace twinslam::estimator {
namespace {

constexpr std::int64_t kPeriod = 50'000'000;  // 20 Hz

TEST(FrameGap, OneMissingFrameIsAGapJitterIsNot) {
  FrameGapDetector gaps;
  std::int64_t t = 1'000'000'000'000;
  EXPECT_FALSE(gaps.on_frame(t));
  for (int i = 0; i < 10; ++i) EXPECT_FALSE(gaps.on_frame(t += kPeriod + (i % 2 ? 3'000'000 : -3'000'000)));
  EXPECT_TRUE(gaps.on_frame(t += 2 * kPeriod));   // one frame missing
  EXPECT_FALSE(gaps.on_frame(t += kPeriod));
  EXPECT_TRUE(gaps.on_frame(t += 20 * kPeriod));  // a second missing
  EXPECT_FALSE(gaps.on_frame(t));                 // a repeated stamp is not a frame
  EXPECT_FALSE(gaps.on_frame(t - kPeriod));       // nor is one from the past
  EXPECT_FALSE(gaps.on_frame(t += kPeriod));
}

TEST(FrameGap, TheFirstIntervalIsNeverAGap) {
  FrameGapDetector gaps;
  EXPECT_FALSE(gaps.on_frame(0));
  EXPECT_FALSE(gaps.on_frame(10 * kPeriod));  // no period known yet
  EXPECT_FALSE(gaps.on_frame(11 * kPeriod));  // the period shrinks to the true one
  EXPECT_TRUE(gaps.on_frame(13 * kPeriod));
}

}  // namespace
}  // namespace twinslam::estimator

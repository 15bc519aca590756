// The estimator service's DDS shell in one process: IMU and feature frames of a platform at rest go in; an Odometry
// and a FrameAck ("estimator") come out for every frame of its vehicle, tracking once static initialization succeeded;
// frames of another vehicle are ignored.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>
#include <unistd.h>
#include <vector>

#include "estimator_node.hpp"
#include "twinslam/dds/topics.hpp"
#include "wait_for.hpp"

namespace twinslam::estimator {
namespace {

using namespace std::chrono_literals;

using testing::wait_for;

TEST(EstimatorNode, OdometryAndAckPerFrameOfItsVehicle) {
  const int domain = 150 + static_cast<int>(::getpid() % 80);  // away from the default domain and other test runs
  dds::NodeConfig service_cfg;
  service_cfg.service = "estimator";
  service_cfg.domain = domain;
  dds::NodeConfig test_cfg = service_cfg;
  test_cfg.service = "test";
  dds::Node service_node(service_cfg), test_node(test_cfg);
  dds::Counters counters;
  EstimatorNodeOptions options;
  options.estimator.max_solver_time_s = 1.0;
  EstimatorNode node(service_node, counters, options);

  std::mutex mutex;
  std::vector<msg::Odometry> odometry;
  std::vector<msg::FrameAck> acks;
  test_node.subscribe<msg::Odometry>(dds::topics::kOdometry, [&](const msg::Odometry& m) {
    std::lock_guard lock(mutex);
    odometry.push_back(m);
  });
  test_node.subscribe<msg::FrameAck>(dds::topics::kFrameAck, [&](const msg::FrameAck& m) {
    std::lock_guard lock(mutex);
    acks.push_back(m);
  });
  auto imu = test_node.writer<msg::Imu>(dds::topics::kImu);
  auto features = test_node.writer<msg::FeatureFrame>(dds::topics::kFeatures);
  ASSERT_TRUE(wait_for([&] { return imu.matched_readers() >= 1 && features.matched_readers() >= 1; }, 5s));

  // 1.5 s at rest, level: specific force +g along z; 30 still features; frames at 20 Hz from 0.1 s.
  const std::int64_t t0 = 1'000'000'000;
  int frames_sent = 0;
  for (int k = 0; k <= 300; ++k) {
    const std::int64_t t = t0 + 5'000'000LL * k;
    msg::Imu m;
    m.vehicle_id("uav0");
    m.stamp_ns(t);
    m.seq(k);
    m.accel_mps2().z(9.81);
    ASSERT_TRUE(imu.publish(m));
    if (k >= 20 && k % 10 == 0) {
      msg::FeatureFrame f;
      f.vehicle_id(frames_sent % 5 == 4 ? "other" : "uav0");  // every fifth frame belongs to another vehicle
      f.stamp_ns(t);
      f.seq(frames_sent++);
      for (int i = 0; i < 30; ++i) {
        msg::Feature feat;
        feat.id(i);
        const Eigen::Vector3d b = Eigen::Vector3d(0.02 * (i % 6) - 0.05, 0.03 * (i / 6) - 0.06, 1.0).normalized();
        feat.bearing_C().x(b.x());
        feat.bearing_C().y(b.y());
        feat.bearing_C().z(b.z());
        f.features().push_back(feat);
      }
      ASSERT_TRUE(features.publish(f));
    }
  }
  const std::size_t own_frames = static_cast<std::size_t>(frames_sent - frames_sent / 5);
  ASSERT_TRUE(wait_for([&] {
    std::lock_guard lock(mutex);
    return acks.size() >= own_frames && odometry.size() >= own_frames;
  }, 20s)) << "acks " << acks.size() << ", odometry " << odometry.size() << " of " << own_frames;
  std::this_thread::sleep_for(200ms);  // nothing more must arrive
  std::lock_guard lock(mutex);
  EXPECT_EQ(acks.size(), own_frames);
  EXPECT_EQ(odometry.size(), own_frames);
  for (const auto& a : acks) {
    EXPECT_EQ(a.service(), "estimator");
    EXPECT_EQ(a.vehicle_id(), "uav0");
  }
  // At rest from the first frame: static initialization needs 0.5 s of IMU and two still frames.
  EXPECT_EQ(odometry.front().status(), msg::ODOM_INITIALIZING);
  EXPECT_EQ(odometry.back().status(), msg::ODOM_TRACKING);
  const auto& p = odometry.back().T_WB().p();
  EXPECT_LT(std::abs(p.x()) + std::abs(p.y()) + std::abs(p.z()), 0.05);  // held still
  EXPECT_EQ(counters.get("features_in"), own_frames);
}

}  // namespace
}  // namespace twinslam::estimator

// The ingest node's lifetime on DDS: once destroyed, nothing another service sends may reach it.
#include <gtest/gtest.h>

#include <chrono>

#include "dataset_fixture.hpp"
#include "ingest_node.hpp"
#include "subprocess.hpp"
#include "wait_for.hpp"

namespace twinslam::ingest {
namespace {

using namespace std::chrono_literals;

dds::NodeConfig config(const std::string& service) {
  dds::NodeConfig c;
  c.service = service;
  c.domain = test::test_domain();
  return c;
}

TEST(IngestNode, ClosesItsReadersWhenDestroyedSoLateAcksReachNothing) {
  const Dataset dataset = load_dataset(test::euroc_dir());
  dds::Node node(config("ingest"));  // outlives the IngestNode, as in twinslam-ingest's main
  dds::Node peer(config("estimator"));
  auto acks = peer.writer<msg::FrameAck>(dds::topics::kFrameAck);
  {
    IngestNode ingest(node, dataset, IngestOptions{});
    ASSERT_TRUE(testing::wait_for([&] { return acks.matched_readers() > 0; }, 10s)) << "the ingest node reads acks";
  }
  // Its callbacks captured the deleted node: the readers must be gone, not merely unused (the heartbeat reader of
  // run() is closed the same way).
  EXPECT_TRUE(testing::wait_for([&] { return acks.matched_readers() == 0; }, 10s));
  msg::FrameAck ack;
  ack.vehicle_id(node.config().vehicle_id);
  ack.service("estimator");
  ack.stamp_ns(1);
  acks.publish(ack);  // would have run the deleted node's callback
}

// A start that never completes says what it waited for: which streams lack readers and whose READY never came (in CI
// a secured run's ingest once timed out without saying which).
TEST(IngestNode, AStartUpTimeoutNamesTheMissingReadersAndServices) {
  const Dataset dataset = load_dataset(test::euroc_dir());
  dds::Node node(config("ingest"));
  dds::Node peer(config("estimator"));
  peer.subscribe<msg::Imu>(dds::topics::kImu, [](const msg::Imu&) {});
  IngestOptions options;
  options.wait_readers = {1, 1, 0};
  options.ack_from = {"estimator"};
  options.start_timeout = std::chrono::milliseconds(4000);  // discovery takes well under a second
  IngestNode ingest(node, dataset, options);
  try {
    ingest.run();
    FAIL() << "ingest started without an image reader";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("no consumer ready within 4000 ms"), std::string::npos) << what;
    EXPECT_NE(what.find("imu 1/1, frames 0/1"), std::string::npos) << what;
    EXPECT_NE(what.find("no READY heard from estimator"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace twinslam::ingest

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

}  // namespace
}  // namespace twinslam::ingest

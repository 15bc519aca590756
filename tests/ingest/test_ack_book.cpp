// Lockstep's bookkeeping (services/ingest/node/ack_book.hpp): a fleet shares the ack and heartbeat topics, so only
// this vehicle's acknowledgements and readiness may let its ingest go on.
#include <gtest/gtest.h>

#include "ack_book.hpp"

namespace twinslam::ingest {
namespace {

msg::FrameAck ack(const std::string& vehicle, const std::string& service, std::int64_t stamp_ns) {
  msg::FrameAck a;
  a.vehicle_id(vehicle);
  a.service(service);
  a.stamp_ns(stamp_ns);
  return a;
}

msg::Heartbeat heartbeat(const std::string& vehicle, const std::string& service, msg::ServiceState state) {
  msg::Heartbeat h;
  h.vehicle_id(vehicle);
  h.service(service);
  h.state(state);
  return h;
}

TEST(AckBook, AnotherVehiclesAcksAndHeartbeatsDoNotCount) {
  AckBook book("uav1");
  book.on_ack(ack("uav2", "estimator", 500));
  book.on_heartbeat(heartbeat("uav2", "estimator", msg::SVC_RUNNING));
  EXPECT_FALSE(book.all_acked({"estimator"}, 100));
  EXPECT_FALSE(book.all_ready({"estimator"}));
  book.on_heartbeat(heartbeat("", "registration", msg::SVC_READY));  // serves every vehicle
  // The start-up timeout names who it still waits for.
  EXPECT_EQ(book.not_ready({"tracking", "estimator", "registration"}), (std::vector<std::string>{"tracking", "estimator"}));
  book.on_heartbeat(heartbeat("uav1", "estimator", msg::SVC_READY));
  EXPECT_TRUE(book.all_ready({"estimator", "registration"}));
  EXPECT_TRUE(book.not_ready({"estimator", "registration"}).empty());
}

TEST(AckBook, AcknowledgedFramesNeverGoBackAndEveryServiceMustHaveAcked) {
  AckBook book("uav1");
  book.on_ack(ack("uav1", "estimator", 300));
  book.on_ack(ack("uav1", "estimator", 200));  // late sample
  EXPECT_EQ(book.last_acked("estimator"), 300);
  EXPECT_TRUE(book.all_acked({"estimator"}, 300));
  EXPECT_FALSE(book.all_acked({"estimator", "tracking"}, 300));
  book.on_ack(ack("uav1", "tracking", 300));
  EXPECT_TRUE(book.all_acked({"estimator", "tracking"}, 300));
  EXPECT_FALSE(book.all_acked({"estimator", "tracking"}, 301));
}

TEST(AckBook, OnlyReadyOrRunningMakesAServiceReady) {
  AckBook book("uav1");
  for (const auto s : {msg::SVC_STARTING, msg::SVC_DONE, msg::SVC_STOPPING, msg::SVC_FAILED}) {
    book.on_heartbeat(heartbeat("uav1", "tracking", s));
  }
  EXPECT_FALSE(book.all_ready({"tracking"}));
  book.on_heartbeat(heartbeat("uav1", "tracking", msg::SVC_RUNNING));
  EXPECT_TRUE(book.all_ready({"tracking"}));
}

}  // namespace
}  // namespace twinslam::ingest

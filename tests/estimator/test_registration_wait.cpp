// When a lockstep estimator holds frames for a registration (registration_wait.hpp): only while the registration is
// matched both ways, and not after `give_up_after` waits in a row ran out until a registration arrives again.
#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>

#include "estimator_node.hpp"
#include "registration_wait.hpp"
#include "twinslam/dds/topics.hpp"

namespace twinslam::estimator {
namespace {

using namespace std::chrono_literals;

TEST(RegistrationWait, WaitsOnlyForARegistrationThatIsMatched) {
  RegistrationWait wait(3);
  EXPECT_TRUE(wait.should_wait(true));
  EXPECT_FALSE(wait.should_wait(false));
}

TEST(RegistrationWait, GivesUpAfterWaitsInARowRanOutAndWaitsAgainOnceOneArrives) {
  RegistrationWait wait(3);
  // Registrations answer: no wait runs out.
  EXPECT_EQ(wait.observe(0, 5).timed_out, 0u);
  // Two waits run out, then a registration arrives: the count in a row starts again.
  EXPECT_EQ(wait.observe(2, 5).timed_out, 2u);
  EXPECT_TRUE(wait.should_wait(true));
  EXPECT_FALSE(wait.observe(2, 6).gave_up);
  EXPECT_FALSE(wait.observe(4, 6).gave_up);  // two in a row
  EXPECT_TRUE(wait.should_wait(true));
  const auto third = wait.observe(5, 6);
  EXPECT_EQ(third.timed_out, 1u);
  EXPECT_TRUE(third.gave_up);
  EXPECT_FALSE(wait.should_wait(true));
  EXPECT_FALSE(wait.observe(5, 6).gave_up);  // said once
  EXPECT_FALSE(wait.should_wait(true));
  // A late answer arrives: frames wait again.
  wait.observe(5, 7);
  EXPECT_TRUE(wait.should_wait(true));
}

// The node's side: the link is up once a registration's LocalMap reader and Registration writer are matched; without
// them the estimator does not hold frames, and waiting for the link ends at its timeout.
TEST(RegistrationWait, TheNodeSeesTheLinkOnlyWhenARegistrationIsMatchedBothWays) {
  const int domain = 150 + static_cast<int>((::getpid() + 37) % 80);
  dds::NodeConfig service_cfg;
  service_cfg.service = "estimator";
  service_cfg.domain = domain;
  dds::NodeConfig edge_cfg = service_cfg;
  edge_cfg.service = "registration";
  dds::Node service_node(service_cfg);
  dds::Counters counters;
  EstimatorNodeOptions options;
  options.await_registration = true;
  EstimatorNode node(service_node, counters, options);
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_FALSE(node.wait_for_registration_link(300ms));
  EXPECT_GE(std::chrono::steady_clock::now() - t0, 300ms);
  dds::Node edge(edge_cfg);
  edge.subscribe<msg::LocalMap>(dds::topics::kLocalMap, [](const msg::LocalMap&) {});
  EXPECT_FALSE(node.wait_for_registration_link(300ms)) << "heard but not answered: no registration writer yet";
  const auto registrations = edge.writer<msg::Registration>(dds::topics::kRegistration);
  ASSERT_TRUE(registrations.valid());
  EXPECT_TRUE(node.wait_for_registration_link(10s));
  EXPECT_TRUE(node.registration_link_up());
}

}  // namespace
}  // namespace twinslam::estimator

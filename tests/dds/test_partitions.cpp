// DDS partitions for a fleet on one edge (issue 14 item 6): each vehicle's processes talk in a partition named after
// it, the edge's in "edge,*". A vehicle's samples reach the edge and never another vehicle; the edge's reach every
// vehicle; a registration instance that serves half of the fleet ("uav0,uav1,edge") reads only that half. Participants
// of one process on a private domain; a sample that must not arrive is given 2 s to do so.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <memory>
#include <string>

#include "subprocess.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/dds/node.hpp"
#include "wait_for.hpp"

namespace twinslam::dds {
namespace {

using namespace std::chrono_literals;

// A participant in `partition` that counts the Odometry samples it reads.
struct Peer {
  explicit Peer(const std::string& partition) {
    NodeConfig c;
    c.service = "test";
    c.domain = twinslam::test::test_domain();
    c.partition = partition;
    node = std::make_unique<Node>(c);
    node->subscribe<msg::Odometry>(topics::kOdometry, [this](const msg::Odometry&) { ++read; });
    out = node->writer<msg::Odometry>(topics::kOdometry);
  }
  void publish_for(std::chrono::milliseconds how_long) const {
    const auto end = std::chrono::steady_clock::now() + how_long;
    msg::Odometry m;
    while (std::chrono::steady_clock::now() < end) {
      out.publish(m);
      std::this_thread::sleep_for(20ms);
    }
  }
  std::atomic<int> read{0};
  std::unique_ptr<Node> node;
  Writer<msg::Odometry> out;
};

TEST(DdsPartitions, AVehiclesSamplesReachTheEdgeAndItsHalfButNoOtherVehicle) {
  Peer uav0("uav0"), uav1("uav1"), uav2("uav2"), edge("edge,*"), half("uav0,uav1,edge"), other_half("uav2,uav3,edge"),
      unpartitioned("");
  // Matched readers of uav0's writer: its own reader, the edge, the half that serves it; nobody else.
  ASSERT_TRUE(testing::wait_for([&] { return uav0.out.matched_readers() >= 3; }, 10s));
  uav0.publish_for(2s);
  EXPECT_GT(uav0.read.load(), 0);
  EXPECT_GT(edge.read.load(), 0);
  EXPECT_GT(half.read.load(), 0);
  EXPECT_EQ(uav1.read.load(), 0) << "another vehicle read uav0's samples";
  EXPECT_EQ(uav2.read.load(), 0) << "another vehicle read uav0's samples";
  EXPECT_EQ(other_half.read.load(), 0) << "the instance serving uav2 and uav3 read uav0's samples";
  EXPECT_EQ(unpartitioned.read.load(), 0) << "a participant in the default partition read uav0's samples";
  EXPECT_EQ(uav0.out.matched_readers(), 3);
}

TEST(DdsPartitions, TheEdgesSamplesReachEveryVehicleAndTheOtherEdgeServices) {
  Peer edge("edge,*"), tiles("edge,*"), uav0("uav0"), uav7("uav7"), half("uav2,uav3,edge");
  ASSERT_TRUE(testing::wait_for([&] { return edge.out.matched_readers() >= 5; }, 10s));
  edge.publish_for(1s);
  EXPECT_GT(tiles.read.load(), 0) << "edge services read each other (MapTile from tiles to registration)";
  EXPECT_GT(uav0.read.load(), 0);
  EXPECT_GT(uav7.read.load(), 0);
  EXPECT_GT(half.read.load(), 0);
}

TEST(DdsPartitions, AnEmptyNameIsRefusedAndTheEnvironmentNamesTheDefault) {
  EXPECT_THROW(resolve_partitions("uav0,,uav1"), UsageError);
  EXPECT_THROW(resolve_partitions(",uav0"), UsageError);
  EXPECT_EQ(resolve_partitions("uav0,edge"), (std::vector<std::string>{"uav0", "edge"}));
  ::setenv("TWINSLAM_PARTITION", "uav[0-4],edge", 1);
  EXPECT_EQ(resolve_partitions(""), (std::vector<std::string>{"uav[0-4]", "edge"}));
  EXPECT_EQ(resolve_partitions("uav9"), (std::vector<std::string>{"uav9"}));  // the option wins over the environment
  ::setenv("TWINSLAM_PARTITION", "a,", 1);
  EXPECT_THROW(resolve_partitions(""), UsageError);
  ::unsetenv("TWINSLAM_PARTITION");
  EXPECT_TRUE(resolve_partitions("").empty());
}

}  // namespace
}  // namespace twinslam::dds

// Which Foxglove channels the pipeline feeds (common/foxglove/derived_channels.hpp): per-vehicle topics, a path that
// grows by distance and keeps its extent when thinned, the registered cloud only for an accepted registration of a
// LocalMap still held, twin tiles latched by key, an undecodable tile counted rather than thrown.
#include <gtest/gtest.h>

#include "foxglove_test_util.hpp"
#include "twinslam/foxglove/derived_channels.hpp"

namespace twinslam::foxglove {
namespace {

using nlohmann::json;
using test::pose;
using test::transform;

msg::Odometry odometry(const std::string& vehicle, double x) {
  msg::Odometry m;
  m.vehicle_id(vehicle);
  m.status(msg::ODOM_ALIGNED);
  m.T_WB(pose(transform(0, {x, 0, 0})));
  return m;
}

std::vector<std::string> topics(const std::vector<DerivedMessage>& out) {
  std::vector<std::string> t;
  for (const auto& d : out) t.push_back(d.topic);
  return t;
}

TEST(FoxgloveDerivedChannels, ThePathGrowsByDistanceAndIsThinnedWithoutLosingItsEnds) {
  DerivedChannelsConfig config;
  config.path_spacing_m = 1.0;
  config.max_path_poses = 8;
  DerivedChannels channels(config);
  EXPECT_EQ(topics(channels.on(odometry("uav0", 0.0))),
            (std::vector<std::string>{"/uav0/estimate/pose", "/uav0/estimate/path"}));
  EXPECT_EQ(topics(channels.on(odometry("uav0", 0.5))), std::vector<std::string>{"/uav0/estimate/pose"});
  msg::Odometry initializing = odometry("uav0", 50);
  initializing.status(msg::ODOM_INITIALIZING);
  EXPECT_EQ(channels.on(initializing).size(), 1u);  // no pose for the path yet
  json last;
  for (int x = 1; x <= 20; ++x) last = json::parse(channels.on(odometry("uav0", x)).back().json);
  const json& poses = last["poses"];
  EXPECT_LE(poses.size(), 8u);
  EXPECT_GE(poses.size(), 4u);
  EXPECT_EQ(poses.front()["position"]["x"], 0.0);
  EXPECT_EQ(poses.back()["position"]["x"], 20.0);
  // Another vehicle has its own topics and path.
  const auto other = channels.on(odometry("uav1", 3));
  ASSERT_EQ(other.size(), 2u);
  EXPECT_EQ(other[1].topic, "/uav1/estimate/path");
  EXPECT_EQ(json::parse(other[1].json)["poses"].size(), 1u);
}

TEST(FoxgloveDerivedChannels, TheRegisteredCloudFollowsOnlyAnAcceptedRegistrationOfAHeldLocalMap) {
  DerivedChannels channels;
  const auto map = test::local_map("uav0", 1000, transform(0, {0, 0, 0}), {{1, 2, 3}});
  EXPECT_EQ(topics(channels.on(map)), std::vector<std::string>{"/uav0/landmarks"});
  msg::Registration r;
  r.vehicle_id("uav0");
  r.keyframe_stamp_ns(1000);
  r.correction_W(pose(transform(0, {0, 0, 2})));
  r.status(msg::REG_REJECTED_RMSE);
  EXPECT_EQ(topics(channels.on(r)), std::vector<std::string>{"/uav0/registration"});
  r.status(msg::REG_ACCEPTED);
  const auto accepted = channels.on(r);
  ASSERT_EQ(topics(accepted), (std::vector<std::string>{"/uav0/registration", "/uav0/landmarks/registered"}));
  const auto points = test::cloud_points(json::parse(accepted[1].json));
  ASSERT_EQ(points.size(), 1u);
  EXPECT_EQ(points[0][2], 5.0f);  // lifted by the correction
  r.keyframe_stamp_ns(999);       // a LocalMap the bridge never saw
  EXPECT_EQ(channels.on(r).size(), 1u);
  r.vehicle_id("uav1");           // another vehicle's registration of the same stamp
  r.keyframe_stamp_ns(1000);
  EXPECT_EQ(channels.on(r).size(), 1u);
}

TEST(FoxgloveDerivedChannels, UnwatchedOnlyKeepsStateAndTilesAndAWatcherThenGetsTheWholePath) {
  DerivedChannels channels;
  for (int x = 0; x < 3; ++x) EXPECT_TRUE(channels.on(odometry("uav0", 2.0 * x), /*render=*/false).empty());
  EXPECT_TRUE(channels.on(test::local_map("uav0", 5, transform(0, {0, 0, 0}), {{1, 2, 3}}), false).empty());
  msg::MapTile tile;
  tile.tile_key("t/0_0");
  EXPECT_EQ(channels.on(tile, false).size(), 1u);  // latched: made even when nobody watches
  const auto watched = channels.on(odometry("uav0", 6.0));
  ASSERT_EQ(watched.size(), 2u);
  EXPECT_EQ(json::parse(watched[1].json)["poses"].size(), 4u);  // the poses seen unwatched are in the path
  msg::Registration r;
  r.vehicle_id("uav0");
  r.keyframe_stamp_ns(5);
  r.status(msg::REG_ACCEPTED);
  r.correction_W(pose(transform(0, {0, 0, 0})));
  EXPECT_EQ(channels.on(r).size(), 2u);  // the LocalMap kept unwatched gives the registered cloud
}

TEST(FoxgloveDerivedChannels, TilesAreLatchedByKeyAndAnUndecodableOneIsCounted) {
  DerivedChannels channels;
  msg::MapTile tile;
  tile.tile_key("t/1_1");
  const auto out = channels.on(tile);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].topic, "/twin/tiles");
  EXPECT_EQ(out[0].latch_key, "t/1_1");
  tile.tile_key("");  // a tile without a key is latched too (under "")
  EXPECT_EQ(channels.on(tile).at(0).latch_key, "");
  tile.mesh_draco({1, 2, 3});
  EXPECT_TRUE(channels.on(tile).empty());
  EXPECT_EQ(channels.tiles_undecodable(), 1u);
  EXPECT_TRUE(channels.on(msg::Imu{}).empty());  // no well-known form
  EXPECT_EQ(DerivedChannels::prefix(""), "/unnamed");
}

}  // namespace
}  // namespace twinslam::foxglove

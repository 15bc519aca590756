// The channels the web view draws next to the estimate (derived_channels.hpp): the ground truth only as far as the
// estimate has come, GNSS fixes placed in W through the dataset's origin, and the services' heartbeats latched per
// instance (a viewer that connects late sees every service).
#include <cmath>

#include <gtest/gtest.h>

#include "foxglove_test_util.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/foxglove/derived_channels.hpp"

namespace twinslam::foxglove {
namespace {

using nlohmann::json;

msg::Odometry odometry_at(std::int64_t stamp_ns, double x) {
  msg::Odometry m;
  m.vehicle_id("uav0");
  m.stamp_ns(stamp_ns);
  m.status(msg::ODOM_ALIGNED);
  m.T_WB(test::pose(test::transform(0, {x, 0, 0})));
  return m;
}

const DerivedMessage* find(const std::vector<DerivedMessage>& out, const std::string& topic) {
  for (const auto& d : out) if (d.topic == topic) return &d;
  return nullptr;
}

TEST(FoxgloveViewChannels, TheTruthIsDrawnOnlyAsFarAsTheEstimateHasCome) {
  DerivedChannels channels;
  std::vector<StampedPoseW> truth;
  for (int i = 0; i < 10; ++i) truth.push_back({i * 1'000'000'000LL, {{0.0, 5.0 * i, 0.0}, {1, 0, 0, 0}}});
  channels.set_truth("uav0", truth);
  const auto first = channels.on(odometry_at(2'500'000'000LL, 0.0));
  const DerivedMessage* t = find(first, "/uav0/truth/path");
  ASSERT_NE(t, nullptr);
  const json poses = json::parse(t->json)["poses"];
  ASSERT_EQ(poses.size(), 3u);  // stamps 0, 1 and 2 s: none after the estimate's 2.5 s
  EXPECT_DOUBLE_EQ(poses[2]["position"]["y"].get<double>(), 10.0);
  EXPECT_EQ(find(channels.on(odometry_at(2'600'000'000LL, 0.0)), "/uav0/truth/path"), nullptr);  // no new truth
  const auto later = channels.on(odometry_at(20'000'000'000LL, 0.0));
  ASSERT_NE(find(later, "/uav0/truth/path"), nullptr);
  EXPECT_EQ(json::parse(find(later, "/uav0/truth/path")->json)["poses"].size(), 10u);
  EXPECT_EQ(find(DerivedChannels().on(odometry_at(1, 0.0)), "/uav0/truth/path"), nullptr);  // no truth given
}

TEST(FoxgloveViewChannels, GnssFixesArePlacedInWThroughTheOrigin) {
  DerivedChannels channels;
  msg::GnssFix fix;
  fix.vehicle_id("uav0");
  fix.latitude_deg(52.0);
  fix.longitude_deg(13.0);
  fix.altitude_m(40.0);
  EXPECT_EQ(find(channels.on(fix), "/uav0/gnss/path"), nullptr);  // no origin: only the Map panel's LocationFix
  EXPECT_THROW(channels.set_origin("52.0,13.0"), UsageError);
  channels.set_origin("52.0,13.0,40.0");
  fix.latitude_deg(52.001);  // ~111 m north of the origin
  const auto out = channels.on(fix);
  ASSERT_NE(find(out, "/uav0/gnss/path"), nullptr);
  const json p = json::parse(find(out, "/uav0/gnss/path")->json)["poses"].at(0)["position"];
  EXPECT_NEAR(p["x"].get<double>(), 0.0, 1e-6);
  EXPECT_NEAR(p["y"].get<double>(), 111.25, 0.1);  // WGS84 metres per 0.001 deg of latitude at 52 deg
  EXPECT_NEAR(p["z"].get<double>(), 0.0, 0.01);
  fix.latitude_deg(std::nan(""));  // a broken fix is not drawn
  EXPECT_EQ(find(channels.on(fix), "/uav0/gnss/path"), nullptr);
}

TEST(FoxgloveViewChannels, HeartbeatsAreLatchedPerServiceInstance) {
  DerivedChannels channels;
  msg::Heartbeat h;
  h.service("estimator");
  h.instance("host:42");
  h.state(msg::SVC_RUNNING);
  h.uptime_ms(1500);
  msg::Counter c;
  c.name("keyframes");
  c.value(7);
  h.counters({c});
  const auto out = channels.on(h, /*render=*/false);  // latched: made even when nobody watches
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].topic, "/services");
  EXPECT_EQ(out[0].latch_key, "estimator@host:42");
  const json j = json::parse(out[0].json);
  EXPECT_EQ(j["state"], "RUNNING");
  EXPECT_EQ(j["counters"][0]["value"], 7);
  EXPECT_EQ(out[0].schema->name, "twinslam.ServiceState");
}

}  // namespace
}  // namespace twinslam::foxglove

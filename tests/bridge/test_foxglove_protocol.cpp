// What the bridge says and what a client's requests do (Foxglove WebSocket protocol v1): the frames a viewer decodes
// must be byte-exact, and no client message may throw or subscribe to something that is not there.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "twinslam/bridge/bridge_config.hpp"
#include "twinslam/bridge/foxglove_protocol.hpp"
#include "twinslam/core/error.hpp"

namespace twinslam::bridge {
namespace {

using nlohmann::json;

TEST(FoxgloveProtocol, MessageDataIsOpcodeSubscriptionTimeThenPayloadLittleEndian) {
  const std::uint8_t payload[] = {0xaa, 0xbb};
  const auto f = message_data(0x04030201u, 0x0c0b0a0908070605ull, payload, 2);
  const std::vector<std::uint8_t> want = {0x01, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 0xaa, 0xbb};
  EXPECT_EQ(f, want);
}

TEST(FoxgloveProtocol, AdvertiseListsEveryChannelWithItsSchema) {
  const json a = json::parse(advertise_json({{3, "twinslam/v2/odometry", "cdr", "twinslam::msg::Odometry", "omgidl",
                                              "module twinslam { };"}}));
  EXPECT_EQ(a["op"], "advertise");
  ASSERT_EQ(a["channels"].size(), 1u);
  const json& c = a["channels"][0];
  EXPECT_EQ(c["id"], 3);
  EXPECT_EQ(c["topic"], "twinslam/v2/odometry");
  EXPECT_EQ(c["encoding"], "cdr");
  EXPECT_EQ(c["schemaName"], "twinslam::msg::Odometry");
  EXPECT_EQ(c["schemaEncoding"], "omgidl");
  EXPECT_EQ(c["schema"], "module twinslam { };");
  const json info = json::parse(server_info_json("twinslam-bridge", "42"));
  EXPECT_EQ(info["op"], "serverInfo");
  EXPECT_TRUE(info["capabilities"].empty());  // streaming only: no client publishing, parameters or services
}

TEST(FoxgloveProtocol, SubscribeAndUnsubscribeRouteChannelsToSubscriptionIds) {
  ClientSubscriptions c({1, 2, 3});
  EXPECT_TRUE(c.apply(R"({"op":"subscribe","subscriptions":[{"id":10,"channelId":2},{"id":11,"channelId":3}]})")
                  .empty());
  EXPECT_EQ(c.subscriptions_of(2), std::vector<std::uint32_t>{10});
  EXPECT_EQ(c.subscriptions_of(3), std::vector<std::uint32_t>{11});
  EXPECT_TRUE(c.subscriptions_of(1).empty());
  EXPECT_TRUE(c.apply(R"({"op":"unsubscribe","subscriptionIds":[10]})").empty());
  EXPECT_TRUE(c.subscriptions_of(2).empty());
  EXPECT_EQ(c.size(), 1u);
}

TEST(FoxgloveProtocol, BadClientMessagesAreAnsweredWithAStatusAndChangeNothing) {
  ClientSubscriptions c({1});
  for (const char* text : {"not json", "[1,2]", R"({"op":7})", R"({"op":"subscribe"})",
                           R"({"op":"subscribe","subscriptions":[{"id":-1,"channelId":1}]})",
                           R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":99}]})",
                           R"({"op":"subscribe","subscriptions":[{"id":4294967296,"channelId":1}]})",
                           R"({"op":"unsubscribe","subscriptionIds":[5]})", R"({"op":"setParameters"})"}) {
    const auto status = c.apply(text);
    ASSERT_EQ(status.size(), 1u) << text;
    EXPECT_EQ(json::parse(status[0])["op"], "status") << text;
  }
  EXPECT_EQ(c.size(), 0u);
  EXPECT_TRUE(c.apply(R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":1}]})").empty());
  const auto reused = c.apply(R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":1}]})");
  ASSERT_EQ(reused.size(), 1u);
  EXPECT_EQ(json::parse(reused[0])["level"], 2);
  EXPECT_EQ(c.size(), 1u);
}

TEST(BridgeConfig, BadValuesAreRefusedNamingTheKey) {
  EXPECT_NO_THROW(BridgeConfig{}.validate());
  EXPECT_THROW(parse_bridge_config("port: 70000\n", "b.yaml").validate("b.yaml"), InputError);
  EXPECT_THROW(parse_bridge_config("colour: red\n", "b.yaml"), InputError);
  try {
    parse_bridge_config("max_queued: 1\n", "b.yaml").validate("b.yaml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("b.yaml: bridge key 'max_queued'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace twinslam::bridge

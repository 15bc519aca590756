// Each conversion of common/foxglove against what Foxglove's panels need: frames and stamps, poses in W with the
// quaternion's w last, landmark clouds placed by T_WL (and by a registration's correction, eq. 3) to float32
// precision, twin tiles decoded to the triangles the twin store holds, and JSON that stays valid for any message.
#include <array>
#include <cmath>
#include <limits>
#include <set>

#include <gtest/gtest.h>

#include "foxglove_test_util.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/twin/store.hpp"

namespace twinslam::foxglove {
namespace {

using nlohmann::json;
using test::pose;
using test::transform;

json required_of(const Schema& s) { return json::parse(s.jsonschema)["required"]; }

// Every top-level key of `message` is one its schema requires, and the other way round.
void expect_matches_schema(const json& message, const Schema& schema) {
  std::vector<std::string> keys;
  for (const auto& [k, v] : message.items()) keys.push_back(k);
  std::vector<std::string> required = required_of(schema).get<std::vector<std::string>>();
  std::sort(keys.begin(), keys.end());
  std::sort(required.begin(), required.end());
  EXPECT_EQ(keys, required) << schema.name;
}

TEST(FoxgloveWellKnown, APoseIsTheBodyInTheWorldWithTheQuaternionsWLast) {
  msg::Odometry m;
  m.vehicle_id("uav1");
  m.stamp_ns(1'403'715'273'262'142'976LL);
  m.T_WB(pose(transform(30, {1, 2, 3})));
  const json j = json::parse(pose_json(m));
  EXPECT_EQ(j["frame_id"], "world");
  EXPECT_EQ(j["timestamp"]["sec"], 1'403'715'273LL);
  EXPECT_EQ(j["timestamp"]["nsec"], 262'142'976);
  EXPECT_DOUBLE_EQ(j["pose"]["position"]["y"].get<double>(), 2.0);
  EXPECT_NEAR(j["pose"]["orientation"]["w"].get<double>(), std::cos(M_PI / 12), 1e-12);
  EXPECT_NEAR(j["pose"]["orientation"]["z"].get<double>(), std::sin(M_PI / 12), 1e-12);
  expect_matches_schema(j, pose_in_frame_schema());
}

TEST(FoxgloveWellKnown, NonFiniteNumbersNegativeStampsAndBadUtf8StillGiveValidJson) {
  msg::GnssFix fix;
  fix.vehicle_id(std::string("uav\xff\xfe", 5));
  fix.stamp_ns(-5);
  fix.latitude_deg(std::numeric_limits<double>::quiet_NaN());
  fix.longitude_deg(std::numeric_limits<double>::infinity());
  const json j = json::parse(location_fix_json(fix));  // throws if the text is not JSON
  EXPECT_TRUE(j["latitude"].is_null());
  EXPECT_TRUE(j["longitude"].is_null());
  EXPECT_EQ(j["timestamp"]["sec"], 0);
  EXPECT_EQ(j["timestamp"]["nsec"], 0);
  EXPECT_EQ(j["position_covariance"].size(), 9u);
  EXPECT_EQ(j["position_covariance_type"], 3);
  expect_matches_schema(j, location_fix_schema());

  msg::Registration r;
  r.reason(std::string("\xc3", 1));
  r.status(static_cast<msg::RegistrationStatus>(77));  // a newer sender's status
  const json h = json::parse(registration_health_json(r));
  EXPECT_EQ(h["status"], "UNKNOWN");
  expect_matches_schema(h, registration_health_schema());
}

TEST(FoxgloveWellKnown, LandmarksArePlacedByTwlAndByTheRegistrationsCorrection) {
  const Eigen::Isometry3d T_WL = transform(90, {10, 0, 1});
  const std::vector<Eigen::Vector3d> p_L{{1, 0, 0}, {0, 2, 0}, {3, 4, 5}};
  const msg::LocalMap m = test::local_map("uav0", 7, T_WL, p_L);
  const Eigen::Isometry3d dT = transform(-5, {0.5, -0.25, 0.1});
  const msg::Pose correction = pose(dT);
  for (const bool corrected : {false, true}) {
    const json cloud = json::parse(landmarks_json(m, corrected ? &correction : nullptr));
    expect_matches_schema(cloud, point_cloud_schema());
    EXPECT_EQ(cloud["point_stride"], 16);
    EXPECT_EQ(cloud["fields"][3]["name"], "quality");
    const auto points = test::cloud_points(cloud);
    ASSERT_EQ(points.size(), p_L.size());
    for (std::size_t i = 0; i < p_L.size(); ++i) {
      const Eigen::Vector3d want = (corrected ? dT : Eigen::Isometry3d::Identity()) * T_WL * p_L[i];
      for (int k = 0; k < 3; ++k) {  // float32 of the double result (the quaternion round trip moves the last bits)
        EXPECT_NEAR(points[i][k], want[k], 1e-6 * (1.0 + std::abs(want[k]))) << i << " " << k;
      }
      EXPECT_EQ(points[i][3], 0.25f * static_cast<float>(i % 4));
    }
  }
}

TEST(FoxgloveWellKnown, ATileBecomesOneSceneEntityWithTheTwinsTriangles) {
  twin::Mesh box;
  box.p_W = {{100, 200, 0}, {110, 200, 0}, {110, 210, 0}, {100, 210, 12}};
  box.triangles = {{0, 1, 2}, {0, 2, 3}};
  msg::MapTile tile;
  tile.tile_key("city/2_4");
  tile.twin_id("city");
  tile.mesh_draco(twin::encode_mesh(box, twin::StoreConfig{}));
  const json scene = json::parse(tile_scene_json(tile));
  expect_matches_schema(scene, scene_update_schema());
  ASSERT_EQ(scene["entities"].size(), 1u);
  const json& e = scene["entities"][0];
  EXPECT_EQ(e["id"], "tile/city/2_4");
  EXPECT_EQ(e["frame_id"], "world");
  ASSERT_EQ(e["triangles"].size(), 1u);
  const json& t = e["triangles"][0];
  ASSERT_EQ(t["indices"].size(), 6u);
  ASSERT_EQ(t["points"].size(), 4u);
  // Draco may reorder vertices and faces: the triangles, as sets of corners rounded to the centimetre, are the box's.
  const auto corners = [](const Eigen::Vector3d& p) {
    return std::array<long, 3>{std::lround(p.x() * 100), std::lround(p.y() * 100), std::lround(p.z() * 100)};
  };
  std::multiset<std::set<std::array<long, 3>>> got, want;
  for (std::size_t i = 0; i < 6; i += 3) {
    std::set<std::array<long, 3>> g, w;
    for (std::size_t k = 0; k < 3; ++k) {
      const json& p = t["points"][t["indices"][i + k].get<std::size_t>()];
      g.insert(corners({p["x"].get<double>(), p["y"].get<double>(), p["z"].get<double>()}));
      w.insert(corners(box.p_W[static_cast<std::size_t>(box.triangles[i / 3][static_cast<int>(k)])]));
    }
    got.insert(g);
    want.insert(w);
  }
  EXPECT_EQ(got, want);

  msg::MapTile empty;
  empty.tile_key("city/9_9");
  EXPECT_TRUE(json::parse(tile_scene_json(empty))["entities"][0]["triangles"].empty());
  msg::MapTile corrupt = tile;
  corrupt.mesh_draco().resize(9);
  EXPECT_THROW(tile_scene_json(corrupt), InputError);
}

TEST(FoxgloveWellKnown, SchemasAreJsonSchemasTitledWithTheirNames) {
  for (const Schema* s : {&pose_in_frame_schema(), &poses_in_frame_schema(), &location_fix_schema(),
                          &point_cloud_schema(), &scene_update_schema(), &registration_health_schema()}) {
    const json j = json::parse(s->jsonschema);
    EXPECT_EQ(j["title"], s->name);
    EXPECT_EQ(j["type"], "object");
    for (const auto& key : j["required"]) EXPECT_TRUE(j["properties"].contains(key)) << s->name << " " << key;
  }
}

}  // namespace
}  // namespace twinslam::foxglove

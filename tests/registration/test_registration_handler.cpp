// The registration service's handlers without DDS (registration_handler.hpp), fed the samples a faulty or hostile
// peer sends (issue 15): a LocalMap of a million landmarks is refused unread, one NaN landmark makes the cloud a
// rejection that names it, a tile whose Draco bytes are corrupt is named when it enters the window and a good copy
// of it replaces it - every LocalMap is answered, none throws. The fuzz target dds_registration does the same with
// arbitrary samples.
#include <gtest/gtest.h>

#include "local_map_message.hpp"
#include "registration_handler.hpp"
#include "synthetic_twin.hpp"
#include "twinslam/dds/convert.hpp"
#include "twinslam/twin/store.hpp"

namespace twinslam::registration {
namespace {

msg::MapTile map_tile(const twin::TileKey& key, const test::PointSet& t) {
  msg::MapTile tile;
  tile.tile_key("synthetic/" + key.str());
  Eigen::AlignedBox3d b;
  for (const auto& p : t.p_W) b.extend(p);
  for (int k = 0; k < 3; ++k) tile.bounds_W()[k] = b.min()[k], tile.bounds_W()[3 + k] = b.max()[k];
  twin::Mesh m;
  m.p_W = t.p_W;
  m.n_W = t.n_W;
  const auto bytes = twin::encode_points(m, twin::StoreConfig{});
  tile.points_draco(std::vector<std::uint8_t>(bytes.begin(), bytes.end()));
  return tile;
}

// A LocalMap of `count` landmarks on the synthetic city seen through a 0.5 m error, keyframe body in the street.
msg::LocalMap street_map(int count) {
  const Eigen::Vector3d body = test::kCentre + Eigen::Vector3d(0, -45, 8);
  const SourceInput src = test::make_source(test::sample_noisy(test::city_surfaces(), count, 0.05, 3),
                                            test::offset_about(body, Eigen::Vector3d::UnitZ(), 0.0, {0.5, 0, 0}), body);
  return test::local_map("uav1", 1'000'000'000, src);
}

class RegistrationHandlerTest : public ::testing::Test {
 protected:
  dds::Counters counters;
  RegistrationHandler handler{counters, RegistrationNodeOptions{}};
  std::map<twin::TileKey, test::PointSet> tiles = test::split_tiles(test::sample_grid(test::city_surfaces(), 1.0));
  void SetUp() override {
    for (const auto& [key, t] : tiles) handler.on_tile(map_tile(key, t));
  }
};

TEST_F(RegistrationHandlerTest, AGoodLocalMapIsAccepted) {
  const msg::Registration r = handler.on_local_map(street_map(600));
  EXPECT_EQ(r.status(), msg::REG_ACCEPTED) << r.reason();
  EXPECT_NEAR(dds::from_msg(r.correction_W()).translation().x(), -0.5, 0.05);
}

TEST_F(RegistrationHandlerTest, AMillionLandmarksAreRefusedUnread) {
  msg::LocalMap huge = street_map(600);
  huge.landmarks().resize(1'000'000, huge.landmarks().front());
  const msg::Registration r = handler.on_local_map(huge);
  EXPECT_EQ(r.status(), msg::REG_REJECTED_FEW_POINTS);
  EXPECT_EQ(r.reason(), "bad input: LocalMap has 1000000 landmarks > max_landmarks 100000");
}

TEST_F(RegistrationHandlerTest, ANonFiniteLandmarkMakesTheCloudARejectionThatNamesIt) {
  msg::LocalMap map = street_map(600);
  map.landmarks()[17].p_L().y(std::numeric_limits<double>::quiet_NaN());
  const msg::Registration r = handler.on_local_map(map);
  EXPECT_EQ(r.status(), msg::REG_REJECTED_FEW_POINTS);
  EXPECT_EQ(r.reason(), "bad input: registration source: landmark 17 is not finite");
  EXPECT_EQ(handler.on_local_map(street_map(600)).status(), msg::REG_ACCEPTED);  // the next good one is served
  // Finite but beyond any world (found by the dds_registration fuzz target: the tile number of -2.6e100 m overflowed
  // an int).
  map = street_map(600);
  map.landmarks()[3].p_L().x(-2.56e100);
  EXPECT_EQ(handler.on_local_map(map).reason(),
            "bad input: registration source: landmark 3 beyond the world's extent (1e7 m)");
  map = street_map(600);
  map.T_WL().p().y(4e12);
  EXPECT_EQ(handler.on_local_map(map).reason(),
            "bad input: vehicle position not finite or beyond the world's extent (1e7 m from W's origin)");
}

TEST(RegistrationHandler, ACorruptTileIsNamedAndAGoodCopyReplacesIt) {
  dds::Counters counters;
  RegistrationHandler handler{counters, RegistrationNodeOptions{}};
  const auto tiles = test::split_tiles(test::sample_grid(test::city_surfaces(), 1.0));
  const auto& [bad_key, bad_points] = *tiles.begin();
  for (const auto& [key, t] : tiles) {
    msg::MapTile tile = map_tile(key, t);
    if (key == bad_key) tile.points_draco().resize(tile.points_draco().size() / 2);  // cut in transit
    handler.on_tile(tile);
  }
  msg::Registration r = handler.on_local_map(street_map(600));
  EXPECT_EQ(r.status(), msg::REG_REJECTED_FEW_POINTS);
  EXPECT_NE(r.reason().find(bad_key.str()), std::string::npos) << r.reason();
  handler.on_tile(map_tile(bad_key, bad_points));  // the tiles service sends it again
  r = handler.on_local_map(street_map(600));
  EXPECT_EQ(r.status(), msg::REG_ACCEPTED) << r.reason();
  msg::MapTile nameless = map_tile(bad_key, bad_points);
  nameless.tile_key("synthetic/not-a-tile");
  handler.on_tile(nameless);
  EXPECT_EQ(counters.get("tiles_rejected"), 1u);
}

}  // namespace
}  // namespace twinslam::registration

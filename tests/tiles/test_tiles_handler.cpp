// The tiles service's handlers without DDS (tiles_handler.hpp): what a diverged estimate, a broken GNSS fix or a
// malformed request does — counted as rejected, no tile sent, the window left where it was.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "tiles_handler.hpp"
#include "twinslam/dds/convert.hpp"
#include "twinslam/twin/geo.hpp"
#include "twinslam/twin/store.hpp"

namespace twinslam::tiles {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

// A 200 m x 200 m ground plane: 16 tiles of 50 m.
TilesConfig plane_store(const std::filesystem::path& dir) {
  twin::Mesh m;
  m.p_W = {{-100, -100, 0}, {100, -100, 0}, {100, 100, 0}, {-100, 100, 0}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  twin::StoreConfig store;
  store.point_spacing_m = 5.0;
  std::filesystem::remove_all(dir);
  twin::build_twin_store(m, {47.3769, 8.5417, 408.0}, store, dir.string());
  TilesConfig c;
  c.twin_dir = dir.string();
  c.window_m = 100.0;
  return c;
}

msg::Odometry odometry(const Eigen::Vector3d& p_W, msg::OdometryStatus status = msg::ODOM_ALIGNED) {
  msg::Odometry m;
  m.vehicle_id("uav1");
  m.status(status);
  m.T_WB().p(dds::to_msg(p_W));
  return m;
}

class TilesHandlerTest : public ::testing::Test {
 protected:
  TilesHandlerTest()
      : handler(counters, plane_store(store_dir), "", [this](const msg::MapTile& t) {
          sent.push_back(t.tile_key());
          return true;
        }) {}
  ~TilesHandlerTest() override { std::filesystem::remove_all(store_dir); }
  // One store per test process: ctest runs the cases of this fixture in parallel, and a shared folder was removed
  // under a running case (CI: "cannot remove all: No such file or directory").
  const std::filesystem::path store_dir =
      std::filesystem::path(::testing::TempDir()) / ("tiles_handler_store_" + std::to_string(::getpid()));
  dds::Counters counters;
  std::vector<std::string> sent;
  TilesHandler handler;
};

TEST_F(TilesHandlerTest, ANonFiniteOrFarAwayOdometryMovesNoWindow) {
  handler.on_odometry(odometry({kNan, 0, 0}));
  handler.on_odometry(odometry({0, std::numeric_limits<double>::infinity(), 0}));
  EXPECT_EQ(counters.get("odometry_rejected"), 2u);
  handler.on_odometry(odometry({1e12, 0, 0}));  // finite: the window is simply outside the twin
  EXPECT_TRUE(sent.empty());
  EXPECT_EQ(counters.get("odometry_in"), 3u);
  handler.on_odometry(odometry({0, 0, 10}));
  EXPECT_EQ(sent.size(), 4u);  // the window [-50, 50)^2 meets the 4 tiles around the origin
  EXPECT_EQ(counters.get("tiles_sent"), 4u);
}

TEST_F(TilesHandlerTest, ABrokenGnssFixIsRejectedAndAGoodOneStreams) {
  msg::GnssFix fix;
  fix.vehicle_id("uav1");
  for (const auto& [lat, lon] : std::vector<std::pair<double, double>>{{kNan, 8.5417}, {47.3769, kNan}, {91.0, 8.0}}) {
    fix.latitude_deg(lat);
    fix.longitude_deg(lon);
    fix.altitude_m(410.0);
    handler.on_gnss(fix);
  }
  EXPECT_EQ(counters.get("gnss_rejected"), 3u);
  EXPECT_TRUE(sent.empty());
  const Eigen::Vector3d lla = twin::EnuFrame({47.3769, 8.5417, 408.0}).to_lla({25, 25, 2});
  fix.latitude_deg(lla.x());
  fix.longitude_deg(lla.y());
  handler.on_gnss(fix);
  EXPECT_EQ(sent.size(), 9u);  // the window [-25, 75)^2 around the middle of tile (0, 0) meets 3 x 3 tiles
  EXPECT_EQ(counters.get("gnss_in"), 4u);
}

TEST_F(TilesHandlerTest, AMalformedRequestIsRejectedAndAGoodOneResends) {
  handler.on_odometry(odometry({0, 0, 10}));
  ASSERT_EQ(sent.size(), 4u);
  msg::TileRequest r;
  r.vehicle_id("uav1");
  for (const double half : {-1.0, 0.0, kNan}) {
    r.half_size_m(half);
    handler.on_request(r);
  }
  r.half_size_m(10.0);
  r.center_e_m(kNan);
  handler.on_request(r);
  EXPECT_EQ(counters.get("tile_requests_rejected"), 4u);
  EXPECT_EQ(sent.size(), 4u);
  r.center_e_m(0.0);
  r.have({"no/such_key", sent[0]});
  handler.on_request(r);  // holds one of the four: the other three go out again
  EXPECT_EQ(sent.size(), 7u);
}

}  // namespace
}  // namespace twinslam::tiles

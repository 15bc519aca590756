// The tiles service over DDS in one process (private domain): a TilesNode on the city-loops twin store and a test
// participant that plays the vehicle (GNSS first, then odometry) and reads MapTile.
// 1. A 60 s slice of the flight at 10 Hz: GNSS drives the window while odometry is still in the local frame (its
//    T_WB there is deliberately elsewhere and must be ignored), then aligned odometry; every tile within 75 m arrives
//    before the vehicle is within 50 m of it, none twice, with its Draco bytes and bounds.
// 2. A reader that joins after the tiles were published still receives every one of them (TRANSIENT_LOCAL), and
//    nothing is re-published for it.
// 3. A TileRequest gets exactly the tiles of its window the requester says it lacks, latched or not; a malformed one
//    is rejected.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <thread>

#include "city_twin_fixture.hpp"
#include "streaming_check.hpp"
#include "tiles_node.hpp"
#include "twinslam/dds/convert.hpp"
#include "wait_for.hpp"

namespace twinslam::tiles {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

using testing::wait_for;

class TilesNodeTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() / ("twinslam_tiles_node_" + std::to_string(::getpid())));
    city_ = new test::CityTwin(test::make_city_twin("city-loops", 0, *dir_ / "twin"));
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete city_;
    delete dir_;
  }
  // One private domain per test, away from the default and from other test binaries.
  static dds::NodeConfig node_config(const std::string& service, int offset) {
    dds::NodeConfig c;
    c.service = service;
    c.vehicle_id = "";
    c.domain = 100 + static_cast<int>(::getpid() % 20) * 2 + offset;
    return c;
  }
  static TilesConfig tiles_config() {
    TilesConfig c;
    c.twin_dir = city_->twin_dir;
    c.window_m = 150.0;  // the checks below are for a 75 m half window
    return c;
  }

  static fs::path* dir_;
  static test::CityTwin* city_;
};
fs::path* TilesNodeTest::dir_ = nullptr;
test::CityTwin* TilesNodeTest::city_ = nullptr;

// What a test reader saw on MapTile, keyed by the grid key.
struct TileLog {
  std::mutex mutex;
  std::map<twin::TileKey, test::Receipt> received;
  std::map<twin::TileKey, msg::MapTile> tiles;
  std::atomic<int> update{0};  // the vehicle's update index when a tile arrives
  std::atomic<unsigned long long> arrivals{0};

  void on_tile(const TileGrid& grid, const msg::MapTile& m) {
    const auto key = grid.parse_wire_key(m.tile_key());
    ASSERT_TRUE(key) << m.tile_key();
    std::lock_guard lock(mutex);
    test::Receipt& r = received[*key];
    if (r.count++ == 0) r.update = update.load();
    tiles[*key] = m;
    ++arrivals;
  }
  std::size_t size() {
    std::lock_guard lock(mutex);
    return received.size();
  }
};

TEST_F(TilesNodeTest, GnssThenOdometryStreamsEveryNearTileInTimeOnce) {
  dds::Node service_node(node_config("tiles", 0)), vehicle(node_config("test", 0));
  dds::Counters counters;
  TilesNode node(service_node, counters, tiles_config());
  const TileGrid grid(city_->index);
  TileLog log;
  vehicle.subscribe<msg::MapTile>(dds::topics::kMapTile, [&](const msg::MapTile& m) { log.on_tile(grid, m); });
  auto odometry = vehicle.writer<msg::Odometry>(dds::topics::kOdometry);
  auto gnss = vehicle.writer<msg::GnssFix>(dds::topics::kGnss);
  ASSERT_TRUE(wait_for([&] { return odometry.matched_readers() >= 1 && gnss.matched_readers() >= 1; }, 5s));

  const twin::EnuFrame enu(city_->index.origin);
  const Eigen::Vector3d local_offset(180, -160, 0);  // where T_WB points while it is still in L: must be ignored
  const double rate_hz = 10.0, gnss_until_s = 5.0, slice_s = 60.0;
  std::vector<Eigen::Vector3d> positions;
  unsigned long long fixes = 0;
  for (int k = 0; k / rate_hz <= slice_s; ++k) {
    const double t = k / rate_hz;
    const Eigen::Vector3d p_W = city_->trajectory.at(t).p_W;
    positions.push_back(p_W);
    log.update.store(k);
    const bool aligned = t >= gnss_until_s;
    msg::Odometry o;
    o.vehicle_id("uav0");
    o.stamp_ns(static_cast<long long>(t * 1e9));
    o.seq(k);
    o.status(aligned ? msg::ODOM_ALIGNED : msg::ODOM_TRACKING);
    Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
    T_WB.translation() = aligned ? p_W : Eigen::Vector3d(p_W + local_offset);
    o.T_WB(dds::to_msg(T_WB));
    ASSERT_TRUE(odometry.publish(o));
    if (k % 2 == 0) {  // 5 Hz GNSS, all along: ignored once odometry is aligned
      const Eigen::Vector3d lla = enu.to_lla(p_W);
      msg::GnssFix f;
      f.vehicle_id("uav0");
      f.stamp_ns(o.stamp_ns());
      f.latitude_deg(lla.x());
      f.longitude_deg(lla.y());
      f.altitude_m(lla.z());
      ASSERT_TRUE(gnss.publish(f));
      ++fixes;
    }
    // Lockstep, so arrival times are exact whatever the machine's load: the node has handled this update (its counters
    // move after the tiles went out) and every tile it sent has arrived before the vehicle moves on.
    ASSERT_TRUE(wait_for([&] {
      return counters.get("odometry_in") >= static_cast<unsigned long long>(k + 1) &&
             counters.get("gnss_in") >= fixes && log.arrivals.load() >= counters.get("tiles_sent");
    }, 10s)) << "update " << k;
  }
  // Tiles that came within 75 m must all arrive; wait for them, then a little longer to catch duplicates.
  std::set<twin::TileKey> near;
  for (const auto& info : city_->index.tiles) {
    for (const auto& p : positions) {
      if (grid.distance_to_square(info.key, p.head<2>()) < 75.0) {
        near.insert(info.key);
        break;
      }
    }
  }
  ASSERT_TRUE(wait_for([&] { return log.size() >= near.size(); }, 10s)) << log.size() << " of " << near.size();
  std::this_thread::sleep_for(300ms);
  service_node.close_readers();
  vehicle.close_readers();

  std::lock_guard lock(log.mutex);
  EXPECT_GE(test::expect_streamed_in_time(grid, positions, log.received), 9);
  EXPECT_EQ(counters.get("tiles_sent"), log.received.size());
  EXPECT_GT(counters.get("gnss_in"), 0u);
  unsigned long long bytes = 0;
  for (const auto& [key, m] : log.tiles) {
    const twin::TileInfo* info = city_->index.find(key);
    ASSERT_NE(info, nullptr);
    EXPECT_EQ(m.twin_id(), city_->index.twin_id);
    EXPECT_EQ(m.triangles(), info->triangles);
    EXPECT_EQ(m.points(), info->points);
    EXPECT_EQ(m.mesh_draco(), twin::read_tile_file(city_->twin_dir, key, false));
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(m.bounds_W()[i], info->bounds_W.min()[i], 1e-4);
      EXPECT_NEAR(m.bounds_W()[3 + i], info->bounds_W.max()[i], 1e-4);
    }
    bytes += m.mesh_draco().size() + m.points_draco().size();
  }
  EXPECT_EQ(counters.get("bytes_sent"), bytes);
}

TEST_F(TilesNodeTest, LateReaderReceivesTheTilesAlreadyPublished) {
  dds::Node service_node(node_config("tiles", 1)), vehicle(node_config("test", 1));
  dds::Counters counters;
  TilesNode node(service_node, counters, tiles_config());
  const TileGrid grid(city_->index);
  TileLog early;
  vehicle.subscribe<msg::MapTile>(dds::topics::kMapTile, [&](const msg::MapTile& m) { early.on_tile(grid, m); });
  auto gnss = vehicle.writer<msg::GnssFix>(dds::topics::kGnss);
  ASSERT_TRUE(wait_for([&] { return gnss.matched_readers() >= 1; }, 5s));
  // Two GNSS fixes 100 m apart (no odometry): two windows' worth of tiles.
  const twin::EnuFrame enu(city_->index.origin);
  for (const Eigen::Vector3d& p_W : {Eigen::Vector3d(0, -60, 20), Eigen::Vector3d(100, -60, 20)}) {
    const Eigen::Vector3d lla = enu.to_lla(p_W);
    msg::GnssFix f;
    f.vehicle_id("uav0");
    f.latitude_deg(lla.x());
    f.longitude_deg(lla.y());
    f.altitude_m(lla.z());
    ASSERT_TRUE(gnss.publish(f));
  }
  ASSERT_TRUE(wait_for([&] { return counters.get("gnss_in") == 2; }, 5s));  // counted after its tiles went out
  const unsigned long long sent = counters.get("tiles_sent");
  ASSERT_GE(sent, 9u);
  ASSERT_TRUE(wait_for([&] { return early.size() == sent; }, 5s));

  // A reader that joins now (another participant, as a restarted registration service would be).
  dds::Node late_node(node_config("late", 1));
  TileLog late;
  late_node.subscribe<msg::MapTile>(dds::topics::kMapTile, [&](const msg::MapTile& m) { late.on_tile(grid, m); });
  EXPECT_TRUE(wait_for([&] { return late.size() == sent; }, 10s)) << late.size() << " of " << sent;
  std::this_thread::sleep_for(200ms);
  late_node.close_readers();
  service_node.close_readers();
  vehicle.close_readers();
  EXPECT_EQ(counters.get("tiles_sent"), sent);  // nothing re-published for the late reader
  std::lock_guard lock_a(early.mutex), lock_b(late.mutex);
  ASSERT_EQ(late.tiles.size(), early.tiles.size());
  for (const auto& [key, m] : early.tiles) {
    ASSERT_EQ(late.tiles.count(key), 1u);
    EXPECT_EQ(late.received.at(key).count, 1);
    EXPECT_EQ(late.tiles.at(key).points_draco(), m.points_draco());
  }
}

TEST_F(TilesNodeTest, RequestResendsOnlyWhatTheRequesterLacks) {
  dds::Node service_node(node_config("tiles", 0)), vehicle(node_config("test", 0));
  dds::Counters counters;
  TilesNode node(service_node, counters, tiles_config());
  const TileGrid grid(city_->index);
  TileLog log;
  vehicle.subscribe<msg::MapTile>(dds::topics::kMapTile, [&](const msg::MapTile& m) { log.on_tile(grid, m); });
  auto gnss = vehicle.writer<msg::GnssFix>(dds::topics::kGnss);
  auto request = vehicle.writer<msg::TileRequest>(dds::topics::kTileRequest);
  ASSERT_TRUE(wait_for([&] { return gnss.matched_readers() >= 1 && request.matched_readers() >= 1; }, 5s));
  const Eigen::Vector3d p_W(0, -60, 20);
  const Eigen::Vector3d lla = twin::EnuFrame(city_->index.origin).to_lla(p_W);
  msg::GnssFix f;
  f.vehicle_id("uav0");
  f.latitude_deg(lla.x());
  f.longitude_deg(lla.y());
  f.altitude_m(lla.z());
  ASSERT_TRUE(gnss.publish(f));
  ASSERT_TRUE(wait_for([&] { return counters.get("gnss_in") == 1; }, 5s));
  const unsigned long long sent = counters.get("tiles_sent");
  ASSERT_GE(sent, 4u);
  ASSERT_TRUE(wait_for([&] { return log.arrivals.load() == sent; }, 5s));

  // The vehicle says it holds every tile of the same window but the nearest one (e.g. it evicted it).
  const std::vector<twin::TileKey> window = grid.tiles_in({p_W.head<2>(), 75.0});
  const twin::TileKey lost{0, -2};  // the tile under (0, -60)
  ASSERT_NE(std::find(window.begin(), window.end(), lost), window.end());
  msg::TileRequest r;
  r.vehicle_id("uav0");
  r.center_e_m(p_W.x());
  r.center_n_m(p_W.y());
  r.half_size_m(75.0);
  for (const auto& key : window) {
    if (!(key == lost)) r.have().push_back(grid.wire_key(key));
  }
  ASSERT_TRUE(request.publish(r));
  r.half_size_m(-1.0);  // malformed: rejected, nothing sent
  ASSERT_TRUE(request.publish(r));
  ASSERT_TRUE(wait_for([&] { return counters.get("tile_requests_in") == 2 && log.arrivals.load() == sent + 1; }, 5s));
  std::this_thread::sleep_for(200ms);
  service_node.close_readers();
  vehicle.close_readers();
  EXPECT_EQ(counters.get("tiles_sent"), sent + 1);
  EXPECT_EQ(counters.get("tile_requests_rejected"), 1u);
  std::lock_guard lock(log.mutex);
  EXPECT_EQ(log.received.at(lost).count, 2);
}

}  // namespace
}  // namespace twinslam::tiles

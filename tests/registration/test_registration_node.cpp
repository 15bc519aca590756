// The registration service over DDS in one process (private domain): a RegistrationNode fed MapTiles of a synthetic
// city (Draco points, as the tiles service sends them) and a LocalMap whose landmarks were seen through a wrong T_WL
// answers with an accepted Registration whose correction undoes the error; a cloud far from every tile is rejected
// with REG_REJECTED_NO_MAP and a reason; a correction the Mahalanobis gate refused over a landmark horizon goes out
// accepted with `readmitted` set. Also WindowedTwin: only tiles inside a vehicle's window are indexed, and
// the index then answers like one built from scratch on those tiles.
#include <gtest/gtest.h>

#include <atomic>
#include <mutex>

#include "local_map_message.hpp"
#include "registration_node.hpp"
#include "subprocess.hpp"
#include "synthetic_twin.hpp"
#include "twinslam/dds/convert.hpp"
#include "twinslam/twin/store.hpp"
#include "wait_for.hpp"

namespace twinslam::registration {
namespace {

using namespace std::chrono_literals;

std::vector<std::uint8_t> encode(const test::PointSet& t) {
  twin::Mesh m;
  m.p_W = t.p_W;
  m.n_W = t.n_W;
  return twin::encode_points(m, twin::StoreConfig{});
}

Eigen::AlignedBox3d bounds(const test::PointSet& t) {
  Eigen::AlignedBox3d b;
  for (const auto& p : t.p_W) b.extend(p);
  return b;
}

TEST(WindowedTwin, IndexesOnlyTheTilesNearAVehicleAndMatchesAFreshIndex) {
  const auto tiles = test::split_tiles(test::sample_grid(test::city_surfaces(), 1.0));
  WindowedTwin twin(50.0, 60.0, 4096, 0.0, 1, 0.0);  // +-30 m around the vehicle, no prefetch ring, no hysteresis
  for (const auto& [key, t] : tiles) twin.add_tile(key, bounds(t), encode(t));
  const Eigen::Vector3d at = test::kCentre + Eigen::Vector3d(-35, -35, 5);
  const auto stats = twin.update("uav0", at);
  EXPECT_GT(stats.added, 0u);
  EXPECT_LT(twin.index().tile_count(), tiles.size());
  // A fresh index on exactly the tiles whose content lies within 30 m (square) of the vehicle.
  TwinTileIndex fresh(50.0);
  for (const auto& [key, t] : tiles) {
    const Eigen::AlignedBox3d b = bounds(t);
    const double dx = std::max({b.min().x() - at.x(), 0.0, at.x() - b.max().x()});
    const double dy = std::max({b.min().y() - at.y(), 0.0, at.y() - b.max().y()});
    if (std::max(dx, dy) <= 30.0) fresh.add_tile(key, t.p_W, t.n_W);
  }
  EXPECT_EQ(twin.index().keys(), fresh.keys());
  for (const auto& q : test::sample_noisy(test::city_surfaces(), 200, 0.3, 5)) {
    const auto a = twin.index().nearest(q, 2.0), b = fresh.nearest(q, 2.0);
    ASSERT_EQ(a.has_value(), b.has_value());
    if (a) {
      EXPECT_NEAR(a->distance_m, b->distance_m, 1e-4);  // Draco's 20-bit positions: < 0.1 mm
    }
  }
  // The vehicle moves away: its old tiles leave the index, the new ones come in.
  const auto moved = twin.update("uav0", test::kCentre + Eigen::Vector3d(40, 40, 5));
  EXPECT_GT(moved.removed, 0u);
  EXPECT_GT(moved.added, 0u);
  EXPECT_FALSE(twin.covers(at, 5.0));
  EXPECT_EQ(twin.stored_tiles(), tiles.size());  // compressed tiles are kept for a return
}

// Square-metric horizontal distance of a tile's content from p [m].
double square_distance(const test::PointSet& t, const Eigen::Vector3d& p) {
  const Eigen::AlignedBox3d b = bounds(t);
  return std::max(std::max({b.min().x() - p.x(), 0.0, p.x() - b.max().x()}),
                  std::max({b.min().y() - p.y(), 0.0, p.y() - b.max().y()}));
}

TEST(WindowedTwin, PrefetchesTheRingAroundTheWindowAFewTilesPerUpdateNearestFirst) {
  const auto tiles = test::split_tiles(test::sample_grid(test::city_surfaces(), 1.0));
  WindowedTwin twin(50.0, 20.0, 4096, 40.0, 1, 0.0);  // window +-10 m, ring out to 50 m, one per update
  for (const auto& [key, t] : tiles) twin.add_tile(key, bounds(t), encode(t));
  const Eigen::Vector3d at = test::kCentre + Eigen::Vector3d(-35, -35, 5);
  std::size_t in_window = 0, in_ring = 0;
  for (const auto& [key, t] : tiles) {
    const double d = square_distance(t, at);
    in_window += d <= 10.0;
    in_ring += d > 10.0 && d <= 50.0;
  }
  ASSERT_GT(in_ring, 1u);  // the test needs a ring of several tiles
  // Every tile of the window at once, and one ring tile per update after that.
  const auto first = twin.update("uav0", at);
  EXPECT_EQ(first.added, in_window + 1);
  EXPECT_EQ(first.prefetched, 1u);
  for (std::size_t k = 1; k < in_ring; ++k) {
    const auto next = twin.update("uav0", at);
    EXPECT_EQ(next.added, 1u);
    EXPECT_EQ(next.prefetched, 1u);
  }
  EXPECT_EQ(twin.update("uav0", at).added, 0u);
  EXPECT_EQ(twin.index().tile_count(), in_window + in_ring);
  // Leaving: tiles farther than window + ring are dropped; the index still equals a fresh one on its tiles.
  const Eigen::Vector3d far = test::kCentre + Eigen::Vector3d(60, 60, 5);
  twin.update("uav0", far);
  TwinTileIndex fresh(50.0);
  for (const auto& key : twin.index().keys()) {
    EXPECT_LE(square_distance(tiles.at(key), far), 50.0);
    fresh.add_tile(key, tiles.at(key).p_W, tiles.at(key).n_W);
  }
  for (const auto& q : test::sample_noisy(test::city_surfaces(), 200, 0.3, 5)) {
    const auto a = twin.index().nearest(q, 2.0), b = fresh.nearest(q, 2.0);
    ASSERT_EQ(a.has_value(), b.has_value());
    if (a) {
      EXPECT_NEAR(a->distance_m, b->distance_m, 1e-4);
    }
  }
}

// The LocalMap the estimator would send for this source cloud (quality 1, no covariance).
// Sets the keyframe covariance the estimator sends: sigma_deg on rotation, sigma_m on translation (rotation first).
void set_covariance(msg::LocalMap& lm, double sigma_deg, double sigma_m, double off_diagonal = 0.0) {
  lm.T_WB_covariance().clear();
  for (int r = 0; r < 6; ++r)
    for (int k = 0; k < 6; ++k) {
      const double s = r < 3 ? sigma_deg * M_PI / 180.0 : sigma_m;
      lm.T_WB_covariance().push_back(r == k ? s * s : off_diagonal);
    }
}

class RegistrationNodeTest : public ::testing::Test {
 protected:
  static dds::NodeConfig config(const std::string& service) {
    dds::NodeConfig c;
    c.service = service;
    c.domain = twinslam::test::test_domain();  // claimed with a lock: parallel tests never share it
    return c;
  }

  // A registration service and a peer that sends it the synthetic city's tiles and collects its answers.
  // The answers outlive the peer whose callback fills them (members are destroyed in reverse order).
  std::mutex m;
  std::vector<msg::Registration> got;
  dds::Node service{config("registration")};
  dds::Counters counters;
  RegistrationNode node{service, counters, RegistrationNodeOptions{}};
  dds::Node peer{config("test")};
  dds::Writer<msg::MapTile> tiles_out = peer.writer<msg::MapTile>(dds::topics::kMapTile);
  dds::Writer<msg::LocalMap> maps_out = peer.writer<msg::LocalMap>(dds::topics::kLocalMap);

  void SetUp() override {
    peer.subscribe<msg::Registration>(dds::topics::kRegistration, [&](const msg::Registration& r) {
      std::lock_guard lock(m);
      got.push_back(r);
    });
    ASSERT_TRUE(testing::wait_for([&] { return tiles_out.matched_readers() > 0 && maps_out.matched_readers() > 0; }, 5s));
    for (const auto& [key, t] : test::split_tiles(test::sample_grid(test::city_surfaces(), 0.5))) {
      msg::MapTile tile;
      tile.tile_key("synthetic/" + key.str());
      tile.twin_id("synthetic");
      const Eigen::AlignedBox3d b = bounds(t);
      for (int k = 0; k < 3; ++k) tile.bounds_W()[k] = b.min()[k], tile.bounds_W()[3 + k] = b.max()[k];
      tile.points(static_cast<unsigned>(t.p_W.size()));
      const auto bytes = encode(t);
      tile.points_draco(std::vector<std::uint8_t>(bytes.begin(), bytes.end()));
      tiles_out.publish(tile);
    }
    ASSERT_TRUE(testing::wait_for([&] { return counters.get("tiles_in") >= 9; }, 10s));
  }

  std::size_t answers() {
    std::lock_guard lock(m);
    return got.size();
  }
};

TEST_F(RegistrationNodeTest, AnswersALocalMapWithTheCorrectionThatUndoesItsAlignmentError) {

  // 1 m / 3 deg off, about the keyframe body.
  const Eigen::Vector3d body = test::kCentre + Eigen::Vector3d(0, -45, 8);
  const Eigen::Isometry3d error = test::offset_about(body, Eigen::Vector3d(0.2, 0.1, 1), 3.0, {0.6, -0.7, 0.4});
  const SourceInput src = test::make_source(test::sample_noisy(test::city_surfaces(), 600, 0.1, 3), error, body);
  const msg::LocalMap lm = test::local_map("uav7", 123, src);
  maps_out.publish(lm);
  // And one far from every tile.
  msg::LocalMap far = lm;
  far.keyframe_stamp_ns(456);
  far.vehicle_id("uav8");
  Eigen::Isometry3d away = Eigen::Isometry3d::Identity();
  away.translation() << 5000, 0, 0;
  far.T_WL(dds::to_msg(away));
  maps_out.publish(far);
  // The same cloud with the estimator's covariance (rotation first): 0.2 deg / 5 cm cannot explain a 1 m / 3 deg
  // correction; 2.5 deg / 2 m can; at 5 deg the estimator is still acquiring its heading, so that correction waits
  // for agreeing keyframes (persistence_gate.hpp); a matrix that is no covariance is ignored (counted), not fatal.
  const auto with_covariance = [&](const char* vehicle, double sigma_deg, double sigma_m, double off_diagonal) {
    msg::LocalMap c = lm;
    c.vehicle_id(vehicle);
    set_covariance(c, sigma_deg, sigma_m, off_diagonal);
    maps_out.publish(c);
  };
  with_covariance("uav9", 0.2, 0.05, 0.0);
  with_covariance("uav10", 2.5, 2.0, 0.0);
  with_covariance("uav11", 1.0, 1.0, 5.0);  // not positive definite
  with_covariance("uav12", 5.0, 2.0, 0.0);
  ASSERT_TRUE(testing::wait_for([&] {
    std::lock_guard lock(m);
    return got.size() >= 6;
  }, 30s));
  std::lock_guard lock(m);
  const auto of = [&](const std::string& vehicle) -> const msg::Registration& {
    return *std::find_if(got.begin(), got.end(), [&](const auto& r) { return r.vehicle_id() == vehicle; });
  };
  EXPECT_EQ(of("uav9").status(), msg::REG_REJECTED_CORRECTION) << of("uav9").reason();
  EXPECT_NE(of("uav9").reason().find("Mahalanobis"), std::string::npos) << of("uav9").reason();
  EXPECT_EQ(of("uav10").status(), msg::REG_ACCEPTED) << of("uav10").reason();
  EXPECT_EQ(of("uav11").status(), msg::REG_ACCEPTED) << of("uav11").reason();
  EXPECT_EQ(of("uav12").status(), msg::REG_REJECTED_CORRECTION) << of("uav12").reason();
  EXPECT_NE(of("uav12").reason().find("unconfirmed"), std::string::npos) << of("uav12").reason();
  EXPECT_EQ(counters.get("covariance_unusable"), 1u);
  const auto& ok = of("uav7");
  const auto& no = of("uav8");
  EXPECT_EQ(ok.status(), msg::REG_ACCEPTED) << ok.reason();
  EXPECT_EQ(ok.keyframe_stamp_ns(), 123);
  const Eigen::Isometry3d residual = dds::from_msg(ok.correction_W()) * error;  // identity when exact
  EXPECT_LT((residual * body - body).norm(), 0.05);
  EXPECT_LT(Eigen::AngleAxisd(residual.linear()).angle() * 180 / M_PI, 0.2);
  EXPECT_GT(ok.inliers(), 300u);
  EXPECT_EQ(no.status(), msg::REG_REJECTED_NO_MAP);
  EXPECT_FALSE(no.reason().empty());
  EXPECT_EQ(counters.get("registrations_out"), 6u);
}

// An estimator sure of a wrong pose (0.2 deg / 5 cm against a 1 m / 3 deg error) sends keyframes 2.5 s apart: the
// Mahalanobis gate refuses the correction until keyframes 10 s apart have found it five times; then the service
// accepts it with Registration.readmitted set (the estimator re-opens its alignment on it), and only that one.
TEST_F(RegistrationNodeTest, ACorrectionRefusedForALandmarkHorizonIsSentAsReadmitted) {
  const Eigen::Vector3d body = test::kCentre + Eigen::Vector3d(0, -45, 8);
  const Eigen::Isometry3d error = test::offset_about(body, Eigen::Vector3d(0.2, 0.1, 1), 3.0, {0.6, -0.7, 0.4});
  const SourceInput src = test::make_source(test::sample_noisy(test::city_surfaces(), 600, 0.1, 3), error, body);
  constexpr std::int64_t kStep_ns = 2'500'000'000;
  for (std::int64_t k = 0; k < 5; ++k) {
    msg::LocalMap lm = test::local_map("uav3", k * kStep_ns, src);
    set_covariance(lm, 0.2, 0.05);
    maps_out.publish(lm);
    // One at a time: the service keeps only the newest LocalMap of a vehicle while it is busy.
    ASSERT_TRUE(testing::wait_for([&] { return answers() == static_cast<std::size_t>(k + 1); }, 30s)) << k;
  }
  std::lock_guard lock(m);
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(got[k].status(), msg::REG_REJECTED_CORRECTION) << k << ": " << got[k].reason();
    EXPECT_FALSE(got[k].readmitted()) << k;
  }
  EXPECT_EQ(got[4].status(), msg::REG_ACCEPTED) << got[4].reason();
  EXPECT_TRUE(got[4].readmitted());
  EXPECT_NE(got[4].reason().find("5 of 5 refused keyframes over 10.0 s"), std::string::npos) << got[4].reason();
  EXPECT_EQ(counters.get("readmitted_persistent"), 1u);
}

TEST(RegistrationNodeParts, TileKeysAndStatusesMap) {
  EXPECT_EQ(parse_tile_key("delft/3_-2")->iy, -2);
  EXPECT_EQ(parse_tile_key("12_7")->ix, 12);
  EXPECT_FALSE(parse_tile_key("twin/3x2").has_value());
  EXPECT_FALSE(parse_tile_key("twin/3_2junk").has_value());
  EXPECT_EQ(to_msg(RegistrationStatus::kCorrectionTooLarge), msg::REG_REJECTED_CORRECTION);
  EXPECT_EQ(to_msg(RegistrationStatus::kAccepted), msg::REG_ACCEPTED);
}

}  // namespace
}  // namespace twinslam::registration

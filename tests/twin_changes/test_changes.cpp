// Twin-change detection on a synthetic street: a ground plane and boxes as the twin, landmarks on the world's
// surfaces seen from a flight down the street. A box the twin lacks, a box only the twin has, and a right twin.
#include <random>

#include <gtest/gtest.h>

#include "twinslam/core/error.hpp"
#include "twinslam/twin/changes.hpp"

namespace twinslam::twin {
namespace {

// A closed box [lo, hi] (walls and roof, outward normals) appended to m.
void add_box(Mesh* m, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  const int base = static_cast<int>(m->p_W.size());
  for (int k = 0; k < 8; ++k) m->p_W.emplace_back(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z());
  const int quads[5][4] = {{0, 1, 5, 4}, {1, 3, 7, 5}, {3, 2, 6, 7}, {2, 0, 4, 6}, {4, 5, 7, 6}};
  for (const auto& q : quads) {
    m->triangles.emplace_back(base + q[0], base + q[1], base + q[2]);
    m->triangles.emplace_back(base + q[0], base + q[2], base + q[3]);
  }
}

Mesh ground() {
  Mesh m;
  m.p_W = {{-200, -200, 0}, {200, -200, 0}, {200, 200, 0}, {-200, 200, 0}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

// Buildings north of the street y = 0 (their south facade at y = 10), 20 m wide, 15 m tall, every 30 m.
Eigen::Vector3d box_lo(int i) { return {-60.0 + 30.0 * i, 10.0, 0.0}; }
Eigen::Vector3d box_hi(int i) { return {-40.0 + 30.0 * i, 30.0, 15.0}; }

// Landmarks on the south facades of boxes `seen` (as the world has them), seen from the flight along y = 0 at
// 8 m, with triangulation noise; t_s: when the flight (2 m/s from x = -80) passed it.
std::vector<LandmarkSighting> sightings(const std::vector<int>& seen, double noise_m = 0.1) {
  std::mt19937 rng(7);
  std::normal_distribution<double> n(0.0, noise_m);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<LandmarkSighting> out;
  for (const int i : seen) {
    for (int k = 0; k < 60; ++k) {
      LandmarkSighting s;
      s.p_W = {box_lo(i).x() + 20 * u(rng) + n(rng), 10.0 + n(rng), 1 + 13 * u(rng) + n(rng)};
      s.observer_W = {s.p_W.x() - 15.0, 0.0, 8.0};
      s.t_s = (s.observer_W.x() + 80.0) / 2.0;
      out.push_back(s);
    }
  }
  return out;
}

// A world of boxes 0..3 with landmarks on all four.
Mesh twin_of(const std::vector<int>& boxes) {
  Mesh m = ground();
  for (const int i : boxes) add_box(&m, box_lo(i), box_hi(i));
  return m;
}

TEST(TwinChanges, NothingIsReportedWhereTheTwinIsRight) {
  const TwinChanges found = find_twin_changes(twin_of({0, 1, 2, 3}), sightings({0, 1, 2, 3}));
  EXPECT_EQ(found.landmarks_used, 240u);
  EXPECT_TRUE(found.places.empty());
  EXPECT_EQ(found.unexplained, 0u);
  EXPECT_EQ(found.sight_lines, 0u);
}

TEST(TwinChanges, ABuildingTheTwinLacksIsReportedMissingAtItsFacade) {
  const TwinChanges found = find_twin_changes(twin_of({0, 1, 3}), sightings({0, 1, 2, 3}));
  ASSERT_EQ(found.places.size(), 1u);
  const TwinChange& c = found.places[0];
  EXPECT_EQ(c.kind, "missing");
  EXPECT_GE(c.landmarks, 50u);  // all but those within min_distance_m of the ground
  for (const auto& p : c.footprint_W) {  // on box 2's south facade
    EXPECT_GE(p.x(), box_lo(2).x() - 0.5);
    EXPECT_LE(p.x(), box_hi(2).x() + 0.5);
    EXPECT_NEAR(p.y(), 10.0, 0.5);
  }
  EXPECT_GT(c.mean_distance_m, 1.5);
  EXPECT_LT(c.first_s, c.last_s);
}

TEST(TwinChanges, ABuildingOnlyTheTwinHasIsReportedAddedWhereTheSightLinesCrossIt) {
  // A box the world lacks, between the street and box 1: the landmarks on box 1 were seen through it.
  Mesh twin = twin_of({0, 1, 2, 3});
  add_box(&twin, {-28, 3, 0}, {-12, 7, 12});
  const TwinChanges found = find_twin_changes(twin, sightings({0, 1, 2, 3}));
  ASSERT_EQ(found.places.size(), 1u) << found.sight_lines << " sight lines, " << found.unexplained << " unexplained";
  const TwinChange& c = found.places[0];
  EXPECT_EQ(c.kind, "added");
  EXPECT_GE(c.sight_lines, 20u);
  for (const auto& p : c.footprint_W) {
    EXPECT_GE(p.x(), -28.5);
    EXPECT_LE(p.x(), -11.5);
    EXPECT_GE(p.y(), 2.5);
    EXPECT_LE(p.y(), 7.5);
  }
  EXPECT_GT(c.mean_depth_m, 1.5);
}

TEST(TwinChanges, TooLittleOrTooBriefEvidenceIsNotAChange) {
  std::vector<LandmarkSighting> few = sightings({2});
  few.resize(5);  // five odd landmarks are not a building
  EXPECT_TRUE(find_twin_changes(twin_of({0, 1, 3}), few).places.empty());
  std::vector<LandmarkSighting> brief = sightings({2});
  for (auto& s : brief) s.t_s = 10.0;  // all at one instant: one keyframe's bad triangulation
  EXPECT_TRUE(find_twin_changes(twin_of({0, 1, 3}), brief).places.empty());
  std::vector<LandmarkSighting> poor = sightings({2});
  for (auto& s : poor) s.quality = 0.2;  // all poorly triangulated: not used
  const TwinChanges none = find_twin_changes(twin_of({0, 1, 3}), poor);
  EXPECT_EQ(none.landmarks_used, 0u);
  EXPECT_TRUE(none.places.empty());
}

TEST(TwinChanges, NonFiniteLandmarksAreSkippedAndBadInputRefused) {
  std::vector<LandmarkSighting> s = sightings({0});
  s[0].p_W.x() = std::nan("");
  s[1].observer_W.z() = std::numeric_limits<double>::infinity();
  EXPECT_EQ(find_twin_changes(twin_of({0}), s).landmarks_used, 58u);
  EXPECT_THROW(find_twin_changes(Mesh{}, s), InputError);
  TwinChangeConfig bad;
  bad.min_distance_m = -1;
  EXPECT_THROW(find_twin_changes(twin_of({0}), s, bad), UsageError);
  bad = {};
  bad.min_quality = 2;
  EXPECT_THROW(bad.validate(), UsageError);
}

}  // namespace
}  // namespace twinslam::twin

// Acceptance of the tiles service on the city-loops flight over the procedural city's twin store: a vehicle has every
// tile within 75 m of it before it gets closer than 50 m to that tile, and nothing is sent twice — through the pure
// streamer over the whole 5 min flight at 20 Hz.
#include <gtest/gtest.h>

#include <unistd.h>

#include "city_twin_fixture.hpp"
#include "streaming_check.hpp"
#include "twinslam/tiles/tile_streamer.hpp"

namespace twinslam::tiles {
namespace {

namespace fs = std::filesystem;

TEST(TilesStreaming, CityLoopsEveryNearTileBeforeItIsWithin50mNothingTwice) {
  const fs::path dir = fs::temp_directory_path() / ("twinslam_tiles_stream_" + std::to_string(::getpid()));
  const test::CityTwin city = test::make_city_twin("city-loops", 0, dir / "twin");
  ASSERT_GT(city.index.tiles.size(), 50u);  // a 600 m city in 50 m tiles
  TileStreamer streamer(twin::read_twin_index(city.twin_dir), 150.0);

  std::vector<Eigen::Vector3d> positions;
  std::map<twin::TileKey, test::Receipt> received;
  const double rate_hz = 20.0;
  for (int k = 0; k * (1.0 / rate_hz) <= city.trajectory.duration(); ++k) {
    positions.push_back(city.trajectory.at(k / rate_hz).p_W);
    for (const twin::TileKey& key : streamer.update("uav0", positions.back()).publish) {
      test::Receipt& r = received[key];
      if (r.count++ == 0) r.update = k;
    }
  }
  const int near = test::expect_streamed_in_time(streamer.grid(), positions, received);
  // The loops circle the central tower: a few dozen tiles, far from the whole city.
  EXPECT_GE(near, 9);
  EXPECT_LT(received.size(), city.index.tiles.size());
  EXPECT_EQ(streamer.published_count(), received.size());
  fs::remove_all(dir);
}

}  // namespace
}  // namespace twinslam::tiles

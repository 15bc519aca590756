// The tiles service's message handlers (tiles_handler.hpp) fed arbitrary samples, as any peer on the link may send
// them: Odometry with any position and status, GnssFix with any latitude, longitude and height, TileRequests with any
// window and any `have` keys, for a few vehicles, in any order. The handler serves a small store built once per
// process (a 200 m street of blocks, 50 m tiles) with room for only 6 tiles on the wire, so the over-limit path runs
// too. It must never throw (a Fast DDS listener thread would die), publish only tiles of its store with finite bounds,
// never put more tiles on the wire than its limit, and never send one vehicle a tile it already holds.
// Input: choice bytes (0: well formed) read by SampleReader; an all-zero input is a vehicle flying along the street.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include <spdlog/spdlog.h>

#include "harness.hpp"
#include "sample_reader.hpp"
#include "tiles_handler.hpp"
#include "twinslam/dds/convert.hpp"
#include "twinslam/twin/store.hpp"

namespace {

namespace msg = twinslam::msg;
namespace twin = twinslam::twin;
namespace tiles = twinslam::tiles;
using twinslam::fuzz::SampleReader;

constexpr double kLat = 47.3769, kLon = 8.5417, kAlt = 408.0;  // the twin's origin
constexpr int kMaxOnWire = 6;
constexpr int kMaxMessages = 32;

// Blocks of 20 x 20 x 15 m every 40 m along a 200 m street, plus the street: 4 x 2 tiles with content.
twin::Mesh street() {
  twin::Mesh m;
  auto quad = [&m](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                   const Eigen::Vector3d& d) {
    const int i = static_cast<int>(m.p_W.size());
    m.p_W.insert(m.p_W.end(), {a, b, c, d});
    m.triangles.emplace_back(i, i + 1, i + 2);
    m.triangles.emplace_back(i, i + 2, i + 3);
  };
  quad({-100, -10, 0}, {100, -10, 0}, {100, 10, 0}, {-100, 10, 0});
  for (double x = -90; x < 100; x += 40) {
    for (const double y : {-40.0, 20.0}) {
      quad({x, y, 0}, {x + 20, y, 0}, {x + 20, y, 15}, {x, y, 15});
      quad({x, y + 20, 0}, {x + 20, y + 20, 0}, {x + 20, y + 20, 15}, {x, y + 20, 15});
    }
  }
  return m;
}

const tiles::TilesConfig& config() {
  static const tiles::TilesConfig c = [] {
    tiles::TilesConfig out;
    out.twin_dir = (twinslam::fuzz::scratch_dir() / "tiles_store").string();
    twin::StoreConfig store;
    store.point_spacing_m = 4.0;
    twin::build_twin_store(street(), {kLat, kLon, kAlt}, store, out.twin_dir);
    out.window_m = 100.0;
    out.cache_tiles = 3;
    out.max_tiles_on_wire = kMaxOnWire;
    return out;
  }();
  return c;
}

std::string vehicle(SampleReader& in) {
  switch (in.u8() % 8) {
    case 0: case 1: case 2: case 3: return "uav1";
    case 4: case 5: return "uav2";
    case 6: return "";
    default: return in.text("uav3");
  }
}

msg::Odometry odometry(SampleReader& in, const std::string& id, int k) {
  msg::Odometry m;
  m.vehicle_id(id);
  m.stamp_ns(in.i64());
  // Aligned unless the input says otherwise; 4 is outside the enum, as a newer peer might send.
  m.status(static_cast<msg::OdometryStatus>((in.u8() + msg::ODOM_ALIGNED) % 5));
  m.T_WB().p(twinslam::dds::to_msg(Eigen::Vector3d(in.value(-100.0 + 8.0 * k), in.value(0.0), in.value(5.0))));
  return m;
}

msg::GnssFix gnss(SampleReader& in, const std::string& id, int k) {
  msg::GnssFix m;
  m.vehicle_id(id);
  m.stamp_ns(in.i64());
  m.latitude_deg(in.value(kLat + 1e-5 * (k % 7)));
  m.longitude_deg(in.value(kLon - 1e-3 + 1e-4 * k));
  m.altitude_m(in.value(kAlt + 10.0));
  return m;
}

msg::TileRequest request(SampleReader& in, const std::string& id, const tiles::TileGrid& grid) {
  msg::TileRequest m;
  m.vehicle_id(id);
  m.stamp_ns(in.i64());
  m.center_e_m(in.value(0.0));
  m.center_n_m(in.value(0.0));
  m.half_size_m(in.value(60.0));
  for (int n = in.u8() % 6; n > 0; --n) {
    const auto& records = grid.records();
    const std::string nominal = grid.wire_key(records[in.u8() % records.size()].key);
    m.have().push_back(in.text(nominal));
  }
  return m;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool quiet = [] {
    spdlog::set_level(spdlog::level::off);  // refused samples are logged: expected here, not news
    return true;
  }();
  (void)quiet;
  SampleReader in(data, size);
  twinslam::dds::Counters counters;
  std::set<std::string> on_wire;
  bool fail_next = false;
  const tiles::TileGrid* grid = nullptr;
  tiles::TilesHandler handler(counters, config(), "", [&](const msg::MapTile& t) {
    if (!grid->parse_wire_key(t.tile_key())) __builtin_trap();  // a tile the store does not have
    for (const double b : t.bounds_W()) {
      if (!std::isfinite(b)) __builtin_trap();
    }
    if (fail_next) return false;  // a full writer history: the tile must be tried again, not counted as held
    on_wire.insert(t.tile_key());
    return true;
  });
  grid = &handler.streamer().grid();
  for (int k = 0; k < kMaxMessages && !in.done(); ++k) {
    fail_next = in.u8() % 8 == 7;
    const std::string id = vehicle(in);
    switch (in.u8() % 3) {
      case 0: handler.on_odometry(odometry(in, id, k)); break;
      case 1: handler.on_gnss(gnss(in, id, k)); break;
      default: handler.on_request(request(in, id, *grid)); break;
    }
    if (handler.streamer().published_count() > static_cast<std::size_t>(kMaxOnWire) ||
        on_wire.size() > static_cast<std::size_t>(kMaxOnWire)) {
      __builtin_trap();  // more tiles latched than the writer can hold: its writes would block
    }
  }
  // The well-formed flight (all-zero input) must get tiles: else the target would only exercise refusals.
  if (size > 0 && std::all_of(data, data + size, [](std::uint8_t b) { return b == 0; }) && on_wire.empty()) {
    __builtin_trap();
  }
  return 0;
}

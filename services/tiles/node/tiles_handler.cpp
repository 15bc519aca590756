#include "tiles_handler.hpp"

#include <spdlog/spdlog.h>

#include "twinslam/core/error.hpp"
#include "twinslam/dds/convert.hpp"

namespace twinslam::tiles {

TilesHandler::TilesHandler(dds::Counters& counters, const TilesConfig& config, std::string vehicle_id,
                           Publish publish)
    : counters_(counters),
      vehicle_id_(std::move(vehicle_id)),
      publish_(std::move(publish)),
      streamer_(twin::read_twin_index(config.twin_dir), config.window_m,
                static_cast<std::size_t>(config.max_tiles_on_wire)),
      cache_(static_cast<std::size_t>(config.cache_tiles), TileCache::store_loader(config.twin_dir)),
      enu_(streamer_.grid().origin()) {}

void TilesHandler::on_odometry(const msg::Odometry& m) {
  if (!serves(m.vehicle_id())) return;
  std::lock_guard lock(mutex_);
  const Eigen::Vector3d p_WB = dds::from_msg(m.T_WB().p());
  if (!p_WB.allFinite()) {
    counters_.add("odometry_rejected");  // a diverged estimate must not move (or stop) the window
  } else if (const auto p_W = positions_.on_odometry(m.vehicle_id(), m.status() == msg::ODOM_ALIGNED, p_WB)) {
    send(streamer_.update(m.vehicle_id(), *p_W));
  }
  counters_.add("odometry_in");  // after its tiles went out: a test can wait for a message's effect
}

void TilesHandler::on_gnss(const msg::GnssFix& m) {
  if (!serves(m.vehicle_id())) return;
  std::lock_guard lock(mutex_);
  struct Count {  // on every path out, after the fix's tiles went out
    dds::Counters& c;
    ~Count() { c.add("gnss_in"); }
  } count{counters_};
  if (positions_.aligned(m.vehicle_id())) return;  // aligned odometry drives the window: skip the conversion
  Eigen::Vector3d p_W = Eigen::Vector3d::Constant(NAN);
  try {
    p_W = enu_.from_lla(m.latitude_deg(), m.longitude_deg(), m.altitude_m());
  } catch (const std::exception& e) {  // GeographicLib rejects |lat| > 90
    spdlog::warn("gnss fix of '{}' at {}: {}", m.vehicle_id(), m.stamp_ns(), e.what());
  }
  if (!p_W.allFinite()) {  // NaN or infinite coordinates convert to NaN without an exception
    counters_.add("gnss_rejected");
    return;
  }
  if (const auto p = positions_.on_gnss(m.vehicle_id(), p_W)) send(streamer_.update(m.vehicle_id(), *p));
}

void TilesHandler::on_request(const msg::TileRequest& m) {
  if (!serves(m.vehicle_id())) return;
  std::lock_guard lock(mutex_);
  std::vector<twin::TileKey> have;
  for (const auto& text : m.have()) {
    if (const auto key = streamer_.grid().parse_wire_key(text)) have.push_back(*key);
  }
  try {
    send(streamer_.request(m.vehicle_id(), {m.center_e_m(), m.center_n_m()}, m.half_size_m(), have));
  } catch (const InputError& e) {
    counters_.add("tile_requests_rejected");
    spdlog::warn("{}", e.what());
  }
  counters_.add("tile_requests_in");  // after its tiles went out, like odometry_in
}

void TilesHandler::send(const StreamDecision& d) {
  counters_.add("tiles_latched", d.new_for_vehicle.size() - std::min(d.new_for_vehicle.size(), d.publish.size()));
  if (!d.over_limit.empty()) {
    if (counters_.get("tiles_over_limit") == 0) {
      spdlog::warn("{} tiles are latched on the wire (max_tiles_on_wire): new tiles are no longer sent",
                   streamer_.published_count());
    }
    counters_.add("tiles_over_limit", d.over_limit.size());
  }
  for (const twin::TileKey& key : d.publish) {
    if (!publish_tile(key)) {
      counters_.add("tiles_failed");
      streamer_.publish_failed(key);  // the next update that needs it tries again
    }
  }
}

bool TilesHandler::publish_tile(const twin::TileKey& key) {
  const TileRecord* info = streamer_.grid().find(key);
  if (info == nullptr) return false;
  std::shared_ptr<const EncodedTile> bytes;
  try {
    bytes = cache_.get(*info);
  } catch (const InputError& e) {
    // Retried on every update that needs it (tiles_failed counts each try): the reason once per tile is enough.
    if (warned_failed_.insert(streamer_.grid().wire_key(key)).second) {
      spdlog::warn("tile {}: {} (retried while needed, counted as tiles_failed)", streamer_.grid().wire_key(key),
                   e.what());
    }
    return false;
  }
  msg::MapTile t;
  t.tile_key(streamer_.grid().wire_key(key));
  t.twin_id(streamer_.grid().twin_id());
  const Eigen::AlignedBox3d box_W = streamer_.grid().bounds_W(*info);
  const Eigen::Vector3d lo = box_W.min(), hi = box_W.max();
  t.bounds_W() = {lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z()};
  t.triangles(info->triangles);
  t.points(info->points);
  t.mesh_draco(bytes->mesh_draco);
  t.points_draco(bytes->points_draco);
  if (!publish_(t)) return false;
  counters_.add("tiles_sent");
  counters_.add("bytes_sent", bytes->bytes());
  return true;
}

}  // namespace twinslam::tiles

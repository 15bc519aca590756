#pragma once
// Which tiles to send to whom. For every position update of a vehicle the streamer returns the tiles whose grid square
// meets the square window (side window_m) around it that this vehicle does not hold yet — differential, like
// Autoware's partial map loading: a tile goes to a vehicle at most once.
//
// Tiles are shared on the wire: MapTile is keyed by tile and latched (deploy/qos/twinslam.xml tile.writer:
// TRANSIENT_LOCAL, KEEP_LAST 1 per instance, 4096 instances), so a tile published once is delivered to every current
// reader and kept for every later one. The streamer therefore also tracks which tiles are published: a second vehicle
// that needs a published tile gets it marked as held but nothing new goes on the wire. Only an explicit TileRequest
// re-publishes tiles the requester says it lacks (it may have dropped them; the re-write replaces the one sample of
// that instance, so the writer's history does not grow).
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include <Eigen/Core>

#include "twinslam/tiles/tile_grid.hpp"

namespace twinslam::tiles {

struct StreamDecision {
  std::vector<twin::TileKey> new_for_vehicle;  // tiles the vehicle now holds that it did not before, nearest first
  std::vector<twin::TileKey> publish;          // of those, the ones to write on the wire, nearest first
  std::vector<twin::TileKey> over_limit;       // needed but not sent: max_on_wire tiles are already latched
};

class TileStreamer {
 public:
  // window_m: side of the square window [m]; max_on_wire: tiles the writer can latch (TilesConfig, validated there).
  // The writer keeps every published tile (one sample per instance) up to tile.writer's max_instances (4096 in
  // deploy/qos/twinslam.xml); past that a write would block and fail, so the streamer stops publishing new tiles and
  // reports them as over_limit (not held: they are tried again on later updates).
  TileStreamer(const twin::TwinIndex& index, double window_m, std::size_t max_on_wire = 4096);

  // A new position p_W of `vehicle` [m, W] (height ignored: tiles hold all heights).
  StreamDecision update(const std::string& vehicle, const Eigen::Vector3d& p_W);

  // TileRequest: `vehicle` wants the window (centre, half side [m]) and holds exactly `have`. The vehicle's held set
  // becomes `have`; every stored tile in the window missing from `have` is returned and published, even if it was
  // published before. Throws InputError for a non-finite centre or a half side that is not finite and > 0.
  StreamDecision request(const std::string& vehicle, const Eigen::Vector2d& center_W, double half_size_m,
                         const std::vector<twin::TileKey>& have);

  // The publication of `key` from the last decision failed: nobody holds it, so the next update that needs it sends
  // it again. If it was the tile's first write it is not on the wire; a failed re-send leaves the latched sample.
  void publish_failed(const twin::TileKey& key);

  const TileGrid& grid() const { return grid_; }
  bool published(const twin::TileKey& key) const { return published_.count(key) != 0; }
  std::size_t published_count() const { return published_.size(); }
  std::size_t vehicles() const { return held_.size(); }
  bool holds(const std::string& vehicle, const twin::TileKey& key) const;
  // Per-vehicle and published sets plus the grid [bytes], approximate.
  std::size_t memory_bytes() const;

 private:
  using KeySet = std::unordered_set<twin::TileKey, TileKeyHash>;
  void sort_nearest(std::vector<twin::TileKey>* keys, const Eigen::Vector2d& p_W) const;
  // Marks `key` held by the vehicle and published if there is room; false (nothing marked) if it is over the limit.
  bool admit(KeySet& held, const twin::TileKey& key, bool* newly_published);
  // Admits every tile of `window` the vehicle does not hold into `d` (new_for_vehicle, publish, over_limit), nearest
  // first.
  void admit_window(KeySet& held, const Window& window, StreamDecision& d);

  TileGrid grid_;
  double half_size_m_;
  std::size_t max_on_wire_;
  std::unordered_map<std::string, KeySet> held_;  // vehicle id -> tiles it holds
  KeySet published_;                              // tiles written on the wire (latched for every reader)
  KeySet first_writes_;                           // of those, the ones first written by the last decision
};

}  // namespace twinslam::tiles

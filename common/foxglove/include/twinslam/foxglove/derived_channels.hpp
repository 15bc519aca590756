#pragma once
// Which Foxglove channels a pipeline message feeds, and their messages (well_known.hpp): per vehicle V
//   /V/estimate/pose        foxglove.PoseInFrame     every Odometry (T_WB)
//   /V/estimate/path        foxglove.PosesInFrame    the path so far, each time it grew by `path_spacing_m`
//   /V/gnss                 foxglove.LocationFix     every GnssFix (Foxglove's Map panel)
//   /V/landmarks            foxglove.PointCloud      every LocalMap, placed by the estimator (T_WL)
//   /V/landmarks/registered foxglove.PointCloud      the same landmarks after an accepted registration (eq. 3)
//   /V/registration         twinslam.RegistrationHealth  every Registration
//   /V/truth/path           foxglove.PosesInFrame    with set_truth(): the ground truth up to the newest estimate's
//                                                    stamp (replaying a simulation), spaced and thinned as the path
//   /V/gnss/path            foxglove.PosesInFrame    with set_origin(): the GNSS fixes placed in W (ENU at the origin)
// and for all vehicles /twin/tiles (foxglove.SceneUpdate, one entity per MapTile, latched by tile key: a viewer that
// comes late needs every tile) and /services (twinslam.ServiceState, every Heartbeat, latched per service instance). Thread-safe (DDS listeners call it concurrently); never throws: a tile whose mesh
// does not decode gives no message and is counted (tiles_undecodable).
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "twinslam/foxglove/well_known.hpp"

namespace twinslam::twin {
class EnuFrame;
}

namespace twinslam::foxglove {

struct StampedPoseW {
  std::int64_t stamp_ns = 0;  // the estimate's clock (the dataset's sensor time) [ns]
  PoseW T_WB;
};
// A TUM file of T_WB (a dataset's groundtruth.tum) for set_truth; InputError naming FILE:LINE when malformed.
std::vector<StampedPoseW> read_truth_tum(const std::string& file);

struct DerivedMessage {
  std::string topic;
  const Schema* schema = nullptr;
  std::string json;
  // Set: a late subscriber gets the last message of each key on this topic (any string, empty included).
  std::optional<std::string> latch_key;
};

struct DerivedChannelsConfig {
  double path_spacing_m = 1.0;     // a pose joins the path once this far from the last one [m]
  std::size_t max_path_poses = 4000;  // past it, every other pose of the path is dropped (the path keeps its extent)
  std::size_t kept_local_maps = 16;   // per vehicle, for the registered cloud (a registration answers a recent one)
};

class DerivedChannels {
 public:
  explicit DerivedChannels(DerivedChannelsConfig config = {});
  ~DerivedChannels();
  DerivedChannels(const DerivedChannels&) = delete;
  DerivedChannels& operator=(const DerivedChannels&) = delete;

  // A vehicle's ground truth T_WB (stamps increasing), drawn up to each estimate's stamp.
  void set_truth(const std::string& vehicle_id, std::vector<StampedPoseW> truth);
  // W's WGS84 origin "LAT,LON,H" ([deg], [deg], ellipsoidal [m]): GNSS fixes are then also drawn in W. Throws
  // UsageError naming a malformed origin.
  void set_origin(const std::string& lat_lon_h);

  // render = false (nobody watches): only the state is kept up to date (the path, the held LocalMaps) and only the
  // latched messages (tiles) are made; no JSON is built for anything else.
  std::vector<DerivedMessage> on(const msg::Odometry& m, bool render = true);
  std::vector<DerivedMessage> on(const msg::GnssFix& m, bool render = true);
  std::vector<DerivedMessage> on(const msg::LocalMap& m, bool render = true);
  std::vector<DerivedMessage> on(const msg::Registration& m, bool render = true);
  std::vector<DerivedMessage> on(const msg::MapTile& m, bool render = true);
  std::vector<DerivedMessage> on(const msg::Heartbeat& m, bool render = true);
  template <class T>
  std::vector<DerivedMessage> on(const T&, bool = true) {
    return {};  // no well-known form (sensor streams, control: their CDR channels carry them)
  }

  std::uint64_t tiles_undecodable() const;
  // "/V" for a vehicle id ("/unnamed" for an empty one).
  static std::string prefix(const std::string& vehicle_id);

 private:
  struct Vehicle {
    std::vector<PoseW> path, truth_path, gnss_path;
    std::vector<StampedPoseW> truth;  // set_truth's, drawn up to truth_next
    std::size_t truth_next = 0;
    std::deque<msg::LocalMap> local_maps;
  };
  // Appends T if it is path_spacing_m from the path's last pose (halving a full path first); false: not appended.
  bool append_spaced(std::vector<PoseW>& path, const PoseW& T) const;
  // Moves the vehicle's truth path up to stamp_ns; true when it grew.
  bool advance_truth(Vehicle& v, std::int64_t stamp_ns) const;

  DerivedChannelsConfig config_;
  std::unique_ptr<twin::EnuFrame> enu_;
  mutable std::mutex mutex_;
  std::map<std::string, Vehicle> vehicles_;
  std::uint64_t tiles_undecodable_ = 0;
};

}  // namespace twinslam::foxglove

#pragma once
// Which position of a vehicle the tiles follow. Odometry's T_WB is in W only once its status says aligned; before
// that (initializing, local-frame tracking, reinitializing) T_WB is in the estimator's local frame L and would put
// the window in the wrong place, so GNSS fixes (converted to W by the caller) drive the window instead. After an
// aligned odometry, GNSS is ignored until the vehicle's odometry stops being aligned (e.g. a reinitialization).
#include <optional>
#include <string>
#include <unordered_map>

#include <Eigen/Core>

namespace twinslam::tiles {

class VehiclePositions {
 public:
  // Returns the position to stream around, or nullopt when this message must not move the window.
  std::optional<Eigen::Vector3d> on_odometry(const std::string& vehicle, bool aligned, const Eigen::Vector3d& p_WB);
  std::optional<Eigen::Vector3d> on_gnss(const std::string& vehicle, const Eigen::Vector3d& p_W);

  bool aligned(const std::string& vehicle) const;

 private:
  std::unordered_map<std::string, bool> aligned_;  // vehicle -> its last odometry was in W
};

}  // namespace twinslam::tiles

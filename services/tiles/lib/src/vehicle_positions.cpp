#include "twinslam/tiles/vehicle_positions.hpp"

namespace twinslam::tiles {

std::optional<Eigen::Vector3d> VehiclePositions::on_odometry(const std::string& vehicle, bool aligned,
                                                             const Eigen::Vector3d& p_WB) {
  aligned_[vehicle] = aligned;
  if (!aligned || !p_WB.allFinite()) return std::nullopt;
  return p_WB;
}

std::optional<Eigen::Vector3d> VehiclePositions::on_gnss(const std::string& vehicle, const Eigen::Vector3d& p_W) {
  if (aligned(vehicle) || !p_W.allFinite()) return std::nullopt;
  return p_W;
}

bool VehiclePositions::aligned(const std::string& vehicle) const {
  const auto it = aligned_.find(vehicle);
  return it != aligned_.end() && it->second;
}

}  // namespace twinslam::tiles

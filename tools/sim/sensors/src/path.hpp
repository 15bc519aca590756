#pragma once
// Planar paths of straight lines and circular arcs (in the east-north plane) with an altitude ramp on each piece,
// parametrized by horizontal arc length. The trajectory's spline control points are sampled from them at constant
// spacing, so the flown speed is nearly constant. Private to the library.
#include <vector>

#include <Eigen/Core>

namespace twinslam::sim::detail {

struct PathPoint {
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();  // [m]
  double heading = 0;    // direction of travel, counter-clockwise from east [rad] (not wrapped)
};

class PlanarPath {
 public:
  void add_line(const Eigen::Vector3d& a_W, const Eigen::Vector3d& b_W);
  // Arc around center_EN [m] of radius [m] from angle start [rad], signed sweep [rad] (> 0 counter-clockwise).
  void add_arc(const Eigen::Vector2d& center_EN, double radius, double start, double sweep, double z_start,
               double z_end);
  double length() const { return total_; }
  PathPoint at(double s) const;  // s [m] clamped into [0, length()]

  // A polyline through points_W whose corners are rounded by circular fillets of `radius` [m] (smaller where the
  // legs are short): bounded curvature, so bounded acceleration and yaw rate at a given speed.
  static PlanarPath filleted_polyline(const std::vector<Eigen::Vector3d>& points_W, double radius);

 private:
  struct Piece {
    bool arc = false;
    Eigen::Vector3d a_W = Eigen::Vector3d::Zero(), b_W = Eigen::Vector3d::Zero();  // line ends [m]
    Eigen::Vector2d center = Eigen::Vector2d::Zero();  // arc [m]
    double radius = 0, start = 0, sweep = 0, z0 = 0, z1 = 0;
    double length = 0, s0 = 0;    // [m]
  };
  std::vector<Piece> pieces_;
  double total_ = 0;
};

}  // namespace twinslam::sim::detail

// W = East-North-Up at a WGS84 origin. GeographicLib's LocalCartesian does geodetic <-> ENU; ECEF <-> ENU is the
// exact affine map p_W = R_W_ECEF (p_ECEF - o_ECEF), the same one LocalCartesian applies internally.
#include "twinslam/twin/geo.hpp"

#include <cmath>
#include <sstream>

#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/LocalCartesian.hpp>

#include "twinslam/core/error.hpp"

namespace twinslam::twin {

GeoOrigin parse_origin(const std::string& text) {
  std::istringstream in(text);
  GeoOrigin o;
  char c1 = 0, c2 = 0;
  std::string rest;
  if (!(in >> o.lat_deg >> c1 >> o.lon_deg >> c2 >> o.alt_m) || c1 != ',' || c2 != ',' || (in >> rest))
    throw UsageError("origin '" + text + "' must be LAT,LON,ALT (degrees, degrees, metres)");
  if (!std::isfinite(o.lat_deg) || std::abs(o.lat_deg) > 90.0)
    throw UsageError("origin '" + text + "': latitude must be within [-90, 90] degrees");
  if (!std::isfinite(o.lon_deg) || std::abs(o.lon_deg) > 180.0)
    throw UsageError("origin '" + text + "': longitude must be within [-180, 180] degrees");
  if (!std::isfinite(o.alt_m) || std::abs(o.alt_m) > 1.0e5)
    throw UsageError("origin '" + text + "': altitude must be a finite height in metres (|alt| <= 100 km)");
  return o;
}

struct EnuFrame::Impl {
  GeographicLib::LocalCartesian local;
  Eigen::Vector3d o_ECEF;
  Eigen::Matrix3d R_W_ECEF;
};

EnuFrame::EnuFrame(const GeoOrigin& origin) : origin_(origin), impl_(std::make_unique<Impl>()) {
  const auto& earth = GeographicLib::Geocentric::WGS84();
  impl_->local = GeographicLib::LocalCartesian(origin.lat_deg, origin.lon_deg, origin.alt_m, earth);
  earth.Forward(origin.lat_deg, origin.lon_deg, origin.alt_m, impl_->o_ECEF.x(), impl_->o_ECEF.y(), impl_->o_ECEF.z());
  const double kDeg = M_PI / 180.0;
  const double sp = std::sin(origin.lat_deg * kDeg), cp = std::cos(origin.lat_deg * kDeg);
  const double sl = std::sin(origin.lon_deg * kDeg), cl = std::cos(origin.lon_deg * kDeg);
  // Rows: East, North, Up expressed in ECEF.
  impl_->R_W_ECEF << -sl, cl, 0.0,        //
      -sp * cl, -sp * sl, cp,             //
      cp * cl, cp * sl, sp;
}

EnuFrame::~EnuFrame() = default;

Eigen::Vector3d EnuFrame::from_ecef(const Eigen::Vector3d& p_ecef) const {
  return impl_->R_W_ECEF * (p_ecef - impl_->o_ECEF);
}

Eigen::Vector3d EnuFrame::to_ecef(const Eigen::Vector3d& p_W) const {
  return impl_->o_ECEF + impl_->R_W_ECEF.transpose() * p_W;
}

Eigen::Vector3d EnuFrame::from_lla(double lat_deg, double lon_deg, double h_m) const {
  Eigen::Vector3d p_W;
  impl_->local.Forward(lat_deg, lon_deg, h_m, p_W.x(), p_W.y(), p_W.z());
  return p_W;
}

Eigen::Vector3d EnuFrame::to_lla(const Eigen::Vector3d& p_W) const {
  Eigen::Vector3d lla;
  impl_->local.Reverse(p_W.x(), p_W.y(), p_W.z(), lla.x(), lla.y(), lla.z());
  return lla;
}

Eigen::Matrix3d EnuFrame::R_W_ECEF() const { return impl_->R_W_ECEF; }

}  // namespace twinslam::twin

#include "twinslam/gnss/constellation.hpp"

#include <array>
#include <cmath>
#include <numbers>

#include "twinslam/gnss/frames.hpp"

namespace twinslam::gnss {
namespace {

constexpr double kDeg = std::numbers::pi / 180;
// Greenwich hour angle at the SPS PS table's epoch: 18 h 36 min 14.4 s [deg].
constexpr double kGreenwichHourAngleDeg = (18 + 36 / 60.0 + 14.4 / 3600.0) * 15.0;

struct Slot {
  double raan_deg, arg_latitude_deg;
};

// GPS SPS Performance Standard, Table 3-1 (planes A..F, slots 1..4).
constexpr std::array<Slot, 24> kGpsSlots{{
    {272.847, 268.126}, {272.847, 161.786}, {272.847, 11.676},  {272.847, 41.806},   // A
    {332.847, 80.956},  {332.847, 173.336}, {332.847, 309.976}, {332.847, 204.376},  // B
    {32.847, 111.876},  {32.847, 11.796},   {32.847, 339.666},  {32.847, 241.556},   // C
    {92.847, 135.226},  {92.847, 265.446},  {92.847, 35.156},   {92.847, 167.356},   // D
    {152.847, 197.046}, {152.847, 302.596}, {152.847, 66.066},  {152.847, 333.686},  // E
    {212.847, 238.886}, {212.847, 345.226}, {212.847, 105.206}, {212.847, 135.346},  // F
}};

// A circular orbit: the argument of latitude is the mean anomaly (with zero argument of perigee).
OrbitElements circular(int id, SatSystem system, double radius_m, double inclination_deg, const Slot& slot) {
  OrbitElements o;
  o.id = id;
  o.system = system;
  o.sqrt_a = std::sqrt(radius_m);
  o.eccentricity = 0;
  o.inclination_rad = inclination_deg * kDeg;
  o.raan_rad = (slot.raan_deg - kGreenwichHourAngleDeg) * kDeg;
  o.raan_rate_rad_s = 0;  // nodal regression (~-0.04 deg/day) is negligible over a flight
  o.arg_perigee_rad = 0;
  o.mean_anomaly_rad = slot.arg_latitude_deg * kDeg;
  o.reference_time_s = 0;
  return o;
}

}  // namespace

std::vector<OrbitElements> gps_nominal_constellation() {
  // The radius whose period is half a sidereal day (26 561.7 km; the table rounds it to 26 559.7 km): the ground
  // tracks then repeat every sidereal day as the real ones do.
  const double half_sidereal_day_s = 86164.0905 / 2;
  const double radius_m = std::cbrt(kGmGps * std::pow(half_sidereal_day_s / (2 * std::numbers::pi), 2));
  std::vector<OrbitElements> out;
  for (std::size_t i = 0; i < kGpsSlots.size(); ++i) {
    out.push_back(circular(static_cast<int>(i) + 1, SatSystem::kGps, radius_m, 55.0, kGpsSlots[i]));
  }
  return out;
}

std::vector<OrbitElements> galileo_nominal_constellation() {
  // Walker 24/3/1: 8 slots 45 deg apart per plane, planes 120 deg apart, phased 15 deg (= 360 * 1 / 24) per plane.
  std::vector<OrbitElements> out;
  for (int plane = 0; plane < 3; ++plane) {
    for (int slot = 0; slot < 8; ++slot) {
      // The pattern fixes the planes only relative to each other; 25 deg keeps them off the GPS planes.
      const Slot s{25.0 + 120.0 * plane, 45.0 * slot + 15.0 * plane};
      out.push_back(circular(plane * 8 + slot + 1, SatSystem::kGalileo, 29600.318e3, 56.0, s));
    }
  }
  return out;
}

std::vector<OrbitElements> nominal_constellation() {
  std::vector<OrbitElements> out = gps_nominal_constellation();
  const std::vector<OrbitElements> gal = galileo_nominal_constellation();
  out.insert(out.end(), gal.begin(), gal.end());
  return out;
}

std::vector<SatelliteInView> satellites_in_view(const std::vector<OrbitElements>& almanac,
                                                const Eigen::Vector3d& receiver_ecef, double t_s, double mask_deg) {
  std::vector<SatelliteInView> out;
  for (const OrbitElements& o : almanac) {
    SatelliteInView s;
    s.id = o.id;
    s.system = o.system;
    s.p_ecef = satellite_ecef(o, t_s);
    const LookAngles a = look_angles(receiver_ecef, s.p_ecef);
    s.elevation_deg = a.elevation_deg;
    s.azimuth_deg = a.azimuth_deg;
    if (s.elevation_deg >= mask_deg) out.push_back(s);
  }
  return out;
}

}  // namespace twinslam::gnss

#pragma once
// An ENU -> WGS84 conversion independent of the project's (GeographicLib's LocalCartesian): PROJ's topocentric and
// geocentric operations chained in a pipeline, to check exports against. Header-only; link PROJ::proj.
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include <Eigen/Core>
#include <proj.h>

namespace twinslam::test {

class ProjEnu {
 public:
  ProjEnu(double lat0_deg, double lon0_deg, double h0_m) : ctx_(proj_context_create()) {
    char def[400];
    std::snprintf(def, sizeof def,
                  "+proj=pipeline +step +inv +proj=topocentric +ellps=WGS84 +lat_0=%.12f +lon_0=%.12f +h_0=%.6f "
                  "+step +inv +proj=cart +ellps=WGS84",
                  lat0_deg, lon0_deg, h0_m);
    pj_ = proj_create(ctx_, def);
    if (pj_ == nullptr) throw std::runtime_error(std::string("PROJ pipeline: ") + def);
  }
  ~ProjEnu() {
    proj_destroy(pj_);
    proj_context_destroy(ctx_);
  }
  ProjEnu(const ProjEnu&) = delete;
  ProjEnu& operator=(const ProjEnu&) = delete;

  // p_W (east, north, up) [m] -> (lat [deg], lon [deg], ellipsoidal h [m]).
  Eigen::Vector3d to_lla(const Eigen::Vector3d& p_W) const {
    const PJ_COORD out = proj_trans(pj_, PJ_FWD, proj_coord(p_W.x(), p_W.y(), p_W.z(), 0));
    return {proj_todeg(out.lpz.phi), proj_todeg(out.lpz.lam), out.lpz.z};
  }

 private:
  PJ_CONTEXT* ctx_;
  PJ* pj_ = nullptr;
};

// Distance [m] between two WGS84 positions a few metres apart: local metres per degree at a's latitude.
inline double lla_distance_m(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  constexpr double kPi = 3.14159265358979323846;
  const double m_per_deg_lat = 111132.954, m_per_deg_lon = 111319.49 * std::cos(a.x() * kPi / 180.0);
  return Eigen::Vector3d((a.x() - b.x()) * m_per_deg_lat, (a.y() - b.y()) * m_per_deg_lon, a.z() - b.z()).norm();
}

}  // namespace twinslam::test

#pragma once
// GNSS jumps (issue 15): a receiver that switches solutions (a fault, a spoofer, a satellite set change) moves its
// fixes tens of metres from one epoch to the next while its stated uncertainty stays small. Fixes are compared epoch
// to epoch against the VIO's own motion: the horizontal step excess
//   x = |dp_fix| - |dp_VIO|            (a lower bound of |dp_fix - R_WL dp_VIO| for any R_WL: no alignment needed)
// is a jump when x > jump_sigmas * sqrt(sigma_h(previous)^2 + sigma_h(this)^2) and x > min_jump_m, sigma_h^2 being a
// fix's horizontal variance (east + north, from its own covariance, not inflated). The fixes after a jump are refused
// until a later jump undoes it (the jump steps since it sum to less than min_jump_m) or it has lasted hold_s, when
// the new level is taken (the receiver was wrong before, or re-converged). Measured on the ray-traced urban GNSS of
// city-loops, city-survey, city-long and Delft (seed 7; 8400 fixes, 5 Hz): the largest step excess of a real fix was
// 3.9 of these sigmas (70 m where the receiver itself said 18 m), so 8 sigmas refuses none of them.
#include <cstdint>
#include <optional>

#include <Eigen/Core>

namespace twinslam::estimator {

struct GnssJumpConfig {
  double jump_sigmas = 8.0;  // [1] step excess beyond this many of the two fixes' horizontal sigmas: a jump; 0: off
  double min_jump_m = 10.0;  // [m] ... and beyond this
  double hold_s = 30.0;      // [s] a jump not undone within this becomes the new level
  void validate() const;     // throws twinslam::InputError naming the field
};

struct GnssJumpCounts {
  unsigned long long jumps = 0, refused = 0, undone = 0, held_out = 0;  // held_out: new level taken after hold_s
};

class GnssJumpDetector {
 public:
  explicit GnssJumpDetector(const GnssJumpConfig& config) : config_(config) {}
  // One fix in stamp order: p_W, its covariance (ENU, as the receiver states it), and the VIO's body position in L at
  // its stamp if the estimator is tracking. True: use it; false: refused (a jump is open).
  bool accept(std::int64_t stamp_ns, const Eigen::Vector3d& p_W, const Eigen::Matrix3d& cov_W,
              const std::optional<Eigen::Vector3d>& p_L);
  bool jump_open() const { return open_since_ns_ >= 0; }
  const GnssJumpCounts& counts() const { return counts_; }

 private:
  struct Fix {
    Eigen::Vector3d p_W;
    double var_h;  // east + north variance [m^2]
    std::optional<Eigen::Vector3d> p_L;
  };
  GnssJumpConfig config_;
  std::optional<Fix> previous_;      // the last fix received, refused or not
  std::int64_t open_since_ns_ = -1;  // stamp of the jump now open
  Eigen::Vector2d jumped_ = Eigen::Vector2d::Zero();  // sum of the jump steps since it opened [m, east-north]
  GnssJumpCounts counts_;
};

}  // namespace twinslam::estimator

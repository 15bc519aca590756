#include "twinslam/estimator/gnss_jump.hpp"

#include <cmath>
#include <string>

#include "twinslam/core/error.hpp"

namespace twinslam::estimator {

void GnssJumpConfig::validate() const {
  const std::pair<const char*, double> nonneg[] = {
      {"gnss_jump_sigmas", jump_sigmas}, {"gnss_jump_min_m", min_jump_m}, {"gnss_jump_hold_s", hold_s}};
  for (const auto& [name, v] : nonneg) {
    if (!(v >= 0.0) || !std::isfinite(v)) throw InputError(std::string("global fusion: ") + name + " must be >= 0");
  }
}

bool GnssJumpDetector::accept(std::int64_t stamp_ns, const Eigen::Vector3d& p_W, const Eigen::Matrix3d& cov_W,
                              const std::optional<Eigen::Vector3d>& p_L) {
  const Fix fix{p_W, cov_W(0, 0) + cov_W(1, 1), p_L};
  const std::optional<Fix> previous = previous_;
  previous_ = fix;
  if (config_.jump_sigmas <= 0.0 || !previous) return true;
  const Eigen::Vector2d step = (fix.p_W - previous->p_W).head<2>();
  const double vio_m = (fix.p_L && previous->p_L) ? (*fix.p_L - *previous->p_L).head<2>().norm() : 0.0;
  const double excess_m = step.norm() - vio_m;
  const bool jump = excess_m > config_.min_jump_m &&
                    excess_m > config_.jump_sigmas * std::sqrt(std::max(previous->var_h + fix.var_h, 0.0));
  if (!jump_open()) {
    if (!jump) return true;
    open_since_ns_ = stamp_ns;
    jumped_ = step;
    ++counts_.jumps;
    ++counts_.refused;
    return false;
  }
  if (jump) {
    jumped_ += step;
    if (jumped_.norm() < config_.min_jump_m) {  // back where the fixes were before it opened
      open_since_ns_ = -1;
      ++counts_.undone;
      return true;
    }
  }
  if (1e-9 * static_cast<double>(stamp_ns - open_since_ns_) > config_.hold_s) {
    open_since_ns_ = -1;  // the new level stands
    ++counts_.held_out;
    return true;
  }
  ++counts_.refused;
  return false;
}

}  // namespace twinslam::estimator

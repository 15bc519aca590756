#pragma once
// Extension point of the sliding window: global measurements (digital-twin map registration, paper eq. 7; GNSS) add
// their residual terms to the window without changes to the estimator. How to write one: docs/ARCHITECTURE.md.
//
// The estimator calls add_terms() every time it builds the window's term list: once per solve, and again right
// before the oldest keyframe is marginalized. A provider's terms on that keyframe then go into the marginalization
// prior like the IMU and visual terms (their information is kept, also on T_WL), and keyframe_marginalized() tells the
// provider to stop attaching that measurement.
#include <cstdint>
#include <vector>

#include "twinslam/estimator/residual_term.hpp"

namespace twinslam::estimator {

// The window's state blocks, oldest first (layouts of imu_state.hpp). The last entry is the newest frame, which may
// be a non-keyframe (dropped with its terms at the next frame if it does not become one).
struct WindowBlocks {
  std::vector<std::int64_t> stamps_ns;
  std::vector<double*> pose;        // [p_L x y z, q_LB x y z w], kPoseSize; tangent [dp, dtheta] (translation first)
  std::vector<double*> speed_bias;  // [v_L, b_g, b_a], kSpeedBiasSize
  std::vector<bool> is_keyframe;
  // The world alignment T_WL (world_alignment.hpp): [p_WL x y z [m], yaw_WL [rad]], kWorldAlignmentSize, Euclidean.
  // L and W are both gravity-aligned, so T_WL = (Rz(yaw_WL), p_WL). It joins the problem only through terms that act
  // on it; until then it is held at its value.
  double* T_WL = nullptr;
};

class WindowFactorProvider {
 public:
  virtual ~WindowFactorProvider() = default;
  // Appends this provider's terms on `blocks` to `terms`. Must be a function of the provider's measurements and the
  // blocks only (the solve and the marginalization call it on the same state and must get the same terms).
  virtual void add_terms(const WindowBlocks& blocks, std::vector<ResidualTerm>& terms) = 0;
  // The keyframe with this stamp has left the window; its terms are in the marginalization prior now.
  virtual void keyframe_marginalized(std::int64_t /*stamp_ns*/) {}
};

}  // namespace twinslam::estimator

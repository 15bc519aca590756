#pragma once
// A GNSS-like provider for tests and the worked example of docs/ARCHITECTURE.md ("How to add a factor"): a position
// fix z_W of body B at a frame stamp, in W, with isotropic sigma. Residual (3), blocks pose [7] and T_WL [4]:
//   r = (Rz(yaw_WL) p_LB + p_WL - z_W) / sigma      (p_LB: the translation of the frame's pose block)
// attached to keyframes only (a non-keyframe leaves the window with its terms), and dropped once its keyframe is
// marginalized — its information then lives on in the marginalization prior.
#include <map>
#include <memory>

#include <ceres/autodiff_cost_function.h>
#include <Eigen/Core>

#include "twinslam/estimator/imu_state.hpp"
#include "twinslam/estimator/window_factor_provider.hpp"
#include "twinslam/estimator/world_alignment.hpp"

namespace twinslam::testing {

struct PositionInWorldFactor {
  Eigen::Vector3d z_W;
  double inv_sigma;
  template <class T>
  bool operator()(const T* pose, const T* T_WL, T* r) const {
    T p_W[3];
    estimator::world_from_local(T_WL, pose, p_W);  // pose[0..2] = p_LB
    for (int k = 0; k < 3; ++k) r[k] = (p_W[k] - T(z_W[k])) * T(inv_sigma);
    return true;
  }
};

class PositionProvider final : public estimator::WindowFactorProvider {
 public:
  // withhold_oldest: never attach a fix to the window's oldest keyframe, so no fix is ever marginalized — what the
  // estimator did before issue 11 (provider information on a leaving keyframe was dropped). For comparisons only.
  explicit PositionProvider(bool withhold_oldest = false) : withhold_oldest_(withhold_oldest) {}

  void add_fix(std::int64_t stamp_ns, const Eigen::Vector3d& z_W, double sigma_m) { fixes_[stamp_ns] = {z_W, sigma_m}; }

  void add_terms(const estimator::WindowBlocks& blocks, std::vector<estimator::ResidualTerm>& terms) override {
    ++calls;
    for (std::size_t k = 0; k < blocks.stamps_ns.size(); ++k) {
      const auto fix = fixes_.find(blocks.stamps_ns[k]);
      if (fix == fixes_.end() || !blocks.is_keyframe[k] || (withhold_oldest_ && k == 0)) continue;
      using Cost = ceres::AutoDiffCostFunction<PositionInWorldFactor, 3, estimator::kPoseSize,
                                               estimator::kWorldAlignmentSize>;
      terms.push_back(estimator::make_term(
          estimator::TermKind::kProvider, "position fix @ " + std::to_string(fix->first) + " ns",
          std::make_unique<Cost>(new PositionInWorldFactor{fix->second.first, 1.0 / fix->second.second}), nullptr,
          {blocks.pose[k], blocks.T_WL}));
      ++terms_added;
    }
  }

  void keyframe_marginalized(std::int64_t stamp_ns) override {
    if (fixes_.erase(stamp_ns) != 0) ++marginalized;
  }

  std::size_t calls = 0, terms_added = 0, marginalized = 0;

 private:
  bool withhold_oldest_;
  std::map<std::int64_t, std::pair<Eigen::Vector3d, double>> fixes_;
};

}  // namespace twinslam::testing

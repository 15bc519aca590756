#pragma once
// Feeds accepted map registrations (map_registration_factor.hpp) into the sliding window as provider terms on the
// keyframe whose stamp the registration answers. A result whose keyframe already left the window (a slow edge, a
// slow link) is re-attached to the oldest kept keyframe through the estimated relative motion between the two
// (counted as `reattached`); one that matches no keyframe at all is counted as `unmatched` — never dropped silently.
#include <cstdint>
#include <map>
#include <memory>

#include "twinslam/estimator/map_registration_factor.hpp"
#include "twinslam/estimator/window_factor_provider.hpp"

namespace twinslam::estimator {

struct MapRegistrationProviderConfig {
  double huber_delta = 3.0;       // robust loss on the whitened 6-residual (about the 95 % chi-square bound) [1]
  double max_reattach_s = 10.0;   // a late result farther than this from the oldest kept keyframe is not used [s]
  void validate() const;          // throws twinslam::InputError naming the field
};

struct MapRegistrationCounts {
  unsigned long long received = 0, attached = 0, reattached = 0, unmatched = 0, marginalized = 0,
                     dropped = 0;  // taken out of the window by drop_all (a re-alignment found them wrong)
};

class MapRegistrationProvider final : public WindowFactorProvider {
 public:
  explicit MapRegistrationProvider(const MapRegistrationProviderConfig& config = {});

  // An accepted registration. T_LB_estimate / T_WL_estimate: the keyframe pose and alignment of the LocalMap it
  // answers (what the estimator published), so the correction is read against the estimate it was computed from.
  void add(const MapRegistration& registration, const Eigen::Isometry3d& T_LB_estimate);

  // Takes every registration not yet marginalized out of the window (counted as `dropped`): they were read against an
  // alignment that a re-admitted registration found wrong.
  void drop_all();

  void add_terms(const WindowBlocks& blocks, std::vector<ResidualTerm>& terms) override;
  void keyframe_marginalized(std::int64_t stamp_ns) override;

  const MapRegistrationCounts& counts() const { return counts_; }

 private:
  struct Pending {
    MapRegistration registration;
    Eigen::Isometry3d T_LB_estimate;
    std::shared_ptr<ceres::CostFunction> cost;  // built once it is attached (shared by solve and marginalization)
    std::int64_t attached_to = -1;              // stamp of the keyframe carrying it
  };
  void attach(Pending& p, const WindowBlocks& blocks);

  MapRegistrationProviderConfig config_;
  std::shared_ptr<ceres::LossFunction> loss_;
  std::multimap<std::int64_t, Pending> pending_;  // by keyframe stamp answered
  MapRegistrationCounts counts_;
};

}  // namespace twinslam::estimator

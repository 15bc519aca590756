#pragma once
// Re-admits corrections the Mahalanobis gate keeps refusing when they keep saying the same thing. The gate
// (registration.hpp) compares a correction with the covariance the estimator sends; after many fused registrations,
// which share landmarks and twin surfaces, that covariance is overconfident, and once the estimate has drifted (say,
// along a facade that hid the drift) every correct registration is refused: measured on city-loops with tracked
// images, runs of 10-20 refusals of the same 1.0-1.2 m correction over 5-13 s. A loosened gate lets wrong single
// registrations in (mahalanobis_floor_m 0.2 / 0.3 m: ATE 0.68 -> 1.27 / 2.65 m); a wrong registration rarely repeats
// the same wrong correction from keyframes a landmark horizon apart, with other landmarks; a drifted estimator does.
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "twinslam/registration/registration.hpp"

namespace twinslam::registration {

class PersistenceGate {
 public:
  explicit PersistenceGate(const RegistrationConfig& config) : config_(config) {}

  // Call with each result of one vehicle in keyframe order (stamp_ns: its keyframe's). A kCorrectionTooLarge result
  // is accepted (status kAccepted, information from its details, a reason saying so) when, among the refusals of the
  // last 2 x persistent_span_s, at least persistent_corrections (itself included) agree with it and the oldest of
  // those is persistent_span_s older than it. Refusals that disagree do not break the count: from a wrong estimate
  // ICP lands in the right basin on some keyframes and in a wrong one on others. Two corrections agree when, as
  // transforms of W (correction_W, the dT of eq. 3), they move the newest keyframe's position to within the larger
  // of persistent_tolerance_m and persistent_tolerance_fraction of its own correction, and turn by
  // persistent_tolerance_deg at most of each other. Compared in W, not about each keyframe: an estimate whose whole
  // frame is off (a T_WL heading error of 4 deg, say) needs the same dT of W from every keyframe, while its
  // correction about a keyframe 30 m from the turn's centre changes by 1.2 m as the vehicle flies 17 m. Why a span:
  // consecutive LocalMaps share most landmarks, so only refusals a landmark horizon apart are nearly independent
  // looks. kNotConverged results (ICP out of iterations, still pulled toward where the cloud fits) count as refusals
  // that agree or not, but are never accepted themselves. Accepted results in between do not count against it.
  // Returns true when it re-admitted `r`. Off when config.persistent_corrections is 0.
  //
  // Acquisition: heading_sigma_deg is the estimator's (from the covariance it sent; nullopt without one). While it is
  // above config.acquisition_heading_sigma_deg, an accepted correction larger than acquisition_min_correction_m/_deg
  // is held as a refusal (status kCorrectionTooLarge, reason "unconfirmed ...") and admitted by the same votes, and
  // heading-ambiguous results vote with their best heading. Why: a first alignment from GNSS in a street canyon is off
  // by metres and degrees, the heading search then spans +-45 deg, and in a city of similar blocks one search can
  // end in a wrong basin that no other keyframe confirms; accepted alone it was declared (city-loops, realistic
  // sensors: 4.4 m / 3.8 deg off for 22 s), while the right heading keeps coming back as the cloud changes.
  bool review(RegistrationResult& r, std::int64_t stamp_ns, std::optional<double> heading_sigma_deg = std::nullopt);

  std::size_t readmitted() const { return readmitted_; }

 private:
  bool agrees(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, const Eigen::Vector3d& p_W) const;
  // Turns an accepted large correction into a refusal while acquiring (see review()); true if it did.
  bool hold_for_confirmation(RegistrationResult& r, double heading_sigma_deg) const;

  RegistrationConfig config_;
  struct Refusal {
    std::int64_t stamp_ns;
    Eigen::Isometry3d correction_W;  // dT of W (eq. 3) that registration found
  };
  std::vector<Refusal> refused_;  // the gate's refusals of the last 2 spans, oldest first
  std::size_t readmitted_ = 0;
};

}  // namespace twinslam::registration

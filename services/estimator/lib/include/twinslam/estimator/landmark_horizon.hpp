#pragma once
// The landmarks a keyframe's LocalMap carries (issue 12: registration's source cloud). The window alone holds at most
// max_landmarks (150) points, often on one facade; registration wants more geometry. So every landmark the window
// reported is remembered with its last estimate in L after it leaves the window (marginalized or its track ended),
// and a LocalMap carries the window's landmarks plus those seen within `horizon_s` whose position lies within
// `horizon_m` of the keyframe. L drifts slowly, so a recently marginalized landmark's last estimate is still a good
// point of the same local map; the horizon bounds how much drift the cloud mixes in.
// The window itself does not stay put in L: each fused registration moves its keyframes (measured on city-loops:
// remembered landmarks within 30 m of the keyframe were off by up to 0.5 m as a group, those in view by 0.1 m).
// follow_window() therefore moves every remembered landmark with the oldest keyframe that was in the window both then
// and now, as if it had stayed in the window.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Geometry>

namespace twinslam::estimator {

// A landmark as the LocalMap carries it.
struct LandmarkEstimate {
  std::int64_t id = -1;
  Eigen::Vector3d p_L = Eigen::Vector3d::Zero();  // [m]
  double quality = 0.0;                           // [0, 1]: observations, parallax, reprojection error
  // Covariance of p_L [m^2] relative to the keyframes that observed it (landmark_covariance_L); zero: unknown.
  Eigen::Matrix3d cov_L = Eigen::Matrix3d::Zero();
};

struct LandmarkHorizonConfig {
  double horizon_s = 10.0;   // landmarks last in the window at most this long ago are kept; 0: window only [s]
  double horizon_m = 60.0;   // ... and only those within this distance of the keyframe [m]
  int max_landmarks = 1500;  // at most this many per LocalMap (the most recently seen first)
  bool follow_window = true; // remembered landmarks move with the window's keyframes (see above)
  bool operator==(const LandmarkHorizonConfig&) const = default;
  void validate(const std::string& source = "local_map") const;  // InputError naming the key
};

class LandmarkHorizon {
 public:
  explicit LandmarkHorizon(const LandmarkHorizonConfig& config = {});

  // The window's landmarks at keyframe `stamp_ns` (body at p_LB): remembers them and returns the LocalMap's cloud,
  // window landmarks (their current estimates) and remembered ones within the horizon (each with the estimate and
  // quality of the keyframe where its quality was highest), sorted by id. Stamps must not go
  // back (a reset of the estimator calls clear()).
  std::vector<LandmarkEstimate> update(std::int64_t stamp_ns, const Eigen::Vector3d& p_LB,
                                       const std::vector<LandmarkEstimate>& window);
  // The window's keyframe poses T_LB by stamp after this solve; call before update(). Moves every remembered landmark
  // by T_LB_k(now) T_LB_k(last call)^-1 of the oldest keyframe k in both (nothing when follow_window is off).
  void follow_window(const std::map<std::int64_t, Eigen::Isometry3d>& keyframes_T_LB);
  void clear() {
    seen_.clear();
    keyframes_.clear();
  }
  std::size_t remembered() const { return seen_.size(); }

 private:
  struct Seen {
    LandmarkEstimate current;  // at the last keyframe that had it in the window
    LandmarkEstimate best;     // at the keyframe where its quality was highest
    std::int64_t last_stamp_ns = 0;
  };
  LandmarkHorizonConfig config_;
  std::map<std::int64_t, Seen> seen_;  // by landmark id
  std::map<std::int64_t, Eigen::Isometry3d> keyframes_;  // the window's keyframe poses at the last follow_window()
};

}  // namespace twinslam::estimator

#pragma once
// Keyframe selection: a pure function of the tracking state since the last keyframe.
//
// A frame becomes a keyframe when (VINS-Mono, Qin et al., TRO 2018, keyframe selection of its
// vision front end, the same two criteria):
//  - the mean parallax of the features tracked since the last keyframe exceeds a threshold. The parallax is
//    rotation-compensated: each current bearing is rotated into the last keyframe's camera with the gyro-integrated
//    relative rotation before measuring the angle, because rotation alone gives no depth; or
//  - the fraction of the last keyframe's features still tracked falls below a threshold (the view changed, new
//    landmarks must be anchored before the old ones are lost).
#include <cstddef>
#include <span>
#include <string_view>

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross()

namespace twinslam::estimator {

struct KeyframePolicyConfig {
  double min_mean_parallax_px = 10.0;  // [px]; VINS-Mono's 10 px at its virtual focal length of 460 px
  double focal_px = 460.0;             // px per radian, converts the angular parallax to px
  double min_tracked_ratio = 0.5;      // tracked / last keyframe's features, in (0, 1]

  void validate() const;  // throws twinslam::InputError naming the bad field
};

// One feature seen in both the last keyframe and the current frame: unit bearings in each camera.
struct TrackedBearing {
  Eigen::Vector3d f_Ck = Eigen::Vector3d::UnitZ();  // in the last keyframe's camera C_k
  Eigen::Vector3d f_Cc = Eigen::Vector3d::UnitZ();  // in the current camera C_c
};

struct KeyframeInput {
  std::span<const TrackedBearing> tracked;           // features tracked from the last keyframe to this frame
  std::size_t keyframe_features = 0;                 // features the last keyframe had
  // Rotation of the current camera in the last keyframe's camera, from gyro preintegration:
  // R_CkCc = R_BC^T dR_kc R_BC.
  Eigen::Matrix3d R_CkCc = Eigen::Matrix3d::Identity();
};

enum class KeyframeReason { kNone, kParallax, kTrackLoss };
std::string_view to_string(KeyframeReason reason);

struct KeyframeDecision {
  bool is_keyframe = false;
  KeyframeReason reason = KeyframeReason::kNone;  // track loss wins when both hold
  double mean_parallax_px = 0.0;                  // rotation-compensated
  double tracked_ratio = 0.0;                     // tracked / keyframe_features (0 if the keyframe had none)
};

KeyframeDecision decide_keyframe(const KeyframePolicyConfig& config, const KeyframeInput& input);

}  // namespace twinslam::estimator

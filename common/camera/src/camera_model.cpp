#include "twinslam/camera/camera_model.hpp"

#include "twinslam/camera/fisheye_equidistant.hpp"
#include "twinslam/camera/pinhole_radtan.hpp"

namespace twinslam {

std::string_view to_string(DistortionModel model) {
  switch (model) {
    case DistortionModel::kRadialTangential:
      return "radial-tangential";
    case DistortionModel::kEquidistant:
      return "equidistant";
  }
  return "unknown";
}

std::unique_ptr<CameraModel> make_camera(const CameraIntrinsics& intrinsics) {
  if (intrinsics.distortion == DistortionModel::kEquidistant) {
    return std::make_unique<FisheyeEquidistant>(intrinsics);
  }
  return std::make_unique<PinholeRadtan>(intrinsics);
}

}  // namespace twinslam

#include "twinslam/camera/camera_config.hpp"

#include <cmath>
#include <sstream>

#include "twinslam/core/error.hpp"

namespace twinslam {
namespace {

[[noreturn]] void bad(const std::string& source, const char* key, const std::string& what) {
  throw InputError(where(source, 0, std::string("key '") + key + "': " + what));
}

std::string num(double x) {
  std::ostringstream s;
  s.precision(10);
  s << x;
  return s.str();
}

}  // namespace

void validate(const CameraIntrinsics& in, const std::string& source) {
  if (in.width <= 0 || in.height <= 0) {
    bad(source, "resolution", "width and height must be positive, got " + std::to_string(in.width) + " x " +
                                  std::to_string(in.height));
  }
  const double k[4] = {in.fu, in.fv, in.cu, in.cv};
  for (double x : k) {
    if (!std::isfinite(x)) bad(source, "intrinsics", "non-finite value " + num(x));
  }
  if (in.fu <= 0.0 || in.fv <= 0.0) {
    bad(source, "intrinsics", "focal lengths must be positive, got fu=" + num(in.fu) + " fv=" + num(in.fv));
  }
  for (double c : in.coefficients) {
    if (!std::isfinite(c)) bad(source, "distortion_coefficients", "non-finite value " + num(c));
  }
}

void validate(const CameraConfig& config, const std::string& source) {
  validate(config.intrinsics, source);
  if (!std::isfinite(config.rate_hz) || config.rate_hz <= 0.0) {
    bad(source, "rate_hz", "must be a positive number, got " + num(config.rate_hz));
  }
  const Eigen::Matrix4d& T = config.T_BC.matrix();
  if (!T.allFinite()) bad(source, "T_BS", "non-finite entry");
  if ((T.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > 1e-9) {
    bad(source, "T_BS", "last row must be [0, 0, 0, 1]");
  }
  // A rotation that is not orthonormal (a typo in one entry, a transposed layout with a translation column) would
  // silently skew every landmark; reject it rather than re-orthonormalize.
  const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
  const double err = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (err > kRotationOrthonormalTol) {
    bad(source, "T_BS", "rotation is not orthonormal (max |R^T R - I| = " + num(err) + ")");
  }
  if (R.determinant() <= 0.0) bad(source, "T_BS", "rotation is a reflection (det < 0)");
}

}  // namespace twinslam

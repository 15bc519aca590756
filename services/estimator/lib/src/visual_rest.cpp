// Visual rest test (visual_rest.hpp). Why over the window and not only frame to frame: in steady flight past distant
// facades consecutive frames move less than 2 px while the IMU feels only gravity, and a static initialization there
// takes 3 m/s for 0 (issue 14: an estimator restarted in flight); over 0.5 s the same flight moves tens of pixels.
// Why de-rotated over the window (frame to frame, a rotation still counts as motion): a drone that starts to
// accelerate tilts first (0.4 deg, 3 px at 460 px focal, while it has moved 1 mm) and a static initialization there
// is right. The rotation comes from the gyroscope, whose unknown bias (0.5 deg/s per axis for a consumer-grade IMU:
// 2 px over the window) is fitted to the bearings along with it; a fitted bias beyond max_rest_gyro_bias_radps is
// motion, not bias (steady flight past a facade looks like a turn the gyro did not feel), so it is not rest either.
#include "visual_rest.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

namespace twinslam::estimator {
namespace {

// R_{B(t0) B(t1)}: the body rotation from t0 to t1 integrated from the gyroscope minus `bias` (each sample's rate
// held until the next sample).
Eigen::Matrix3d gyro_rotation(const std::vector<ImuSample>& imu, std::int64_t t0, std::int64_t t1,
                              const Eigen::Vector3d& bias) {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  // The buffer is in stamp order: start at the sample holding t0 rather than scanning all of it per residual.
  const auto after = std::upper_bound(imu.begin(), imu.end(), t0,
                                      [](std::int64_t t, const ImuSample& x) { return t < x.stamp_ns; });
  for (auto i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(after - imu.begin() - 1, 0));
       i + 1 < imu.size() && imu[i].stamp_ns < t1; ++i) {
    const std::int64_t a = std::max(imu[i].stamp_ns, t0), b = std::min(imu[i + 1].stamp_ns, t1);
    if (b <= a) continue;
    const Eigen::Vector3d phi = (imu[i].gyro_B - bias) * 1e-9 * static_cast<double>(b - a);
    if (phi.norm() > 0.0) R = R * Eigen::AngleAxisd(phi.norm(), phi.normalized()).toRotationMatrix();
  }
  return R;
}

// The kept frames' bearings rotated into this camera with the gyro rotation for a bias, against this frame's.
struct RestProblem {
  const WindowState& s;
  const std::vector<FeatureBearing>& features;
  Eigen::Matrix3d R_BC;

  // R_{C_now C_earlier} for the kept frame f with gyro bias b.
  Eigen::Matrix3d rotation(const MotionInitFrame& f, std::int64_t now_ns, const Eigen::Vector3d& b) const {
    return R_BC.transpose() * gyro_rotation(s.imu, f.stamp_ns, now_ns, b).transpose() * R_BC;
  }
  // Stacked f_now x R f_earlier over all common tracks of all kept frames (each ~ the angle between them [rad]).
  Eigen::VectorXd residuals(std::int64_t now_ns, const Eigen::Vector3d& b) const {
    std::vector<double> r;
    for (const MotionInitFrame& f : s.rest_frames) {
      const Eigen::Matrix3d R = rotation(f, now_ns, b);
      for (const auto& x : features) {
        const auto it = f.bearings.find(x.id);
        if (it == f.bearings.end()) continue;
        const Eigen::Vector3d c = x.f_C.cross(R * it->second);
        r.insert(r.end(), {c.x(), c.y(), c.z()});
      }
    }
    return Eigen::Map<Eigen::VectorXd>(r.data(), static_cast<Eigen::Index>(r.size()));
  }
  // Gauss-Newton on the bias (numeric Jacobian: three parameters, a few hundred residuals, only while initializing).
  Eigen::Vector3d fit_bias(std::int64_t now_ns) const {
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    constexpr double kStep = 1e-5;  // [rad/s]
    for (int it = 0; it < 3; ++it) {
      const Eigen::VectorXd r0 = residuals(now_ns, b);
      if (r0.size() == 0) return b;
      Eigen::MatrixXd J(r0.size(), 3);
      for (int k = 0; k < 3; ++k) J.col(k) = (residuals(now_ns, b + kStep * Eigen::Vector3d::Unit(k)) - r0) / kStep;
      const Eigen::Matrix3d H = J.transpose() * J;
      if (H.determinant() <= 0.0) return b;
      b -= H.ldlt().solve(J.transpose() * r0);
    }
    return b;
  }
};

// Mean angle [px] between this frame's bearings and an earlier frame's rotated into this camera (R_CnowCearlier),
// over common tracks; infinity with none in common (stillness not shown).
double mean_motion_px(const MotionInitFrame& earlier, const Eigen::Matrix3d& R_CnCe,
                      const std::vector<FeatureBearing>& features, double focal_px) {
  double sum = 0.0;
  int n = 0;
  for (const auto& b : features) {
    const auto it = earlier.bearings.find(b.id);
    if (it == earlier.bearings.end()) continue;
    const Eigen::Vector3d f = R_CnCe * it->second;
    sum += std::atan2(b.f_C.cross(f).norm(), b.f_C.dot(f));
    ++n;
  }
  return n > 0 ? focal_px * sum / n : std::numeric_limits<double>::infinity();
}

}  // namespace

bool visually_still(WindowState& s, std::int64_t stamp_ns, const std::vector<FeatureBearing>& features) {
  const auto window_ns = static_cast<std::int64_t>(s.config.static_window_s * 1e9);
  while (s.rest_frames.size() > 1 && stamp_ns - s.rest_frames[1].stamp_ns >= window_ns) s.rest_frames.pop_front();
  const double limit_px = s.config.max_rest_feature_motion_px;
  // Frame to frame, as seen (a turn is not rest either: the static initialization takes the mean specific force for
  // gravity), then over the window with the gyro's rotation removed (steady flight is not rest).
  bool still = !s.rest_frames.empty() &&
               mean_motion_px(s.rest_frames.back(), Eigen::Matrix3d::Identity(), features, s.config.focal_px) <= limit_px;
  if (still) {
    const RestProblem pb{s, features, camera_T_BC(s).linear()};
    const Eigen::Vector3d bias = pb.fit_bias(stamp_ns);
    still = bias.norm() <= s.config.max_rest_gyro_bias_radps;
    for (const MotionInitFrame& f : s.rest_frames) {
      still = still && mean_motion_px(f, pb.rotation(f, stamp_ns, bias), features, s.config.focal_px) <= limit_px;
    }
  }
  MotionInitFrame now;
  now.stamp_ns = stamp_ns;
  for (const auto& b : features) now.bearings[b.id] = b.f_C;
  s.rest_frames.push_back(std::move(now));
  return features.empty() || still;
}

}  // namespace twinslam::estimator

// Closed-form visual-inertial initialization in motion (motion_init.hpp for the derivation).
#include "twinslam/estimator/motion_init.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "motion_init_refine.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/estimator/preintegration.hpp"

namespace twinslam::estimator {
namespace {

using Matrix36 = Eigen::Matrix<double, 3, 6>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;
constexpr double kDeg = M_PI / 180.0;

// Rotation and gravity-free position of every frame's body in B_0: one preintegration 0 -> k per frame (zero
// linearization bias), which also gives the bias Jacobians the refinement needs.
struct FrameMotion {
  double t_s = 0.0;                                  // since frame 0 [s]
  Eigen::Matrix3d R_0k = Eigen::Matrix3d::Identity();
  Eigen::Vector3d dp_0k = Eigen::Vector3d::Zero();   // [m, B_0]
  std::shared_ptr<Preintegration> pre;               // null for frame 0
};

std::vector<FrameMotion> integrate(const std::vector<MotionInitFrame>& frames, const std::vector<ImuSample>& imu,
                                   const ImuNoise& noise) {
  PreintegrationConfig pc;
  pc.noise = noise;
  std::vector<FrameMotion> out(frames.size());
  const std::int64_t t0 = frames.front().stamp_ns;
  for (std::size_t k = 1; k < frames.size(); ++k) {
    const std::int64_t t1 = frames[k].stamp_ns;
    FrameMotion& m = out[k];
    m.pre = std::make_shared<Preintegration>(pc, ImuBias{}, covering_samples(imu, t0, t1), t0, t1);
    m.t_s = m.pre->dt();
    m.R_0k = m.pre->delta().R;
    m.dp_0k = m.pre->delta().p;
  }
  return out;
}

// At most n frames evenly spread over the window, always the oldest and the newest.
std::vector<MotionInitFrame> pick_frames(const std::vector<MotionInitFrame>& frames, int n) {
  if (static_cast<int>(frames.size()) <= n) return frames;
  std::vector<MotionInitFrame> out;
  for (int i = 0; i < n; ++i) {
    out.push_back(frames[static_cast<std::size_t>(std::lround(i * (frames.size() - 1.0) / (n - 1.0)))]);
  }
  return out;
}

struct Ray {
  std::size_t frame = 0;
  Eigen::Vector3d d_B0;   // unit direction in B_0
  Eigen::Vector3d a_B0;   // the part of the camera centre known from the IMU: dp_0k + R_0k t_BC [m]
  double weight = 1.0;
};

// Landmarks observed often enough and with enough parallax (angle span of their rays in B_0).
std::vector<std::vector<Ray>> collect_rays(const std::vector<MotionInitFrame>& frames,
                                           const std::vector<FrameMotion>& motion, const Eigen::Isometry3d& T_BC,
                                           const MotionInitConfig& c) {
  std::unordered_map<std::int64_t, std::vector<Ray>> by_id;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const Eigen::Matrix3d R_0C = motion[k].R_0k * T_BC.linear();
    const Eigen::Vector3d a = motion[k].dp_0k + motion[k].R_0k * T_BC.translation();
    for (const auto& [id, f_C] : frames[k].bearings) by_id[id].push_back({k, (R_0C * f_C).normalized(), a, 1.0});
  }
  std::vector<std::vector<Ray>> out;
  const double cos_min = std::cos(c.min_parallax_deg * kDeg);
  for (auto& [id, rays] : by_id) {
    if (static_cast<int>(rays.size()) < c.min_observations) continue;
    double min_cos = 1.0;
    for (const Ray& r : rays) min_cos = std::min(min_cos, r.d_B0.dot(rays.front().d_B0));
    if (min_cos < cos_min) out.push_back(std::move(rays));
  }
  return out;
}

// Normal equations of all rays with the landmarks eliminated (Schur complement onto x = [v_0; g]).
struct Reduced {
  Matrix6d H = Matrix6d::Zero();
  Vector6d r = Vector6d::Zero();
  std::vector<Eigen::Matrix3d> A;   // per landmark, for back-substitution
  std::vector<Matrix36> C;
  std::vector<Eigen::Vector3d> rP;
};

// d/dx of the camera centre c_k = [t I, t^2/2 I] x + a_k.
Matrix36 centre_jacobian(double t) {
  Matrix36 J;
  J << t * Eigen::Matrix3d::Identity(), 0.5 * t * t * Eigen::Matrix3d::Identity();
  return J;
}

Reduced reduce(const std::vector<std::vector<Ray>>& landmarks, const std::vector<FrameMotion>& motion) {
  Reduced red;
  for (const auto& rays : landmarks) {
    // Residual of a ray: (I - d d^T)(P - c_k): the component of P - c_k off the ray. M = I - d d^T = [d]x^T [d]x.
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    Matrix36 C = Matrix36::Zero();
    Eigen::Vector3d rP = Eigen::Vector3d::Zero();
    for (const Ray& ray : rays) {
      const Eigen::Matrix3d M = ray.weight * (Eigen::Matrix3d::Identity() - ray.d_B0 * ray.d_B0.transpose());
      const Matrix36 J = centre_jacobian(motion[ray.frame].t_s);
      A += M;
      C -= M * J;
      rP += M * ray.a_B0;
      red.H += J.transpose() * M * J;
      red.r -= J.transpose() * M * ray.a_B0;
    }
    const Eigen::Matrix3d A_inv = A.inverse();
    red.H -= C.transpose() * A_inv * C;
    red.r -= C.transpose() * A_inv * rP;
    red.A.push_back(A);
    red.C.push_back(C);
    red.rP.push_back(rP);
  }
  return red;
}

Eigen::Vector3d landmark(const Reduced& red, std::size_t j, const Vector6d& x) {
  return red.A[j].ldlt().solve(red.rP[j] - red.C[j] * x);
}

// Minimizes over x with |g| = G (VINS-Mono's RefineGravity): g = G g_hat + B w on the tangent plane, a few times.
Vector6d solve_on_sphere(const Reduced& red, Vector6d x, double G) {
  for (int it = 0; it < 4; ++it) {
    const Eigen::Vector3d g_hat = x.tail<3>().normalized();
    const Eigen::Vector3d any = std::abs(g_hat.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    const Eigen::Vector3d b1 = g_hat.cross(any).normalized(), b2 = g_hat.cross(b1);
    Eigen::Matrix<double, 6, 5> T = Eigen::Matrix<double, 6, 5>::Zero();
    T.topLeftCorner<3, 3>().setIdentity();
    T.block<3, 1>(3, 3) = b1;
    T.block<3, 1>(3, 4) = b2;
    Vector6d x0 = Vector6d::Zero();
    x0.tail<3>() = G * g_hat;
    const Eigen::Matrix<double, 5, 5> H5 = T.transpose() * red.H * T;
    const Eigen::Matrix<double, 5, 1> y = H5.ldlt().solve(T.transpose() * (red.r - red.H * x0));
    x.head<3>() = y.head<3>();
    x.tail<3>() = G * (G * g_hat + b1 * y(3) + b2 * y(4)).normalized();
  }
  return x;
}

// Weights the rays by 1 / depth^2 so that each residual is an angle (the noise is angular), with a Huber cap.
void reweight(std::vector<std::vector<Ray>>& landmarks, const Reduced& red, const std::vector<FrameMotion>& motion,
              const Vector6d& x, double huber_rad) {
  for (std::size_t j = 0; j < landmarks.size(); ++j) {
    const Eigen::Vector3d P = landmark(red, j, x);
    for (Ray& ray : landmarks[j]) {
      const Eigen::Vector3d to_P = P - (centre_jacobian(motion[ray.frame].t_s) * x + ray.a_B0);
      const double depth = std::max(to_P.norm(), 0.5);
      const double angle = std::atan2(to_P.cross(ray.d_B0).norm(), to_P.dot(ray.d_B0));
      ray.weight = (angle > huber_rad ? huber_rad / angle : 1.0) / (depth * depth);
    }
  }
}

// RMS of the gravity-free acceleration of the body over the window [m/s^2]: the velocity change the IMU measured
// between consecutive frames, g t + dv_0k in B_0 with the refined biases, over the time between them. Metric scale
// comes only from this acceleration (c_k = v_0 t_k + g t_k^2 / 2 + dp_0k): at constant velocity every scale fits
// the rays, and the refinement settles on a collapsed one whose landmarks are close and whose sigmas shrink with it.
double excitation_mps2(const std::vector<FrameMotion>& motion, const ImuBias& bias, const Eigen::Vector3d& g_B0) {
  Eigen::Vector3d u_prev = Eigen::Vector3d::Zero();
  double t_prev = 0.0, sum = 0.0;
  int n = 0;
  for (const FrameMotion& m : motion) {
    if (!m.pre || m.t_s <= t_prev) continue;
    const Eigen::Vector3d u = g_B0 * m.t_s + m.pre->corrected(bias).v;
    sum += ((u - u_prev) / (m.t_s - t_prev)).squaredNorm();
    ++n;
    u_prev = u;
    t_prev = m.t_s;
  }
  return n > 0 ? std::sqrt(sum / n) : 0.0;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

}  // namespace

void MotionInitConfig::validate() const {
  auto positive = [](double v, const char* name) {
    if (!(v > 0) || !std::isfinite(v)) throw InputError(std::string("motion_init.") + name + ": must be > 0");
  };
  positive(window_s, "window_s");
  positive(min_span_s, "min_span_s");
  if (min_span_s > window_s) throw InputError("motion_init.min_span_s: must be <= window_s");
  if (min_landmarks < 3) throw InputError("motion_init.min_landmarks: must be >= 3");
  if (max_frames < 3) throw InputError("motion_init.max_frames: must be >= 3");
  if (max_landmarks < min_landmarks) throw InputError("motion_init.max_landmarks: must be >= min_landmarks");
  if (min_observations < 2) throw InputError("motion_init.min_observations: must be >= 2");
  positive(min_parallax_deg, "min_parallax_deg");
  positive(max_gravity_norm_error, "max_gravity_norm_error");
  positive(max_tilt_sigma_deg, "max_tilt_sigma_deg");
  positive(max_velocity_sigma_mps, "max_velocity_sigma_mps");
  if (!(min_excitation_mps2 >= 0) || !std::isfinite(min_excitation_mps2)) {
    throw InputError("motion_init.min_excitation_mps2: must be >= 0");
  }
  positive(max_median_error_px, "max_median_error_px");
  positive(pixel_sigma, "pixel_sigma");
  positive(velocity_prior_sigma_mps, "velocity_prior_sigma_mps");
  positive(tilt_prior_sigma_rad, "tilt_prior_sigma_rad");
}

std::optional<MotionInitResult> try_motion_init(const std::vector<MotionInitFrame>& all_frames,
                                                const std::vector<ImuSample>& imu, const Eigen::Isometry3d& T_BC,
                                                const ImuNoise& noise, double gravity_mps2, double focal_px,
                                                const MotionInitConfig& c) {
  if (all_frames.size() < 3 || imu.empty()) return std::nullopt;
  const std::int64_t t_first = all_frames.front().stamp_ns, t_last = all_frames.back().stamp_ns;
  if (1e-9 * static_cast<double>(t_last - t_first) < c.min_span_s) return std::nullopt;
  if (imu.front().stamp_ns > t_first || imu.back().stamp_ns < t_last) return std::nullopt;
  const std::vector<MotionInitFrame> picked = pick_frames(all_frames, c.max_frames);
  const std::vector<MotionInitFrame>& frames = picked;
  const std::vector<FrameMotion> motion = integrate(frames, imu, noise);
  std::vector<std::vector<Ray>> landmarks = collect_rays(frames, motion, T_BC, c);
  if (static_cast<int>(landmarks.size()) < c.min_landmarks) return std::nullopt;
  if (static_cast<int>(landmarks.size()) > c.max_landmarks) {
    std::stable_sort(landmarks.begin(), landmarks.end(), [](const auto& a, const auto& b) { return a.size() > b.size(); });
    landmarks.resize(static_cast<std::size_t>(c.max_landmarks));
  }

  // Pass 1 (metric residuals) gives depths; pass 2 weighs the rays as angles, which is how the noise is.
  Reduced red = reduce(landmarks, motion);
  Vector6d x = red.H.ldlt().solve(red.r);
  if (!x.allFinite()) return std::nullopt;
  reweight(landmarks, red, motion, x, 3.0 / focal_px);
  red = reduce(landmarks, motion);
  x = red.H.ldlt().solve(red.r);
  if (!x.allFinite() || std::abs(x.tail<3>().norm() / gravity_mps2 - 1.0) > c.max_gravity_norm_error) {
    return std::nullopt;
  }
  x = solve_on_sphere(red, x, gravity_mps2);

  // Maximum-likelihood refinement on the angles with the IMU biases (motion_init_refine.hpp), then quality.
  RefineProblem pb;
  pb.t_BC = T_BC.translation();
  pb.sigma_rad = c.pixel_sigma / focal_px;
  pb.huber_rad = 2.0 * pb.sigma_rad;
  for (const FrameMotion& m : motion) {
    RefineFrame f;
    f.t_s = m.t_s;
    f.R_0k = m.R_0k;
    f.dp_0k = m.dp_0k;
    if (m.pre) {
      f.dR_dbg = m.pre->bias_jacobians().dR_dbg;
      f.dp_dbg = m.pre->bias_jacobians().dp_dbg;
      f.dp_dba = m.pre->bias_jacobians().dp_dba;
    }
    pb.frames.push_back(f);
  }
  RefineState st;
  st.v0_B0 = x.head<3>();
  st.g_B0 = x.tail<3>();
  for (std::size_t j = 0; j < landmarks.size(); ++j) {
    st.P_B0.push_back(landmark(red, j, x));
    for (const Ray& ray : landmarks[j]) {
      pb.rays.push_back({j, ray.frame, motion[ray.frame].R_0k.transpose() * ray.d_B0});
    }
  }
  if (!refine_motion_init(pb, st, c.max_refine_iterations)) return std::nullopt;
  const std::vector<double> err = ray_angles(pb, st);
  MotionInitResult out;
  out.median_error_px = focal_px * median(err);
  // Robust sigma of the angular noise: 1.4826 x the median absolute error of one axis; the median of the 2D angle
  // of an isotropic Gaussian is 1.18 sigma.
  const Eigen::Matrix<double, 5, 5> cov = motion_init_covariance(pb, st, out.median_error_px / focal_px / 1.1774);
  out.velocity_sigma_mps = std::sqrt(cov.topLeftCorner<3, 3>().diagonal().maxCoeff());
  out.tilt_sigma_deg = std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(cov.bottomRightCorner<2, 2>())
                                     .eigenvalues().maxCoeff()) / gravity_mps2 / kDeg;
  out.landmarks = static_cast<int>(landmarks.size());
  out.g_B0 = st.g_B0;
  ImuBias bias;
  bias.gyro = st.b_g;
  bias.accel = st.b_a;
  out.excitation_mps2 = excitation_mps2(motion, bias, st.g_B0);
  if (out.median_error_px > c.max_median_error_px || !(out.velocity_sigma_mps <= c.max_velocity_sigma_mps) ||
      !(out.tilt_sigma_deg <= c.max_tilt_sigma_deg) || !(out.excitation_mps2 >= c.min_excitation_mps2)) {
    return std::nullopt;
  }

  // L: gravity along -z, heading of the newest body 0, origin at the newest body (like the static initialization).
  const FrameMotion& last = motion.back();
  const PreintegratedDelta d = last.pre->corrected(bias);
  const Eigen::Matrix3d R_up = Eigen::Quaterniond::FromTwoVectors(out.g_B0.normalized(), -Eigen::Vector3d::UnitZ())
                                   .toRotationMatrix();
  const Eigen::Matrix3d R_tmp = R_up * d.R;
  const Eigen::Matrix3d R_LB0 = Eigen::AngleAxisd(-std::atan2(R_tmp(1, 0), R_tmp(0, 0)), Eigen::Vector3d::UnitZ()) * R_up;
  out.state.q_LB = Eigen::Quaterniond(R_LB0 * d.R).normalized();
  out.state.v_L = R_LB0 * (st.v0_B0 + out.g_B0 * last.t_s + d.v);
  out.state.bias.gyro = bias.gyro;  // the accelerometer bias is barely observable in 2 s: the window estimates it
  out.state.p_L.setZero();
  return out;
}

}  // namespace twinslam::estimator

// Resuming from a checkpoint (resume.hpp).
#include "twinslam/estimator/resume.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "twinslam/core/error.hpp"

namespace twinslam::estimator {
namespace {

constexpr double kDeg = M_PI / 180.0;

double yaw_of(const Eigen::Matrix3d& R) { return std::atan2(R(1, 0), R(0, 0)); }

nlohmann::json vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

// An array of n numbers under `key`, each within +-limit, or InputError naming the file and the key. The limits are
// far beyond any flight's (W is a city's local frame) and keep the state carried over the gap finite.
Eigen::VectorXd numbers(const nlohmann::json& j, const char* key, int n, double limit, const std::string& file) {
  if (!j.contains(key) || !j[key].is_array() || static_cast<int>(j[key].size()) != n) {
    throw InputError(where(file, 0, std::string("'") + key + "' must be an array of " + std::to_string(n) + " numbers"));
  }
  Eigen::VectorXd out(n);
  for (int i = 0; i < n; ++i) {
    const auto& x = j[key][static_cast<std::size_t>(i)];
    if (!x.is_number() || !(std::abs(x.get<double>()) <= limit)) {
      throw InputError(where(file, 0, std::string("'") + key + "' holds a value that is not a number within +-" +
                                          std::to_string(limit)));
    }
    out(i) = x.get<double>();
  }
  return out;
}

// A sigma: a number in (0, limit] (a zero sigma would be an infinitely certain prior).
double sigma(const nlohmann::json& j, const char* key, double limit, const std::string& file) {
  if (!j.contains(key) || !j[key].is_number() || !(j[key].get<double>() > 0) || !(j[key].get<double>() <= limit)) {
    throw InputError(where(file, 0, std::string("'") + key + "' must be a number in (0, " + std::to_string(limit) + "]"));
  }
  return j[key].get<double>();
}

}  // namespace

void ResumeConfig::validate() const {
  auto non_negative = [](double v, const char* name) {
    if (!(v >= 0) || !std::isfinite(v)) throw InputError(std::string("resume.") + name + ": must be >= 0");
  };
  non_negative(max_age_s, "max_age_s");
  non_negative(max_accel_mps2, "max_accel_mps2");
  non_negative(max_rate_degps, "max_rate_degps");
  non_negative(velocity_sigma_mps, "velocity_sigma_mps");
  non_negative(tilt_sigma_deg, "tilt_sigma_deg");
  non_negative(gyro_bias_sigma_radps, "gyro_bias_sigma_radps");
  non_negative(accel_bias_sigma_mps2, "accel_bias_sigma_mps2");
}

std::optional<ResumePlan> plan_resume(const EstimatorCheckpoint& cp, std::int64_t frame_ns, const ResumeConfig& c,
                                      std::string* why) {
  // In double: the int64 difference of two arbitrary stamps can overflow (the checkpoint file is outside input).
  const double dt = 1e-9 * (static_cast<double>(frame_ns) - static_cast<double>(cp.stamp_ns));
  if (dt < 0.0 || dt > c.max_age_s) {
    if (why) {
      *why = dt < 0.0 ? "the checkpoint is " + std::to_string(-dt) + " s after the first frame"
                      : "the checkpoint is " + std::to_string(dt) + " s old (resume.max_age_s " +
                            std::to_string(c.max_age_s) + ")";
    }
    return std::nullopt;
  }
  // Carried over the gap at constant velocity and attitude; what the gap may have changed goes into the sigmas.
  const Eigen::Matrix3d R_WB = cp.q_WB.normalized().toRotationMatrix();
  const double yaw = yaw_of(R_WB);
  const Eigen::Matrix3d R_LW = Eigen::AngleAxisd(-yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  ResumePlan plan;
  plan.age_s = dt;
  plan.state_L.q_LB = Eigen::Quaterniond(R_LW * R_WB).normalized();
  plan.state_L.v_L = R_LW * cp.v_W;
  plan.state_L.bias = cp.bias;
  plan.sigmas.velocity_mps = c.velocity_sigma_mps + c.max_accel_mps2 * dt;
  plan.sigmas.roll_pitch_rad = (c.tilt_sigma_deg + c.max_rate_degps * dt) * kDeg;
  plan.sigmas.gyro_bias_radps = c.gyro_bias_sigma_radps;
  plan.sigmas.accel_bias_mps2 = c.accel_bias_sigma_mps2;
  plan.pose_W.p_W = cp.p_W + cp.v_W * dt;
  plan.pose_W.yaw_deg = yaw / kDeg;
  plan.pose_W.sigmas = WorldAlignmentSigmas{cp.position_sigma_m + 0.5 * c.max_accel_mps2 * dt * dt,
                                            (cp.yaw_sigma_deg + c.max_rate_degps * dt) * kDeg};
  return plan;
}

void write_checkpoint(const std::filesystem::path& path, const EstimatorCheckpoint& cp) {
  const Eigen::Quaterniond q = cp.q_WB.normalized();
  const nlohmann::json j = {{"stamp_ns", cp.stamp_ns},
                            {"p_W", vec(cp.p_W)},
                            {"q_WB_wxyz", {q.w(), q.x(), q.y(), q.z()}},
                            {"v_W", vec(cp.v_W)},
                            {"gyro_bias", vec(cp.bias.gyro)},
                            {"accel_bias", vec(cp.bias.accel)},
                            {"position_sigma_m", cp.position_sigma_m},
                            {"yaw_sigma_deg", cp.yaw_sigma_deg}};
  std::filesystem::path tmp = path;
  tmp += ".tmp";
  {
    std::ofstream out(tmp);
    out << j.dump() << '\n';
    if (!out) throw std::runtime_error(tmp.string() + ": cannot write the checkpoint");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);  // atomic: a reader sees the old checkpoint or the new one, never half
  if (ec) throw std::runtime_error(path.string() + ": cannot replace the checkpoint: " + ec.message());
}

std::optional<EstimatorCheckpoint> read_checkpoint(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::ifstream in(path);
  if (!in) {
    if (!std::filesystem::exists(path)) return std::nullopt;
    throw InputError(where(file, 0, "cannot read the checkpoint"));
  }
  std::stringstream text;
  text << in.rdbuf();
  const nlohmann::json j = nlohmann::json::parse(text.str(), nullptr, false);
  if (j.is_discarded() || !j.is_object()) throw InputError(where(file, 0, "not a JSON object (an estimator checkpoint)"));
  // Sensor stamps are >= 0 and fit int64 (a larger unsigned value would wrap to a negative stamp).
  if (!j.contains("stamp_ns") || !j["stamp_ns"].is_number_integer() ||
      (j["stamp_ns"].is_number_unsigned() ? j["stamp_ns"].get<std::uint64_t>() > std::uint64_t{INT64_MAX}
                                          : j["stamp_ns"].get<std::int64_t>() < 0)) {
    throw InputError(where(file, 0, "'stamp_ns' must be an integer in [0, 2^63) [ns]"));
  }
  EstimatorCheckpoint cp;
  cp.stamp_ns = j["stamp_ns"].get<std::int64_t>();
  cp.p_W = numbers(j, "p_W", 3, 1e7, file);                  // [m]
  const Eigen::VectorXd q = numbers(j, "q_WB_wxyz", 4, 2.0, file);
  if (std::abs(q.norm() - 1.0) > 1e-3) throw InputError(where(file, 0, "'q_WB_wxyz' is not a unit quaternion"));
  cp.q_WB = Eigen::Quaterniond(q(0), q(1), q(2), q(3)).normalized();
  cp.v_W = numbers(j, "v_W", 3, 1e3, file);                  // [m/s]
  cp.bias.gyro = numbers(j, "gyro_bias", 3, 10.0, file);      // [rad/s]
  cp.bias.accel = numbers(j, "accel_bias", 3, 100.0, file);   // [m/s^2]
  cp.position_sigma_m = sigma(j, "position_sigma_m", 1e6, file);
  cp.yaw_sigma_deg = sigma(j, "yaw_sigma_deg", 360.0, file);
  return cp;
}

}  // namespace twinslam::estimator

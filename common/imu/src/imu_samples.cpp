#include "twinslam/imu/imu_samples.hpp"

#include <algorithm>
#include <string>

#include "twinslam/core/error.hpp"
#include "twinslam/geometry/so3.hpp"

namespace twinslam::imu {
namespace {

bool finite(const ImuSample& s) { return s.gyro_B.allFinite() && s.accel_B.allFinite(); }
std::string stamp(std::int64_t t) { return std::to_string(t) + " ns"; }

}  // namespace

std::span<const ImuSample> covering_samples(std::span<const ImuSample> sorted, std::int64_t t_i_ns,
                                            std::int64_t t_j_ns) {
  const auto by_stamp = [](const ImuSample& s, std::int64_t t) { return s.stamp_ns < t; };
  auto first = std::lower_bound(sorted.begin(), sorted.end(), t_i_ns, by_stamp);  // first stamp >= t_i
  if (first != sorted.begin() && (first == sorted.end() || first->stamp_ns > t_i_ns)) --first;
  auto last = std::lower_bound(first, sorted.end(), t_j_ns, by_stamp);  // first stamp >= t_j
  if (last != sorted.end()) ++last;
  return sorted.subspan(static_cast<std::size_t>(first - sorted.begin()), static_cast<std::size_t>(last - first));
}

ImuSample interpolate(const ImuSample& a, const ImuSample& b, std::int64_t t) {
  if (t == a.stamp_ns) return a;
  if (t == b.stamp_ns) return b;
  const double alpha = static_cast<double>(t - a.stamp_ns) / static_cast<double>(b.stamp_ns - a.stamp_ns);
  return {t, (1.0 - alpha) * a.gyro_B + alpha * b.gyro_B, (1.0 - alpha) * a.accel_B + alpha * b.accel_B};
}

std::vector<ImuSample> integration_nodes(std::span<const ImuSample> samples, std::int64_t t_i_ns,
                                         std::int64_t t_j_ns) {
  if (t_j_ns <= t_i_ns) {
    throw InputError("IMU interval: stamps must increase (t_i " + stamp(t_i_ns) + ", t_j " + stamp(t_j_ns) + ")");
  }
  for (std::size_t k = 0; k < samples.size(); ++k) {
    if (!finite(samples[k])) throw InputError("IMU sample at " + stamp(samples[k].stamp_ns) + " is not finite");
    if (k > 0 && samples[k].stamp_ns <= samples[k - 1].stamp_ns) {
      throw InputError("IMU timestamps do not increase at " + stamp(samples[k].stamp_ns));
    }
  }
  if (samples.empty() || samples.front().stamp_ns > t_i_ns || samples.back().stamp_ns < t_j_ns) {
    throw InputError("IMU samples do not cover the interval [" + stamp(t_i_ns) + ", " + stamp(t_j_ns) + "]");
  }
  std::vector<ImuSample> nodes;
  std::size_t k = 0;
  while (samples[k + 1].stamp_ns <= t_i_ns && k + 2 < samples.size()) ++k;  // samples[k] <= t_i < samples[k+1]
  nodes.push_back(samples[k].stamp_ns == t_i_ns ? samples[k] : interpolate(samples[k], samples[k + 1], t_i_ns));
  for (++k; k < samples.size() && samples[k].stamp_ns < t_j_ns; ++k) {
    if (samples[k].stamp_ns > t_i_ns) nodes.push_back(samples[k]);
  }
  // Now samples[k] is the first sample at or after t_j (it exists because the samples cover t_j).
  nodes.push_back(interpolate(samples[k - 1], samples[k], t_j_ns));
  return nodes;
}

Eigen::Matrix3d integrate_gyro(const std::vector<ImuSample>& nodes, const Eigen::Vector3d& gyro_bias_B) {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  for (std::size_t k = 0; k + 1 < nodes.size(); ++k) {
    const double h = 1e-9 * static_cast<double>(nodes[k + 1].stamp_ns - nodes[k].stamp_ns);  // [s]
    if (h <= 0.0) continue;
    const Eigen::Vector3d w = 0.5 * (nodes[k].gyro_B + nodes[k + 1].gyro_B) - gyro_bias_B;  // [rad/s]
    R = R * geometry::so3_exp(w * h);
  }
  // Products of hundreds of rotations drift off SO(3) by round-off; project once at the end.
  return geometry::so3_normalize(R);
}

std::optional<Eigen::Matrix3d> gyro_rotation_B(std::span<const ImuSample> buffer, std::int64_t t_i_ns,
                                               std::int64_t t_j_ns, const Eigen::Vector3d& gyro_bias_B) {
  if (t_j_ns <= t_i_ns || buffer.empty()) return std::nullopt;
  const auto slice = covering_samples(buffer, t_i_ns, t_j_ns);
  if (slice.empty() || slice.front().stamp_ns > t_i_ns || slice.back().stamp_ns < t_j_ns) return std::nullopt;
  return integrate_gyro(integration_nodes(slice, t_i_ns, t_j_ns), gyro_bias_B);
}

}  // namespace twinslam::imu

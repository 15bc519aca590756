#include "twinslam/sim/feature_tracks.hpp"

#include <algorithm>
#include <cstdio>
#include <random>

#include "twinslam/core/error.hpp"

namespace twinslam::sim {

FeatureTrackWriter::FeatureTrackWriter(const std::filesystem::path& file, std::vector<Eigen::Vector3d> landmarks_W,
                                       FeatureTrackConfig config, std::uint64_t seed)
    : out_(file), landmarks_W_(std::move(landmarks_W)), config_(config), seed_(seed) {
  if (!out_) throw InputError(file.string() + ": cannot write");
  out_ << "#timestamp [ns],landmark_id,u [px],v [px],u_noisy [px],v_noisy [px]\n";
}

int FeatureTrackWriter::add_frame(std::int64_t stamp_ns, const Eigen::Isometry3d& T_WC, const CameraModel& camera,
                                  const Renderer& world) {
  const Eigen::Isometry3d T_CW = T_WC.inverse();
  const Eigen::Vector3d c_W = T_WC.translation();
  struct Candidate {
    double range;
    std::size_t id;
    Eigen::Vector2d uv;
  };
  std::vector<Candidate> visible;
  for (std::size_t i = 0; i < landmarks_W_.size(); ++i) {
    const Eigen::Vector3d& p_W = landmarks_W_[i];
    const double range = (p_W - c_W).norm();
    if (range > config_.max_range_m || range < 0.3) continue;
    Eigen::Vector2d uv;
    if (camera.project(T_CW * p_W, &uv) != ProjectionStatus::kOk) continue;
    if (!camera.in_image(uv, config_.border_px)) continue;
    if (!world.visible(p_W, c_W)) continue;  // occluded by the world (the twin plays no part here)
    visible.push_back({range, i, uv});
  }
  if (static_cast<int>(visible.size()) > config_.max_per_frame) {
    std::nth_element(visible.begin(), visible.begin() + config_.max_per_frame, visible.end(),
                     [](const Candidate& a, const Candidate& b) { return a.range < b.range; });
    visible.resize(config_.max_per_frame);
  }
  std::sort(visible.begin(), visible.end(), [](const Candidate& a, const Candidate& b) { return a.id < b.id; });
  // Noise seeded per frame: the file does not depend on how frames are scheduled.
  std::mt19937_64 rng(seed_ ^ static_cast<std::uint64_t>(stamp_ns));
  std::normal_distribution<double> noise(0.0, config_.pixel_sigma);
  char line[160];
  for (const auto& c : visible) {
    const double un = c.uv.x() + noise(rng), vn = c.uv.y() + noise(rng);
    std::snprintf(line, sizeof(line), "%lld,%zu,%.4f,%.4f,%.4f,%.4f\n", static_cast<long long>(stamp_ns), c.id,
                  c.uv.x(), c.uv.y(), un, vn);
    out_ << line;
  }
  return static_cast<int>(visible.size());
}

}  // namespace twinslam::sim

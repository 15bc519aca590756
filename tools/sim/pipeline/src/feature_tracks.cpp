#include "twinslam/sim/feature_tracks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>

#include "twinslam/core/error.hpp"
#include "twinslam/sim/world/random.hpp"
#include "twinslam/sim/world/surface_distance.hpp"
#include "twinslam/sim/world/traffic.hpp"

namespace twinslam::sim {

FeatureTrackWriter::FeatureTrackWriter(const std::filesystem::path& file, std::vector<Eigen::Vector3d> landmarks_W,
                                       FeatureTrackConfig config, std::uint64_t seed)
    : out_(file), landmarks_W_(std::move(landmarks_W)), config_(config), seed_(seed) {
  if (!out_) throw InputError(file.string() + ": cannot write");
  out_ << "#timestamp [ns],landmark_id,u [px],v [px],u_noisy [px],v_noisy [px]\n";
}

namespace {

// The camera along the rows of one frame (rolling shutter): its pose at each row's time, linearly interpolated between
// rows (30 us apart; one pose for a global shutter).
class RowPoses {
 public:
  RowPoses(const FrameCapture& frame, int height) : frame_(frame), height_(height) {
    if (frame.shutter.line_time_s == 0) {
      T_WC_.push_back(frame.T_WC(frame.t_s));
      return;
    }
    for (int v = 0; v < height; ++v) T_WC_.push_back(frame.T_WC(time(v)));
  }
  bool rolling() const { return T_WC_.size() > 1; }
  double time(double v) const { return frame_.t_s + frame_.shutter.row_offset_s(v, height_); }
  Eigen::Isometry3d at(double v) const {
    if (!rolling()) return T_WC_.front();
    const double r = std::clamp(v, 0.0, static_cast<double>(height_ - 1));
    const std::size_t i = std::min(static_cast<std::size_t>(r), T_WC_.size() - 2);
    const double a = r - static_cast<double>(i);
    const Eigen::Quaterniond q0(T_WC_[i].linear()), q1(T_WC_[i + 1].linear());
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = q0.slerp(a, q1).toRotationMatrix();
    T.translation() = (1 - a) * T_WC_[i].translation() + a * T_WC_[i + 1].translation();
    return T;
  }

 private:
  const FrameCapture& frame_;
  int height_;
  std::vector<Eigen::Isometry3d> T_WC_;
};

// The pixel of a point p_at(t) under a rolling shutter: start from the middle row's pose, then move to the row it lands
// on until that row stops changing (the row's time moves the point by far less than a row per row, so this converges
// in two or three steps). row_out: the row whose time the pixel is of.
template <typename PointAt>
bool project_on_row(const RowPoses& rows, const CameraModel& camera, double middle_row, const PointAt& p_at,
                    Eigen::Vector2d* uv, double* row_out) {
  double row = middle_row;
  for (int it = 0; it < 8; ++it) {
    if (camera.project(rows.at(row).inverse() * p_at(rows.time(row)), uv) != ProjectionStatus::kOk) return false;
    if (!rows.rolling()) break;
    const double next = std::clamp(uv->y(), 0.0, static_cast<double>(camera.height() - 1));
    const bool settled = std::abs(next - row) < 1e-4;
    row = next;
    if (settled) break;
  }
  *row_out = row;
  return true;
}

}  // namespace

int FeatureTrackWriter::add_frame(std::int64_t stamp_ns, const Eigen::Isometry3d& T_WC, const CameraModel& camera,
                                  const Renderer& world) {
  FrameCapture frame;
  frame.T_WC = [&T_WC](double) { return T_WC; };
  return add_frame(stamp_ns, frame, camera, world);
}

int FeatureTrackWriter::add_frame(std::int64_t stamp_ns, const FrameCapture& frame, const CameraModel& camera,
                                  const Renderer& world) {
  const RowPoses rows(frame, camera.height());
  const double middle_row = 0.5 * (camera.height() - 1);
  const Eigen::Isometry3d T_WC = rows.at(middle_row);  // the pose at the frame's time
  const Eigen::Isometry3d T_CW = T_WC.inverse();
  const Eigen::Vector3d c_W = T_WC.translation();
  std::unique_ptr<TrafficSnapshot> cars;
  const Traffic* traffic = frame.traffic && !frame.traffic->empty() ? frame.traffic : nullptr;
  if (traffic) {
    // The cars that can hide a landmark in range (or carry one): those within that range of the camera.
    const double t0 = rows.time(0), t1 = rows.time(camera.height() - 1);
    std::vector<std::size_t> near;
    for (std::size_t k = 0; k < traffic->size(); ++k) {
      const auto [centre, radius] = traffic->bounding_sphere(k, t0, t1);
      if ((centre - c_W).norm() <= config_.max_range_m + radius + 1.0) near.push_back(k);
    }
    cars = traffic->snapshot(t0, t1, &near);
    if (car_landmarks_of_ != traffic) {  // the same points for every frame (seeded per car)
      car_landmarks_V_.clear();
      for (std::size_t k = 0; k < traffic->size() && config_.landmarks_per_car > 0; ++k) {
        std::vector<Eigen::Vector3d> points;
        for (const auto& p : sample_surface(traffic->mesh_V(k), config_.landmarks_per_car, seed_ ^ hash64(k + 1)))
          points.push_back(p.p_W);
        car_landmarks_V_.push_back(std::move(points));
      }
      car_landmarks_of_ = traffic;
    }
  }
  struct Candidate {
    double range;
    std::size_t id;
    Eigen::Vector2d uv;
  };
  std::vector<Candidate> visible;
  // A point seen at pixel uv, at the time of its row: in the image, not behind the world or a car.
  const auto keep = [&](std::size_t id, const Eigen::Vector3d& p_W, const Eigen::Vector2d& uv, double row) {
    if (!camera.in_image(uv, config_.border_px)) return;
    const Eigen::Vector3d c = rows.rolling() ? Eigen::Vector3d(rows.at(row).translation()) : c_W;
    if (!world.visible(p_W, c)) return;  // occluded by the world (the twin plays no part here)
    const double range = (p_W - c).norm();
    if (cars && cars->occluded(c, (p_W - c) / range, rows.time(row), range - 0.05)) return;
    visible.push_back({range, id, uv});
  };
  for (std::size_t i = 0; i < landmarks_W_.size(); ++i) {
    const Eigen::Vector3d& p_W = landmarks_W_[i];
    const double range = (p_W - c_W).norm();
    if (range > config_.max_range_m || range < 0.3) continue;
    Eigen::Vector2d uv;
    if (camera.project(T_CW * p_W, &uv) != ProjectionStatus::kOk) continue;
    double row = middle_row;
    if (rows.rolling()) {
      // A rolling shutter moves a point by a few pixels at most: only those near the image are worth the fixed point.
      if (!camera.in_image(uv, -50.0)) continue;
      if (!project_on_row(rows, camera, uv.y(), [&p_W](double) { return p_W; }, &uv, &row)) continue;
    }
    keep(i, p_W, uv, row);
  }
  for (std::size_t k = 0; k < car_landmarks_V_.size() && traffic; ++k) {
    for (std::size_t j = 0; j < car_landmarks_V_[k].size(); ++j) {
      const Eigen::Vector3d& p_V = car_landmarks_V_[k][j];
      const auto p_at = [&](double t) -> Eigen::Vector3d { return traffic->T_WV(k, t) * p_V; };
      const double range = (p_at(frame.t_s) - c_W).norm();
      if (range > config_.max_range_m || range < 0.3) continue;
      Eigen::Vector2d uv;
      double row = middle_row;
      if (!project_on_row(rows, camera, middle_row, p_at, &uv, &row)) continue;
      keep(landmarks_W_.size() + k * static_cast<std::size_t>(config_.landmarks_per_car) + j, p_at(rows.time(row)),
           uv, row);
    }
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

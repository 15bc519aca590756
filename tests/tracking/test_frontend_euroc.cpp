// The frontend on the real EuRoC V1_01 excerpt (95 frames, 752x480, radial-tangential pinhole) with the gyro
// prediction: enough features, long tracks, stable unique ids, bearings that reproject to their pixels. Writes a
// picture of the last frame's tracks to <bin>/tracks_euroc.png (docs/tracks_euroc.png is a copy of it).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "twinslam/camera/sensor_yaml.hpp"
#include "twinslam/ingest/dataset.hpp"
#include "twinslam/tracking/frontend.hpp"
#include "twinslam/tracking/gyro_rotation.hpp"
#include "twinslam/tracking/track_drawing.hpp"

namespace twinslam::tracking {
namespace {

namespace fs = std::filesystem;
const fs::path kEuroc = fs::path(TWINSLAM_SHARED_DIR) / "data/euroc-v1-01-micro";

class FrontendEuroc : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const CameraConfig cam = read_camera_sensor_yaml(kEuroc / "mav0/cam0/sensor.yaml");
    camera_ = make_camera(cam.intrinsics);
    const ingest::Dataset data = ingest::load_dataset(kEuroc);
    std::vector<imu::ImuSample> imu;
    for (const auto& r : data.imu) imu.push_back({r.stamp_ns, r.gyro_radps, r.accel_mps2});

    Frontend frontend(camera_);
    TrackHistory history(10);
    frames_ = new std::vector<FrameResult>();
    for (std::size_t k = 0; k < data.images.size(); ++k) {
      const cv::Mat img = cv::imread(data.images[k].file.string(), cv::IMREAD_GRAYSCALE);
      ASSERT_FALSE(img.empty()) << data.images[k].file;
      std::optional<Eigen::Matrix3d> R;
      if (k > 0) R = gyro_rotation_C(imu, data.images[k - 1].stamp_ns, data.images[k].stamp_ns, cam.T_BC.linear());
      frames_->push_back(frontend.track(data.images[k].stamp_ns, img, R ? &*R : nullptr));
      history.add(frames_->back());
      if (k + 1 == data.images.size()) {
        cv::imwrite((fs::path(TWINSLAM_BIN_DIR) / "tracks_euroc.png").string(), history.draw(img, frames_->back()));
      }
    }
  }
  static void TearDownTestSuite() { delete frames_; }

  static std::shared_ptr<const CameraModel> camera_;
  static std::vector<FrameResult>* frames_;
};
std::shared_ptr<const CameraModel> FrontendEuroc::camera_;
std::vector<FrameResult>* FrontendEuroc::frames_ = nullptr;

TEST_F(FrontendEuroc, AtLeast100FeaturesPerFrameAndMedianTrackLength20AtTheEnd) {
  ASSERT_EQ(frames_->size(), 95u);
  int fewest = 1000;
  for (std::size_t k = 1; k < frames_->size(); ++k) {
    fewest = std::min(fewest, static_cast<int>((*frames_)[k].features.size()));
    EXPECT_TRUE((*frames_)[k].stats.predicted);
  }
  EXPECT_GE(fewest, 100);
  std::vector<std::uint32_t> lengths;
  for (const auto& f : frames_->back().features) lengths.push_back(f.track_length);
  std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
  const std::uint32_t median = lengths[lengths.size() / 2];
  EXPECT_GE(median, 20u);
  int lost_klt = 0, lost_fb = 0, lost_ransac = 0, pruned = 0;
  for (const auto& r : *frames_) {
    lost_klt += r.stats.lost_klt;
    lost_fb += r.stats.lost_fb;
    lost_ransac += r.stats.lost_ransac;
    pruned += r.stats.pruned;
  }
  std::printf("fewest features %d, median track length at the end %u; lost: klt %d fb %d ransac %d pruned %d\n",
              fewest, median, lost_klt, lost_fb, lost_ransac, pruned);
}

TEST_F(FrontendEuroc, IdsAreUniqueStableAndNeverReused) {
  std::map<std::uint64_t, std::pair<std::size_t, std::uint32_t>> last;  // id -> (frame index, track length)
  std::uint64_t max_id = 0;
  for (std::size_t k = 0; k < frames_->size(); ++k) {
    std::set<std::uint64_t> ids;
    std::uint64_t frame_max = max_id;
    for (const auto& f : (*frames_)[k].features) {
      ASSERT_TRUE(ids.insert(f.id).second) << "id " << f.id << " twice in frame " << k;
      const auto it = last.find(f.id);
      if (it == last.end()) {
        EXPECT_EQ(f.track_length, 1u) << "new id " << f.id;
        EXPECT_GT(f.id, max_id) << "id " << f.id << " reused or not increasing";
      } else {
        EXPECT_EQ(it->second.first + 1, k) << "id " << f.id << " came back after a gap";
        EXPECT_EQ(f.track_length, it->second.second + 1) << "id " << f.id;
      }
      last[f.id] = {k, f.track_length};
      frame_max = std::max(frame_max, f.id);
    }
    max_id = frame_max;
  }
}

TEST_F(FrontendEuroc, BearingsAreUnitAndReprojectToTheirPixels) {
  double worst_norm = 0.0, worst_px = 0.0;
  for (const auto& r : *frames_) {
    for (const auto& f : r.features) {
      worst_norm = std::max(worst_norm, std::abs(f.bearing_C.norm() - 1.0));
      Eigen::Vector2d uv;
      ASSERT_EQ(camera_->project(f.bearing_C, &uv), ProjectionStatus::kOk);
      worst_px = std::max(worst_px, (uv - f.uv).norm());
    }
  }
  EXPECT_LT(worst_norm, 1e-12);
  EXPECT_LT(worst_px, 1e-6);
}

}  // namespace
}  // namespace twinslam::tracking

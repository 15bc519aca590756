// A moving sequence with exact ground truth: a camera turning through a textured panorama at infinity (yaw 1 deg per
// frame = 20 deg/s, five times the mean turn rate of city-loops, plus a pitch/roll wobble of up to 0.6 deg per frame),
// 60 frames of 640x400 at 20 Hz, with the exact gyro rotation. Every track is checked
// against the true position of the pixel where it was first detected, as the acceptance asks for simulated
// images: >= 120 features per frame, < 1 % of tracks more than 2 px from the truth, median track length >= 10.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include <opencv2/imgproc.hpp>

#include "twinslam/geometry/so3.hpp"
#include "twinslam/tracking/frontend.hpp"

namespace twinslam::tracking {
namespace {

TEST(FrontendSequence, TracksFollowTheTruePixelsThroughAPanningSequence) {
  CameraIntrinsics in;
  in.width = 640;
  in.height = 400;
  in.fu = in.fv = 400.0;
  in.cu = 319.5;
  in.cv = 199.5;
  Eigen::Matrix3d K, K_T;
  K << 400, 0, 319.5, 0, 400, 199.5, 0, 0, 1;
  K_T << 400, 0, 1699.5, 0, 400, 699.5, 0, 0, 1;  // the panorama's own pinhole
  cv::Mat noise(1400, 3400, CV_32F), panorama;
  cv::RNG rng(21);
  rng.fill(noise, cv::RNG::UNIFORM, 0.0, 1.0);
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), 2.0);
  cv::normalize(noise, panorama, 0, 255, cv::NORM_MINMAX, CV_8U);

  Frontend frontend(make_camera(in));
  std::map<std::uint64_t, Eigen::Vector3d> first_ray_T;  // id -> bearing in the panorama frame at first detection
  Eigen::Matrix3d R_T_cam = geometry::so3_exp(Eigen::Vector3d(0.0, -0.6, 0.0));
  std::vector<int> counts;
  std::vector<std::uint32_t> final_lengths;
  int checked = 0, wrong = 0, lost_klt = 0, lost_fb = 0, lost_ransac = 0, pruned = 0;
  for (int k = 0; k < 60; ++k) {
    const Eigen::Matrix3d R_step = geometry::so3_exp(
        Eigen::Vector3d(0.01 * std::sin(0.3 * k), 1.0 * M_PI / 180.0, 0.01 * std::cos(0.2 * k)));
    if (k > 0) R_T_cam = R_T_cam * R_step;  // R_step = R_prev_curr: the camera's turn since the previous frame
    const Eigen::Matrix3d H = K * R_T_cam.transpose() * K_T.inverse();
    cv::Mat Hc(3, 3, CV_64F), img;
    for (int i = 0; i < 9; ++i) Hc.at<double>(i / 3, i % 3) = H(i / 3, i % 3);
    cv::warpPerspective(panorama, img, Hc, cv::Size(640, 400));

    const FrameResult r = frontend.track(k * 50'000'000LL, img, k > 0 ? &R_step : nullptr);
    if (k > 0) counts.push_back(static_cast<int>(r.features.size()));
    lost_klt += r.stats.lost_klt;
    lost_fb += r.stats.lost_fb;
    lost_ransac += r.stats.lost_ransac;
    pruned += r.stats.pruned;
    for (const auto& f : r.features) {
      if (f.track_length == 1) {
        first_ray_T[f.id] = R_T_cam * K.inverse() * f.uv.homogeneous();
        continue;
      }
      const Eigen::Vector2d truth = (K * R_T_cam.transpose() * first_ray_T.at(f.id)).hnormalized();
      ++checked;
      if ((f.uv - truth).norm() > 2.0) ++wrong;
    }
    if (k == 59) {
      for (const auto& f : r.features) final_lengths.push_back(f.track_length);
    }
  }
  std::sort(counts.begin(), counts.end());
  std::sort(final_lengths.begin(), final_lengths.end());
  const int median_count = counts[counts.size() / 2];
  const std::uint32_t median_length = final_lengths[final_lengths.size() / 2];
  std::printf("features per frame: min %d median %d; wrong tracks %d of %d; median track length at the end %u; "
              "lost: klt %d fb %d ransac %d pruned %d\n",
              counts.front(), median_count, wrong, checked, median_length, lost_klt, lost_fb, lost_ransac, pruned);
  EXPECT_GE(median_count, 120);
  EXPECT_LT(wrong, checked / 100 + 1);
  EXPECT_GE(median_length, 10u);
}

// The same for a 200-degree fisheye (ideal equidistant, 183 px/rad), looking into a textured sphere at infinity (an
// equirectangular map): features beyond 90 degrees from the optical axis are tracked, and the RANSAC on bearings
// keeps them.
TEST(FrontendSequence, FisheyeTracksBeyond90DegreesFollowTheTruePixels) {
  CameraIntrinsics in;
  in.distortion = DistortionModel::kEquidistant;
  in.width = 640;
  in.height = 400;
  in.fu = in.fv = 320.0 / (100.0 * M_PI / 180.0);  // +-100 deg across the width
  in.cu = 319.5;
  in.cv = 199.5;
  const std::shared_ptr<const CameraModel> camera = make_camera(in);
  cv::Mat noise(600, 1200, CV_32F), sphere;  // 0.3 deg per texel: longitude across, latitude down
  cv::RNG rng(23);
  rng.fill(noise, cv::RNG::UNIFORM, 0.0, 1.0);
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), 1.5);
  cv::normalize(noise, sphere, 0, 255, cv::NORM_MINMAX, CV_8U);
  std::vector<Eigen::Vector3d> rays(640 * 400);  // bearing of every pixel, once
  for (int v = 0; v < 400; ++v) {
    for (int u = 0; u < 640; ++u) ASSERT_TRUE(camera->unproject(Eigen::Vector2d(u, v), &rays[v * 640 + u]));
  }
  auto render = [&](const Eigen::Matrix3d& R_S_cam) {  // camera orientation in the sphere's frame
    cv::Mat1f map_u(400, 640), map_v(400, 640);
    for (int i = 0; i < 640 * 400; ++i) {
      const Eigen::Vector3d f = R_S_cam * rays[i];
      map_u(i / 640, i % 640) = static_cast<float>((std::atan2(f.x(), f.z()) + M_PI) / (2 * M_PI) * 1200.0 - 0.5);
      const double latitude = std::asin(std::clamp(f.y(), -1.0, 1.0));
      map_v(i / 640, i % 640) = static_cast<float>((latitude + M_PI / 2) / M_PI * 600.0 - 0.5);
    }
    cv::Mat img;
    cv::remap(sphere, img, map_u, map_v, cv::INTER_LINEAR, cv::BORDER_WRAP);
    return img;
  };

  Frontend frontend(camera);
  std::map<std::uint64_t, Eigen::Vector3d> first_ray_S;
  Eigen::Matrix3d R_S_cam = Eigen::Matrix3d::Identity();
  int checked = 0, wrong = 0, beyond_90 = 0, fewest = 1000;
  for (int k = 0; k < 40; ++k) {
    const Eigen::Matrix3d R_step = geometry::so3_exp(
        Eigen::Vector3d(0.01 * std::sin(0.3 * k), 1.0 * M_PI / 180.0, 0.01 * std::cos(0.2 * k)));
    if (k > 0) R_S_cam = R_S_cam * R_step;
    const FrameResult r = frontend.track(k * 50'000'000LL, render(R_S_cam), k > 0 ? &R_step : nullptr);
    if (k > 0) fewest = std::min(fewest, static_cast<int>(r.features.size()));
    for (const auto& f : r.features) {
      if (f.track_length == 1) {
        first_ray_S[f.id] = R_S_cam * f.bearing_C;
        continue;
      }
      Eigen::Vector2d truth;
      ASSERT_EQ(camera->project(R_S_cam.transpose() * first_ray_S.at(f.id), &truth), ProjectionStatus::kOk);
      ++checked;
      if ((f.uv - truth).norm() > 2.0) ++wrong;
      if (f.bearing_C.z() < 0.0) ++beyond_90;
    }
  }
  std::printf("fisheye: fewest features %d; wrong tracks %d of %d; %d track observations beyond 90 deg\n", fewest,
              wrong, checked, beyond_90);
  EXPECT_GE(fewest, 120);
  EXPECT_LT(wrong, checked / 100 + 1);
  EXPECT_GT(beyond_90, 200);
}

}  // namespace
}  // namespace twinslam::tracking

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

}  // namespace
}  // namespace twinslam::tracking

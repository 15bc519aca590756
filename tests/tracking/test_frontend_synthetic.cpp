// The frontend on synthetic images with known motion: a sub-pixel image shift, and a large camera rotation rendered
// by the homography K R K^-1 of a pinhole camera, tracked with and without the gyro prediction.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include <opencv2/imgproc.hpp>

#include "twinslam/core/error.hpp"
#include "twinslam/geometry/so3.hpp"
#include "twinslam/tracking/frontend.hpp"

namespace twinslam::tracking {
namespace {

std::shared_ptr<const CameraModel> pinhole_640x400() {
  CameraIntrinsics in;
  in.width = 640;
  in.height = 400;
  in.fu = in.fv = 400.0;
  in.cu = 319.5;
  in.cv = 199.5;
  return make_camera(in);
}

// Smooth random texture (seeded): blurred uniform noise stretched to the full 8-bit range.
cv::Mat texture(int width, int height, unsigned seed) {
  cv::Mat noise(height, width, CV_32F);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::UNIFORM, 0.0, 1.0);
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), 2.0);
  cv::Mat out;
  cv::normalize(noise, out, 0, 255, cv::NORM_MINMAX, CV_8U);
  return out;
}

std::map<std::uint64_t, Eigen::Vector2d> by_id(const FrameResult& r) {
  std::map<std::uint64_t, Eigen::Vector2d> m;
  for (const auto& f : r.features) m[f.id] = f.uv;
  return m;
}

TEST(FrontendSynthetic, SubpixelShiftIsMeasuredWithinATenthOfAPixel) {
  const cv::Mat img0 = texture(640, 400, 7);
  const Eigen::Vector2d shift(3.3, -2.7);  // px
  const cv::Mat A = (cv::Mat_<double>(2, 3) << 1, 0, shift.x(), 0, 1, shift.y());
  cv::Mat img1;
  cv::warpAffine(img0, img1, A, img0.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT_101);

  Frontend frontend(pinhole_640x400());
  const FrameResult r0 = frontend.track(0, img0);
  const FrameResult r1 = frontend.track(50'000'000, img1);
  EXPECT_EQ(static_cast<int>(r0.features.size()), frontend.config().max_features);
  const auto p0 = by_id(r0);
  int checked = 0;
  auto camera = pinhole_640x400();
  for (const auto& f : r1.features) {
    // Within half a KLT window plus the shift of the edge, warpAffine's border fill is not a shifted image.
    if (f.track_length != 2 || !camera->in_image(f.uv, frontend.config().klt_window_px / 2 + 4)) continue;
    ++checked;
    EXPECT_LT((f.uv - p0.at(f.id) - shift).norm(), 0.1) << "feature " << f.id << " at " << f.uv.transpose();
  }
  EXPECT_GE(checked, 140);  // almost all of the 180 survive a 4 px shift, a few are near the edge
}

TEST(FrontendSynthetic, ClaheKeepsTracksThroughAnExposureDrop) {
  // The shifted frame is also 45 % darker with less contrast, as when auto-exposure reacts to a bright window.
  const cv::Mat img0 = texture(640, 400, 9);
  const cv::Mat A = (cv::Mat_<double>(2, 3) << 1, 0, 1.6, 0, 1, 0.8);
  cv::Mat img1;
  cv::warpAffine(img0, img1, A, img0.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT_101);
  img1.convertTo(img1, CV_8U, 0.55, 10.0);
  FrontendConfig config;
  config.clahe = true;
  Frontend frontend(pinhole_640x400(), config);
  const FrameResult r0 = frontend.track(0, img0);
  const FrameResult r1 = frontend.track(50'000'000, img1);
  ASSERT_EQ(static_cast<int>(r0.features.size()), config.max_features);
  EXPECT_GE(r1.stats.tracked, 150) << "lost: klt " << r1.stats.lost_klt << " fb " << r1.stats.lost_fb << " ransac "
                                   << r1.stats.lost_ransac;
}

struct RotationRun {
  int tracked = 0;
  int trackable = 0;             // features whose true position in frame 1 lies inside the image
  int lost = 0;                  // trackable features that did not survive
  double median_error_px = 0.0;  // of the surviving tracks against the true homography
  double max_error_px = 0.0;
};

// Frame 0 and frame 1 view the same infinitely far scene before and after the camera turned by R_prev_curr, so the
// image moves by the homography x_curr = K R_prev_curr^T K^-1 x_prev.
RotationRun run_rotation(bool with_prediction) {
  const auto camera = pinhole_640x400();
  // 13 deg, mostly pan and tilt (translational KLT cannot follow a large roll of its window, prediction or not).
  const Eigen::Matrix3d R_prev_curr = geometry::so3_exp(Eigen::Vector3d(0.10, 0.20, 0.03));
  Eigen::Matrix3d K;
  K << 400, 0, 319.5, 0, 400, 199.5, 0, 0, 1;
  const Eigen::Matrix3d H = K * R_prev_curr.transpose() * K.inverse();
  // Both frames view one large textured plane at infinity (a panorama with its own pinhole K_T), so the newly seen
  // area of frame 1 holds real texture consistent with the homography, not a border fill.
  const cv::Mat panorama = texture(1400, 1000, 11);
  Eigen::Matrix3d K_T;
  K_T << 400, 0, 699.5, 0, 400, 499.5, 0, 0, 1;
  auto render = [&](const Eigen::Matrix3d& R_T_cam) {  // the camera's orientation relative to the panorama's
    const Eigen::Matrix3d H_cam_T = K * R_T_cam.transpose() * K_T.inverse();
    cv::Mat Hc(3, 3, CV_64F), out;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) Hc.at<double>(i, j) = H_cam_T(i, j);
    }
    cv::warpPerspective(panorama, out, Hc, cv::Size(640, 400), cv::INTER_LINEAR, cv::BORDER_CONSTANT);
    return out;
  };
  const cv::Mat img0 = render(Eigen::Matrix3d::Identity());
  const cv::Mat img1 = render(R_prev_curr);

  FrontendConfig config;
  config.min_eigenvalue = 0.0;
  config.min_distance_px = 8.0;  // the turn compresses part of the view: few tracks should be lost to pruning
  Frontend frontend(camera, config);
  const FrameResult r0 = frontend.track(0, img0);
  const FrameResult r1 = frontend.track(50'000'000, img1, with_prediction ? &R_prev_curr : nullptr);
  EXPECT_EQ(r1.stats.predicted, with_prediction);

  RotationRun run;
  const auto p0 = by_id(r0);
  const auto p1 = by_id(r1);
  std::vector<double> errors;
  for (const auto& f : r1.features) {
    if (f.track_length != 2) continue;
    ++run.tracked;
    errors.push_back((f.uv - (H * p0.at(f.id).homogeneous()).hnormalized()).norm());
  }
  for (const auto& f : r0.features) {
    if (!camera->in_image((H * f.uv.homogeneous()).hnormalized(), 15.0)) continue;
    ++run.trackable;
    if (!p1.count(f.id)) ++run.lost;
  }
  if (!errors.empty()) {
    std::sort(errors.begin(), errors.end());
    run.median_error_px = errors[errors.size() / 2];
    run.max_error_px = errors.back();
  }
  return run;
}

TEST(FrontendSynthetic, GyroPredictionKeepsTracksThroughALargeRotation) {
  const RotationRun with = run_rotation(true);
  const RotationRun without = run_rotation(false);
  // About 90 px of image motion: beyond the reach of 3 pyramid levels without a guess.
  ASSERT_EQ(with.trackable, without.trackable);
  ASSERT_GE(with.trackable, 100);
  EXPECT_LE(with.lost, with.trackable / 10);
  EXPECT_GT(without.lost, 3 * with.lost + 20);
  EXPECT_GT(with.tracked, without.tracked);
  // Translational KLT on a patch that the turn also slightly skews and scales, in an image resampled at varying
  // sub-pixel phase: sub-pixel, not exact (the pure shift above is exact to 0.1 px).
  EXPECT_LT(with.median_error_px, 0.3);
  EXPECT_LT(with.max_error_px, 1.0);
  std::printf("rotation 13 deg, %d trackable: with prediction tracked %d lost %d (median error %.3f px, max %.3f px); "
              "without: tracked %d lost %d\n",
              with.trackable, with.tracked, with.lost, with.median_error_px, with.max_error_px, without.tracked,
              without.lost);
}

TEST(FrontendSynthetic, BadInputIsRejectedWithAMessage) {
  Frontend frontend(pinhole_640x400());
  EXPECT_THROW(frontend.track(0, cv::Mat(400, 640, CV_8UC3, cv::Scalar(0))), InputError);
  EXPECT_THROW(frontend.track(0, cv::Mat(480, 752, CV_8UC1, cv::Scalar(0))), InputError);
  frontend.track(100, texture(640, 400, 3));
  EXPECT_THROW(frontend.track(100, texture(640, 400, 3)), InputError);  // stamp not after the previous
  Eigen::Matrix3d nan_rotation = Eigen::Matrix3d::Identity();
  nan_rotation(0, 0) = std::nan("");
  EXPECT_THROW(frontend.track(200, texture(640, 400, 3), &nan_rotation), InputError);
  EXPECT_THROW(Frontend(nullptr), InputError);
}

TEST(FrontendConfig, ValidateNamesTheBadKey) {
  FrontendConfig config;
  EXPECT_NO_THROW(config.validate());
  config.klt_window_px = 20;  // must be odd
  try {
    config.validate("tracking.yaml");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("tracking.yaml"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("klt_window_px"), std::string::npos);
  }
  config = FrontendConfig{};
  config.max_features = 0;
  EXPECT_THROW(config.validate(), InputError);
  config = FrontendConfig{};
  config.ransac_confidence = 1.0;
  EXPECT_THROW(config.validate(), InputError);
  // The reference alignment, presmoothing and span RANSAC keys (issue 6).
  config = FrontendConfig{};
  config.ref_window_px = 0;  // off is allowed
  EXPECT_NO_THROW(config.validate());
  config.ref_window_px = 16;
  EXPECT_THROW(config.validate(), InputError);
  config = FrontendConfig{};
  config.ref_min_zncc = 1.0;
  EXPECT_THROW(config.validate(), InputError);
  config = FrontendConfig{};
  config.presmooth_sigma_px = -1.0;
  EXPECT_THROW(config.validate(), InputError);
  config = FrontendConfig{};
  config.ransac_span_frames = 8;
  EXPECT_THROW(config.validate(), InputError);
}

}  // namespace
}  // namespace twinslam::tracking

// Quality of the window's landmarks (window_landmarks): what registration filters its source cloud by.
#include <gtest/gtest.h>

#include "twinslam/estimator/sliding_window_state.hpp"

namespace twinslam::estimator {
namespace {

// A window of keyframes on a line along x (identity attitude, camera = body), each seeing the point p_L.
WindowState window_seeing(const Eigen::Vector3d& p_L, const std::vector<double>& x_m, double parallax_at_init_deg) {
  WindowState s;
  s.config.T_BC = Eigen::Isometry3d::Identity();
  for (std::size_t i = 0; i < x_m.size(); ++i) {
    auto f = std::make_unique<WindowFrame>();
    f->id = static_cast<std::int64_t>(i);
    f->keyframe = true;
    f->pose = {x_m[i], 0.0, 0.0, 0.0, 0.0, 0.0, 1.0};
    f->bearings[7] = (p_L - Eigen::Vector3d(x_m[i], 0.0, 0.0)).normalized();
    s.frames.push_back(std::move(f));
  }
  WindowLandmark lm;
  lm.lm.id = 7;
  lm.lm.anchor_keyframe = 0;
  lm.lm.f_Ca = s.frames.front()->bearings.at(7);
  lm.rho = lm.lm.rho = 1.0 / (p_L - Eigen::Vector3d(x_m[0], 0.0, 0.0)).norm();
  lm.parallax_deg = parallax_at_init_deg;
  s.landmarks.emplace(7, lm);
  return s;
}

TEST(LandmarkQuality, ParallaxIsThatOfTheKeyframesObservingItNowNotAtTriangulation) {
  // Triangulated from the first two keyframes 0.5 m apart (1.4 deg at 20 m), then seen over 4 m (11 deg): as well
  // determined as any point, so full quality. Judged by its triangulation parallax it stayed at 0.29 for life, and
  // registration (min_quality 0.5) had too few points for the first minute of city-loops.
  const Eigen::Vector3d p_L(0.0, 0.0, 20.0);
  const auto out = window_landmarks(window_seeing(p_L, {0.0, 0.5, 1.0, 2.0, 3.0, 4.0}, 1.43));
  ASSERT_EQ(out.size(), 1u);
  EXPECT_DOUBLE_EQ(out[0].quality, 1.0);
  EXPECT_LT((out[0].p_L - p_L).norm(), 1e-9);
}

TEST(LandmarkQuality, ShortBaselineAndFewObserversStayPoor) {
  // Two observers 0.5 m apart at 20 m: 1.4 deg of parallax (q 0.29) and one observation beyond the anchor (q 0.25).
  const auto out = window_landmarks(window_seeing(Eigen::Vector3d(0.0, 0.0, 20.0), {0.0, 0.5}, 1.43));
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR(out[0].quality, 0.25 * std::atan(0.5 / 20.0) * 180.0 / M_PI / 5.0, 1e-6);
  // A landmark whose anchor left the window is not reported.
  WindowState s = window_seeing(Eigen::Vector3d(0.0, 0.0, 20.0), {0.0, 0.5, 1.0}, 1.43);
  s.frames.pop_front();
  EXPECT_TRUE(window_landmarks(s).empty());
}

}  // namespace
}  // namespace twinslam::estimator

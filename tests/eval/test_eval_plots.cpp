// Evaluation figures with several estimates in one figure (what `twinslam bench` will draw).
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "synthetic.hpp"
#include "twinslam/eval/plots.hpp"
#include "twinslam/plot/plot.hpp"

namespace twinslam::eval {
namespace {
namespace fs = std::filesystem;

bool has_color(const cv::Mat& img, plot::Rgb c) {
  for (int y = 0; y < img.rows; ++y) {
    for (int x = 0; x < img.cols; ++x) {
      const auto& p = img.at<cv::Vec3b>(y, x);
      if (p[0] == c.b && p[1] == c.g && p[2] == c.r) return true;
    }
  }
  return false;
}

TEST(EvalPlots, SeveralEstimatesShareOneFigure) {
  const Trajectory gt = test::helix(3000, 100'000'000);  // 300 s, ~300 m
  Trajectory drifting = gt, offset = gt;
  for (std::size_t k = 0; k < gt.size(); ++k) {
    drifting.poses[k].T_XB.translation() *= 1.0 + 2e-5 * static_cast<double>(k);
    offset.poses[k].T_XB.translation() += Eigen::Vector3d(0.5, -0.5, 0.2);
  }
  const EvalResult a = evaluate(gt, drifting, {});
  EvalConfig posyaw;
  posyaw.align = AlignMode::PosYaw;
  const EvalResult b = evaluate(gt, offset, posyaw);
  // Kept in the build folder so a person can look at them.
  const fs::path dir = fs::path(TWINSLAM_BIN_DIR) / ".." / "test-output" / "eval-plots";
  const auto files = write_eval_plots(dir, gt, {{"vio", &a}, {"vio-twin", &b}});
  ASSERT_EQ(files.size(), 6u);
  for (const auto& f : files) {
    const cv::Mat img = cv::imread(f.string());
    ASSERT_FALSE(img.empty()) << f;
    EXPECT_TRUE(has_color(img, plot::palette(0))) << f;  // first estimate
    EXPECT_TRUE(has_color(img, plot::palette(1))) << f;  // second estimate
  }
}

}  // namespace
}  // namespace twinslam::eval

// The plotting library draws what it is given where it belongs.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "twinslam/core/error.hpp"
#include "twinslam/plot/plot.hpp"

namespace twinslam::plot {
namespace {

int count_color(const cv::Mat& img, Rgb c) {
  int n = 0;
  for (int y = 0; y < img.rows; ++y) {
    for (int x = 0; x < img.cols; ++x) {
      const auto& p = img.at<cv::Vec3b>(y, x);
      if (p[0] == c.b && p[1] == c.g && p[2] == c.r) ++n;
    }
  }
  return n;
}

TEST(Plot, LineIsDrawnInsideTheAxes) {
  LinePlot p;
  p.title = "t";
  p.lines.push_back({"red", {0.0, 10.0}, {1.0, 1.0}, Rgb{255, 0, 0}, 3});
  const cv::Mat img = p.render();
  EXPECT_EQ(img.cols, 1000);
  EXPECT_EQ(img.rows, 700);
  EXPECT_GT(count_color(img, Rgb{255, 0, 0}), 500);  // a ~870 px long, 3 px thick line (plus the legend sample)
}

TEST(Plot, AScatterDrawsDotsAndNoLineBetweenThem) {
  LinePlot p;
  // Two dots inside the axes (and two at the corners, which set the range and are clipped).
  Line dots{"", {0.0, 3.0, 7.0, 10.0}, {0.0, 7.0, 3.0, 10.0}, Rgb{0, 160, 0}, 1};
  dots.marker_px = 4;
  p.lines.push_back(dots);
  const cv::Mat img = p.render();
  const int n = count_color(img, Rgb{0, 160, 0});
  EXPECT_GT(n, 2 * 20);   // two filled dots of radius 4 px (about 30 px of exact colour each)
  EXPECT_LT(n, 4 * 60);   // and no 2000 px of polyline between them
}

TEST(Plot, EqualAspectKeepsMetresSquare) {
  // A 10 m x 10 m square outline: drawn with equal aspect, its pixel width and height match.
  LinePlot p;
  p.equal_aspect = true;
  p.lines.push_back({"", {0, 10, 10, 0, 0}, {0, 0, 10, 10, 0}, Rgb{0, 0, 255}, 1});
  const cv::Mat img = p.render();
  int xmin = img.cols, xmax = 0, ymin = img.rows, ymax = 0;
  for (int y = 0; y < img.rows; ++y) {
    for (int x = 0; x < img.cols; ++x) {
      const auto& px = img.at<cv::Vec3b>(y, x);
      if (px[0] > 200 && px[1] < 80 && px[2] < 80) {
        xmin = std::min(xmin, x), xmax = std::max(xmax, x), ymin = std::min(ymin, y), ymax = std::max(ymax, y);
      }
    }
  }
  EXPECT_NEAR(xmax - xmin, ymax - ymin, 2);
}

TEST(Plot, BoxPlotDrawsOneBoxPerSeriesAndCategory) {
  BoxPlot p;
  p.categories = {"10", "50"};
  p.series.push_back({"a", Rgb{0, 160, 0}, {{1, 2, 3, 4, 5}, {2, 3, 4}}});
  const cv::Mat img = p.render();
  EXPECT_GT(count_color(img, Rgb{0, 160, 0}), 100);  // box outlines, medians, whiskers
}

TEST(Plot, UnwritablePathIsAnInputError) {
  LinePlot p;
  EXPECT_THROW(p.save("/nonexistent-folder/x.png"), InputError);
}

}  // namespace
}  // namespace twinslam::plot

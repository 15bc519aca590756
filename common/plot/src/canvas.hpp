#pragma once
// Shared drawing of the frame around a plot: data-to-pixel mapping, tick choice, axes, grid, labels, legend.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

#include "twinslam/plot/plot.hpp"

namespace twinslam::plot::detail {

cv::Scalar bgr(Rgb c);

// The plot area in pixels and the data range it shows.
struct Frame {
  cv::Rect area;
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  // Sub-pixel coordinates relative to `area`, with cv's 4-bit fixed point (shift = kShift) for smooth lines.
  cv::Point to_px(double x, double y) const;
};
constexpr int kShift = 4;

// Layout of a figure of the given size with margins for ticks, labels and title.
cv::Rect plot_area(int width, int height);

// "Nice" tick positions (1, 2, 5 x 10^k steps) covering [lo, hi], about `target` of them, and their decimals.
std::vector<double> nice_ticks(double lo, double hi, int target, int* decimals);

// Widens [lo, hi] to whole ticks and returns the ticks; a zero range is widened to +-1 around its value.
std::vector<double> widen_to_ticks(double& lo, double& hi, int target, int* decimals);

// White canvas, title, axis labels, grid and numeric y ticks; x ticks numeric (x_names empty) or named at 1..n.
cv::Mat draw_frame(int width, int height, const Frame& f, const std::string& title, const std::string& xlabel,
                   const std::string& ylabel, const std::vector<double>& xticks, int xdec,
                   const std::vector<double>& yticks, int ydec, const std::vector<std::string>& x_names = {});

// Legend box in the top-right corner of the plot area.
void draw_legend(cv::Mat& img, const cv::Rect& area, const std::vector<std::pair<std::string, Rgb>>& entries);

void write_png(const cv::Mat& img, const std::filesystem::path& png);

}  // namespace twinslam::plot::detail

#pragma once
// Figures readable without the code: title, axis labels with units, numeric tick labels, grid, legend.
// render() draws into an 8-bit BGR image; save() writes a PNG (creating no folders) and throws InputError on failure.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace twinslam::plot {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
};

// Distinguishable colours for estimates (index 0, 1, ...); ground truth is drawn in kBlack.
Rgb palette(std::size_t index);
constexpr Rgb kBlack{0, 0, 0};

struct Line {
  std::string label;  // legend entry; empty = not in the legend
  std::vector<double> x, y;
  Rgb color;
  int thickness = 2;  // [px]
  int marker_px = 0;  // > 0: a scatter: each point a dot of this radius [px], no line between them
};

struct LinePlot {
  std::string title, xlabel, ylabel;
  bool equal_aspect = false;  // one metre is as long on both axes (maps, not time series)
  bool y_from_zero = false;   // errors: keep 0 on the y axis
  int width = 1000, height = 700;  // [px]
  std::vector<Line> lines;

  cv::Mat render() const;
  void save(const std::filesystem::path& png) const;
};

// One series of boxes (e.g. one estimate), one box per category (e.g. segment length).
struct BoxSeries {
  std::string label;
  Rgb color;
  std::vector<std::vector<double>> samples;  // samples[category]; an empty list draws no box
};

// Tukey box plot: box from the 25th to the 75th percentile, median line, whiskers to the furthest sample within
// 1.5 IQR, samples beyond drawn as dots.
struct BoxPlot {
  std::string title, xlabel, ylabel;
  std::vector<std::string> categories;
  std::vector<BoxSeries> series;
  int width = 1000, height = 700;

  cv::Mat render() const;
  void save(const std::filesystem::path& png) const;
};

}  // namespace twinslam::plot

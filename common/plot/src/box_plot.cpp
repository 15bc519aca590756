#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "canvas.hpp"

namespace twinslam::plot {
namespace {

double quantile_sorted(const std::vector<double>& v, double q) {
  const double pos = q * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(pos));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (pos - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

struct Box {
  double q1, median, q3, whisker_lo, whisker_hi;
  std::vector<double> outliers;
};

Box tukey(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  Box b{quantile_sorted(v, 0.25), quantile_sorted(v, 0.5), quantile_sorted(v, 0.75), 0, 0, {}};
  const double iqr = b.q3 - b.q1, lo_fence = b.q1 - 1.5 * iqr, hi_fence = b.q3 + 1.5 * iqr;
  b.whisker_lo = b.q1;
  b.whisker_hi = b.q3;
  for (double x : v) {
    if (x < lo_fence || x > hi_fence) {
      b.outliers.push_back(x);
    } else {
      b.whisker_lo = std::min(b.whisker_lo, x);
      b.whisker_hi = std::max(b.whisker_hi, x);
    }
  }
  return b;
}

cv::Scalar lighter(Rgb c) {  // box fill: the series colour mixed with white
  return cv::Scalar(0.4 * c.b + 153, 0.4 * c.g + 153, 0.4 * c.r + 153);
}

}  // namespace

cv::Mat BoxPlot::render() const {
  // Boxes first (the y range includes outliers), then the frame, then the drawing.
  std::vector<std::vector<Box>> boxes(series.size());
  double ylo = 0.0, yhi = 0.0;  // errors: keep 0 in view
  for (std::size_t s = 0; s < series.size(); ++s) {
    for (std::size_t c = 0; c < categories.size(); ++c) {
      if (c >= series[s].samples.size() || series[s].samples[c].empty()) {
        boxes[s].push_back({0, 0, 0, 0, 0, {}});
        continue;
      }
      boxes[s].push_back(tukey(series[s].samples[c]));
      for (double v : series[s].samples[c]) {
        ylo = std::min(ylo, v);
        yhi = std::max(yhi, v);
      }
    }
  }
  detail::Frame f;
  f.area = detail::plot_area(width, height);
  f.x0 = 0.5;
  f.x1 = static_cast<double>(categories.size()) + 0.5;
  f.y0 = ylo;
  f.y1 = yhi * 1.05;
  int ydec = 0, xdec = 0;
  const std::vector<double> yticks = detail::widen_to_ticks(f.y0, f.y1, 8, &ydec);
  std::vector<double> xticks;
  for (std::size_t c = 0; c < categories.size(); ++c) xticks.push_back(static_cast<double>(c + 1));
  cv::Mat img = detail::draw_frame(width, height, f, title, xlabel, ylabel, xticks, xdec, yticks, ydec, categories);
  cv::Mat inside = img(f.area);

  const double slot = 0.8 / static_cast<double>(std::max<std::size_t>(series.size(), 1));  // category width share
  std::vector<std::pair<std::string, Rgb>> legend;
  for (std::size_t s = 0; s < series.size(); ++s) {
    const cv::Scalar ink = detail::bgr(series[s].color);
    for (std::size_t c = 0; c < categories.size(); ++c) {
      if (c >= series[s].samples.size() || series[s].samples[c].empty()) continue;
      const Box& b = boxes[s][c];
      const double centre = static_cast<double>(c + 1) - 0.4 + slot * (static_cast<double>(s) + 0.5);
      const double half = 0.35 * slot;
      const cv::Point tl = f.to_px(centre - half, b.q3), br = f.to_px(centre + half, b.q1);
      const cv::Rect body(tl.x >> detail::kShift, tl.y >> detail::kShift,
                          std::max(1, (br.x - tl.x) >> detail::kShift), std::max(1, (br.y - tl.y) >> detail::kShift));
      cv::rectangle(inside, body, lighter(series[s].color), cv::FILLED);
      cv::rectangle(inside, body, ink, 1);
      const auto seg = [&](double xa, double ya, double xb, double yb, int thick) {
        cv::line(inside, f.to_px(xa, ya), f.to_px(xb, yb), ink, thick, cv::LINE_AA, detail::kShift);
      };
      seg(centre - half, b.median, centre + half, b.median, 2);
      seg(centre, b.q3, centre, b.whisker_hi, 1);
      seg(centre, b.q1, centre, b.whisker_lo, 1);
      seg(centre - 0.5 * half, b.whisker_hi, centre + 0.5 * half, b.whisker_hi, 1);
      seg(centre - 0.5 * half, b.whisker_lo, centre + 0.5 * half, b.whisker_lo, 1);
      for (double o : b.outliers) {
        cv::circle(inside, f.to_px(centre, o), 2 << detail::kShift, ink, 1, cv::LINE_AA, detail::kShift);
      }
    }
    if (!series[s].label.empty()) legend.emplace_back(series[s].label, series[s].color);
  }
  detail::draw_legend(img, f.area, legend);
  return img;
}

void BoxPlot::save(const std::filesystem::path& png) const { detail::write_png(render(), png); }

}  // namespace twinslam::plot

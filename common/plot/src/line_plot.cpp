#include <algorithm>
#include <cmath>
#include <limits>

#include <opencv2/imgproc.hpp>

#include "canvas.hpp"

namespace twinslam::plot {
namespace {

struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    if (!std::isfinite(v)) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  bool valid() const { return lo <= hi; }
};

}  // namespace

cv::Mat LinePlot::render() const {
  Range xr, yr;
  for (const auto& l : lines) {
    for (double v : l.x) xr.add(v);
    for (double v : l.y) yr.add(v);
  }
  if (!xr.valid()) xr = {0.0, 1.0};
  if (!yr.valid()) yr = {0.0, 1.0};
  if (y_from_zero) yr.lo = std::min(yr.lo, 0.0);
  if (xr.hi == xr.lo) xr = {xr.lo - 1.0, xr.hi + 1.0};
  if (yr.hi == yr.lo) yr = {yr.lo - 1.0, yr.hi + 1.0};

  detail::Frame f;
  f.area = detail::plot_area(width, height);
  std::vector<double> xticks, yticks;
  int xdec = 0, ydec = 0;
  if (equal_aspect) {
    // Same metres per pixel on both axes, centred on the data, 4 % margin.
    const double upp = 1.04 * std::max((xr.hi - xr.lo) / f.area.width, (yr.hi - yr.lo) / f.area.height);
    const double cx = 0.5 * (xr.lo + xr.hi), cy = 0.5 * (yr.lo + yr.hi);
    f.x0 = cx - 0.5 * upp * f.area.width;
    f.x1 = cx + 0.5 * upp * f.area.width;
    f.y0 = cy - 0.5 * upp * f.area.height;
    f.y1 = cy + 0.5 * upp * f.area.height;
    xticks = detail::nice_ticks(f.x0, f.x1, 10, &xdec);
    yticks = detail::nice_ticks(f.y0, f.y1, 8, &ydec);
    xdec = ydec = std::max(xdec, ydec);  // same axis units, same precision
  } else {
    f.x0 = xr.lo;
    f.x1 = xr.hi;
    xticks = detail::nice_ticks(f.x0, f.x1, 10, &xdec);
    f.y0 = yr.lo;
    f.y1 = yr.hi;
    yticks = detail::widen_to_ticks(f.y0, f.y1, 8, &ydec);
  }
  cv::Mat img = detail::draw_frame(width, height, f, title, xlabel, ylabel, xticks, xdec, yticks, ydec);
  cv::Mat inside = img(f.area);  // drawing into the plot area's view clips lines to it
  std::vector<std::pair<std::string, Rgb>> legend;
  for (const auto& l : lines) {
    std::vector<cv::Point> pts;
    pts.reserve(l.x.size());
    for (std::size_t i = 0; i < l.x.size() && i < l.y.size(); ++i) pts.push_back(f.to_px(l.x[i], l.y[i]));
    if (l.marker_px > 0) {
      for (const cv::Point& q : pts) {
        cv::circle(inside, q, l.marker_px << detail::kShift, detail::bgr(l.color), cv::FILLED, cv::LINE_AA,
                   detail::kShift);
      }
    } else if (pts.size() == 1) {
      cv::circle(inside, pts[0], 3 << detail::kShift, detail::bgr(l.color), cv::FILLED, cv::LINE_AA, detail::kShift);
    } else if (!pts.empty()) {
      cv::polylines(inside, pts, false, detail::bgr(l.color), l.thickness, cv::LINE_AA, detail::kShift);
    }
    if (!l.label.empty()) legend.emplace_back(l.label, l.color);
  }
  detail::draw_legend(img, f.area, legend);
  return img;
}

void LinePlot::save(const std::filesystem::path& png) const { detail::write_png(render(), png); }

}  // namespace twinslam::plot

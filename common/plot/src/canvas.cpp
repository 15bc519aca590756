#include "canvas.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "twinslam/core/error.hpp"

namespace twinslam::plot {

Rgb palette(std::size_t index) {
  // Tableau-10 order: blue, orange, green, red, purple, brown, pink, grey, olive, cyan.
  static const Rgb kColors[] = {{31, 119, 180}, {255, 127, 14}, {44, 160, 44},  {214, 39, 40},   {148, 103, 189},
                                {140, 86, 75},  {227, 119, 194}, {127, 127, 127}, {188, 189, 34}, {23, 190, 207}};
  return kColors[index % 10];
}

namespace detail {
namespace {

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
const cv::Scalar kInk(0, 0, 0);
const cv::Scalar kGrid(225, 225, 225);

void text(cv::Mat& img, const std::string& s, cv::Point anchor, double scale, int thickness, double align_x,
          double align_y) {
  int baseline = 0;
  const cv::Size size = cv::getTextSize(s, kFont, scale, thickness, &baseline);
  // align 0 = left/top, 0.5 = centre, 1 = right/bottom of the text box at the anchor.
  const cv::Point origin(anchor.x - static_cast<int>(align_x * size.width),
                         anchor.y + static_cast<int>((1.0 - align_y) * size.height));
  cv::putText(img, s, origin, kFont, scale, kInk, thickness, cv::LINE_AA);
}

std::string format(double v, int decimals) {
  char buf[32];
  if (std::abs(v) < 0.5 * std::pow(10.0, -decimals)) v = 0.0;  // no "-0.0"
  if (decimals > 4) {
    std::snprintf(buf, sizeof(buf), "%.3g", v);  // tiny steps: "2.5e-07", not a margin-wide "0.00000025"
  } else {
    std::snprintf(buf, sizeof(buf), "%.*f", decimals, v);
  }
  return buf;
}

// Y label written vertically: drawn horizontally on a scratch image, rotated, then pasted.
void vertical_text(cv::Mat& img, const std::string& s, cv::Point centre, double scale) {
  int baseline = 0;
  const cv::Size size = cv::getTextSize(s, kFont, scale, 1, &baseline);
  cv::Mat scratch(size.height + baseline + 4, size.width + 4, CV_8UC3, cv::Scalar(255, 255, 255));
  cv::putText(scratch, s, cv::Point(2, size.height + 2), kFont, scale, kInk, 1, cv::LINE_AA);
  cv::Mat rotated;
  cv::rotate(scratch, rotated, cv::ROTATE_90_COUNTERCLOCKWISE);
  cv::Rect dst(centre.x - rotated.cols / 2, centre.y - rotated.rows / 2, rotated.cols, rotated.rows);
  dst &= cv::Rect(0, 0, img.cols, img.rows);
  rotated(cv::Rect(0, 0, dst.width, dst.height)).copyTo(img(dst));
}

}  // namespace

cv::Scalar bgr(Rgb c) { return cv::Scalar(c.b, c.g, c.r); }

cv::Point Frame::to_px(double x, double y) const {
  const double u = (x - x0) / (x1 - x0) * area.width;
  const double v = (1.0 - (y - y0) / (y1 - y0)) * area.height;
  return cv::Point(static_cast<int>(std::lround(u * (1 << kShift))), static_cast<int>(std::lround(v * (1 << kShift))));
}

cv::Rect plot_area(int width, int height) { return cv::Rect(105, 55, width - 105 - 30, height - 55 - 75); }

namespace {

// Smallest step of the form {1, 2, 5} x 10^k that is >= raw.
double nice_step(double raw) {
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0}) {
    if (m * mag >= raw * (1.0 - 1e-9)) return m * mag;
  }
  return 10.0 * mag;
}

std::vector<double> ticks_with_step(double lo, double hi, double step, int* decimals) {
  *decimals = std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9)));
  std::vector<double> ticks;
  const auto first = static_cast<long long>(std::ceil(lo / step - 1e-9));
  const auto last = static_cast<long long>(std::floor(hi / step + 1e-9));
  for (long long k = first; k <= last; ++k) ticks.push_back(static_cast<double>(k) * step);  // no accumulated error
  return ticks;
}

}  // namespace

std::vector<double> nice_ticks(double lo, double hi, int target, int* decimals) {
  return ticks_with_step(lo, hi, nice_step((hi - lo) / std::max(target, 1)), decimals);
}

std::vector<double> widen_to_ticks(double& lo, double& hi, int target, int* decimals) {
  if (!(hi > lo)) {
    const double pad = lo == 0.0 ? 1.0 : 0.1 * std::abs(lo);
    lo -= pad;
    hi += pad;
  }
  const double step = nice_step((hi - lo) / std::max(target, 1));
  lo = std::floor(lo / step + 1e-9) * step;
  hi = std::ceil(hi / step - 1e-9) * step;
  return ticks_with_step(lo, hi, step, decimals);
}

cv::Mat draw_frame(int width, int height, const Frame& f, const std::string& title, const std::string& xlabel,
                   const std::string& ylabel, const std::vector<double>& xticks, int xdec,
                   const std::vector<double>& yticks, int ydec, const std::vector<std::string>& x_names) {
  cv::Mat img(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  const cv::Rect& a = f.area;
  const auto px = [&](double x, double y) {
    const cv::Point p = f.to_px(x, y);
    return cv::Point(a.x + p.x / (1 << kShift), a.y + p.y / (1 << kShift));
  };
  for (double t : yticks) {
    const int y = px(f.x0, t).y;
    cv::line(img, {a.x, y}, {a.x + a.width, y}, kGrid, 1);
    cv::line(img, {a.x - 5, y}, {a.x, y}, kInk, 1);
    text(img, format(t, ydec), {a.x - 8, y}, 0.5, 1, 1.0, 0.5);
  }
  for (std::size_t i = 0; i < xticks.size(); ++i) {
    const int x = px(xticks[i], f.y0).x;
    if (x_names.empty()) cv::line(img, {x, a.y}, {x, a.y + a.height}, kGrid, 1);
    cv::line(img, {x, a.y + a.height}, {x, a.y + a.height + 5}, kInk, 1);
    const std::string label = x_names.empty() ? format(xticks[i], xdec) : x_names[i];
    text(img, label, {x, a.y + a.height + 10}, 0.5, 1, 0.5, 0.0);
  }
  cv::rectangle(img, a, kInk, 1);
  text(img, title, {a.x + a.width / 2, 18}, 0.75, 2, 0.5, 0.0);
  text(img, xlabel, {a.x + a.width / 2, height - 28}, 0.6, 1, 0.5, 0.0);
  vertical_text(img, ylabel, {20, a.y + a.height / 2}, 0.6);
  return img;
}

void draw_legend(cv::Mat& img, const cv::Rect& area, const std::vector<std::pair<std::string, Rgb>>& entries) {
  if (entries.empty()) return;
  int widest = 0, baseline = 0;
  for (const auto& e : entries) widest = std::max(widest, cv::getTextSize(e.first, kFont, 0.5, 1, &baseline).width);
  const int row = 22, w = widest + 60, h = row * static_cast<int>(entries.size()) + 10;
  const cv::Rect box(area.x + area.width - w - 10, area.y + 10, w, h);
  cv::rectangle(img, box, cv::Scalar(255, 255, 255), cv::FILLED);
  cv::rectangle(img, box, cv::Scalar(160, 160, 160), 1);
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const int y = box.y + 5 + row / 2 + row * static_cast<int>(i);
    cv::line(img, {box.x + 8, y}, {box.x + 38, y}, bgr(entries[i].second), 3, cv::LINE_AA);
    text(img, entries[i].first, {box.x + 46, y}, 0.5, 1, 0.0, 0.5);
  }
}

void write_png(const cv::Mat& img, const std::filesystem::path& png) {
  bool ok = false;
  try {
    ok = cv::imwrite(png.string(), img);
  } catch (const cv::Exception&) {
    ok = false;
  }
  if (!ok) throw InputError(where(png.string(), 0, "cannot write PNG"));
}

}  // namespace detail
}  // namespace twinslam::plot

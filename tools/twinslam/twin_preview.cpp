// Top-down PNG of a twin store (twin_preview.hpp): painter's algorithm over triangles sorted by height, so roofs
// cover the ground and facades (which project to lines) sit at their buildings' edges.
#include "twin_preview.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "twinslam/core/error.hpp"

namespace twinslam::cli {
namespace {

struct Canvas {
  double min_e = 0, max_n = 0, metres_per_px = 1, min_u = 0, span_u = 1;
  cv::Mat lut;  // 256 BGR colours, low (blue) to high (yellow)

  cv::Point px(const Eigen::Vector3d& p_W) const {
    return {static_cast<int>(std::lround((p_W.x() - min_e) / metres_per_px)),
            static_cast<int>(std::lround((max_n - p_W.y()) / metres_per_px))};
  }
  cv::Scalar colour(double u_m) const {
    const int i = std::clamp(static_cast<int>(255.0 * (u_m - min_u) / span_u), 0, 255);
    const cv::Vec3b c = lut.at<cv::Vec3b>(i, 0);
    return {static_cast<double>(c[0]), static_cast<double>(c[1]), static_cast<double>(c[2])};
  }
};

struct Shape {
  double height_m;                 // sort key: highest drawn last
  std::vector<cv::Point> corners;  // 3 for a triangle, 1 for a point
  double colour_u_m;
};

}  // namespace

std::pair<int, int> write_twin_preview(const std::string& twin_dir, const twin::TwinIndex& index,
                                       const std::string& png_path, int max_side_px) {
  const Eigen::AlignedBox3d& ext = index.extent_W;
  Canvas c;
  c.metres_per_px = std::max({ext.sizes().x(), ext.sizes().y(), 1e-3}) / max_side_px;
  c.min_e = ext.min().x();
  c.max_n = ext.max().y();
  c.min_u = ext.min().z();
  c.span_u = std::max(ext.sizes().z(), 1e-3);
  cv::Mat ramp(256, 1, CV_8UC1);
  for (int i = 0; i < 256; ++i) ramp.at<std::uint8_t>(i, 0) = static_cast<std::uint8_t>(i);
  cv::applyColorMap(ramp, c.lut, cv::COLORMAP_VIRIDIS);
  const int w = std::max(1, static_cast<int>(std::ceil(ext.sizes().x() / c.metres_per_px)) + 1);
  const int h = std::max(1, static_cast<int>(std::ceil(ext.sizes().y() / c.metres_per_px)) + 1);
  cv::Mat image(h, w, CV_8UC3, cv::Scalar(20, 20, 20));

  std::vector<Shape> shapes;
  for (const twin::TileInfo& info : index.tiles) {
    const twin::Tile tile = twin::load_tile(twin_dir, index, info.key);
    const twin::Mesh& m = tile.mesh_W;
    for (const Eigen::Vector3i& t : m.triangles) {
      const double top = std::max({m.p_W[t[0]].z(), m.p_W[t[1]].z(), m.p_W[t[2]].z()});
      const double mean = (m.p_W[t[0]].z() + m.p_W[t[1]].z() + m.p_W[t[2]].z()) / 3.0;
      shapes.push_back({top, {c.px(m.p_W[t[0]]), c.px(m.p_W[t[1]]), c.px(m.p_W[t[2]])}, mean});
    }
    if (m.triangles.empty()) {  // a point-set twin: the points are all there is to draw
      for (const Eigen::Vector3d& p : tile.points_W.p_W) shapes.push_back({p.z(), {c.px(p)}, p.z()});
    }
  }
  std::stable_sort(shapes.begin(), shapes.end(),
                   [](const Shape& a, const Shape& b) { return a.height_m < b.height_m; });
  for (const Shape& s : shapes) {
    if (s.corners.size() == 1) {
      cv::circle(image, s.corners[0], 0, c.colour(s.colour_u_m), cv::FILLED);  // one pixel
    } else {
      cv::fillConvexPoly(image, s.corners, c.colour(s.colour_u_m), cv::LINE_8);
    }
  }
  // Tile boundaries over everything: they show how the store is cut.
  const double size = index.tile_size_m;
  const cv::Scalar grey(128, 128, 128);
  for (double e = std::floor(ext.min().x() / size) * size; e <= ext.max().x(); e += size) {
    const int u = c.px({e, 0, 0}).x;
    if (u >= 0 && u < w) cv::line(image, {u, 0}, {u, h - 1}, grey, 1);
  }
  for (double n = std::floor(ext.min().y() / size) * size; n <= ext.max().y(); n += size) {
    const int v = c.px({0, n, 0}).y;
    if (v >= 0 && v < h) cv::line(image, {0, v}, {w - 1, v}, grey, 1);
  }
  bool written = false;
  try {
    written = cv::imwrite(png_path, image);
  } catch (const cv::Exception&) {  // OpenCV's message spans lines; ours must be one
    written = false;
  }
  if (!written) throw InputError(where(png_path, 0, "cannot write the preview (a writable .png path?)"));
  return {w, h};
}

}  // namespace twinslam::cli

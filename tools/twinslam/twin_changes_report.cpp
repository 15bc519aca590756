#include "twin_changes_report.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "twinslam/core/csv.hpp"
#include "twinslam/core/error.hpp"

namespace twinslam::cli {
namespace fs = std::filesystem;

std::vector<twin::LandmarkSighting> read_sightings(const fs::path& run, std::int64_t epoch_ns,
                                                   std::int64_t aligned_from_ns) {
  const fs::path file = run / "landmarks.csv";
  if (!fs::exists(file)) {
    throw InputError(file.string() + ": missing: only runs aligned to W record their landmarks (twin or GNSS modes)");
  }
  std::vector<twin::LandmarkSighting> out;
  read_csv(file, 10, [&](const CsvRow& row) {
    if (parse_int64(file, row, 2, "keyframe_stamp_ns") < aligned_from_ns) return;
    twin::LandmarkSighting s;
    s.p_W = {parse_double(file, row, 3, "x_W"), parse_double(file, row, 4, "y_W"), parse_double(file, row, 5, "z_W")};
    s.quality = parse_double(file, row, 6, "quality");
    s.observer_W = {parse_double(file, row, 7, "observer_x_W"), parse_double(file, row, 8, "observer_y_W"),
                    parse_double(file, row, 9, "observer_z_W")};
    s.t_s = 1e-9 * static_cast<double>(parse_int64(file, row, 1, "first_keyframe_stamp_ns") - epoch_ns);
    out.push_back(s);
  });
  return out;
}

nlohmann::json changes_geojson(const std::vector<twin::TwinChange>& changes, const twin::EnuFrame& W) {
  nlohmann::json features = nlohmann::json::array();
  for (const twin::TwinChange& c : changes) {
    nlohmann::json ring = nlohmann::json::array(), local = nlohmann::json::array();
    for (std::size_t i = 0; i <= c.footprint_W.size(); ++i) {  // RFC 7946: the ring ends where it starts
      const Eigen::Vector2d& p = c.footprint_W[i % c.footprint_W.size()];
      const Eigen::Vector3d lla = W.to_lla(Eigen::Vector3d(p.x(), p.y(), 0.0));
      ring.push_back({lla.y(), lla.x()});
      if (i < c.footprint_W.size()) local.push_back({p.x(), p.y()});
    }
    features.push_back({{"type", "Feature"},
                        {"geometry", {{"type", "Polygon"}, {"coordinates", {ring}}}},
                        {"properties",
                         {{"kind", c.kind},
                          {"landmarks", c.landmarks},
                          {"sight_lines", c.sight_lines},
                          {"mean_distance_m", c.mean_distance_m},
                          {"mean_depth_m", c.mean_depth_m},
                          {"first_s", c.first_s},
                          {"last_s", c.last_s},
                          {"footprint_W", local}}}});
  }
  return {{"type", "FeatureCollection"}, {"features", features}};
}

void write_changes_png(const fs::path& png, const twin::Mesh& twin_W, const Trajectory& trajectory_W,
                       const std::vector<twin::TwinChange>& changes, int max_side_px) {
  const Eigen::AlignedBox3d box = twin_W.bounds();
  const double m_per_px = std::max({box.sizes().x(), box.sizes().y(), 1.0}) / max_side_px;
  const auto px = [&](double e, double n) {
    return cv::Point(static_cast<int>(std::lround((e - box.min().x()) / m_per_px)),
                     static_cast<int>(std::lround((box.max().y() - n) / m_per_px)));
  };
  cv::Mat image(static_cast<int>(box.sizes().y() / m_per_px) + 1, static_cast<int>(box.sizes().x() / m_per_px) + 1,
                CV_8UC3, cv::Scalar(30, 30, 30));
  // Painter's order by height: roofs over facades over the ground.
  std::vector<std::pair<double, std::size_t>> order;
  for (std::size_t t = 0; t < twin_W.triangles.size(); ++t) {
    const auto& tri = twin_W.triangles[t];
    order.emplace_back(std::max({twin_W.p_W[tri[0]].z(), twin_W.p_W[tri[1]].z(), twin_W.p_W[tri[2]].z()}), t);
  }
  std::sort(order.begin(), order.end());
  const double span = std::max(box.sizes().z(), 1.0);
  for (const auto& [top, t] : order) {
    std::vector<cv::Point> corners;
    for (int k = 0; k < 3; ++k) corners.push_back(px(twin_W.p_W[twin_W.triangles[t][k]].x(), twin_W.p_W[twin_W.triangles[t][k]].y()));
    const double grey = 70 + 150 * (top - box.min().z()) / span;
    cv::fillConvexPoly(image, corners, cv::Scalar(grey, grey, grey), cv::LINE_AA);
  }
  for (std::size_t i = 1; i < trajectory_W.poses.size(); ++i) {
    const Eigen::Vector3d a = trajectory_W.poses[i - 1].p_X(), b = trajectory_W.poses[i].p_X();
    cv::line(image, px(a.x(), a.y()), px(b.x(), b.y()), cv::Scalar(255, 140, 0), 2, cv::LINE_AA);
  }
  for (const twin::TwinChange& c : changes) {
    std::vector<cv::Point> ring;
    for (const auto& p : c.footprint_W) ring.push_back(px(p.x(), p.y()));
    cv::polylines(image, ring, true, cv::Scalar(0, 0, 255), 3, cv::LINE_AA);
    cv::putText(image, c.kind, ring.front() + cv::Point(4, -4), cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(0, 0, 255), 2);
  }
  if (!cv::imwrite(png.string(), image)) throw InputError(png.string() + ": cannot write");
}

}  // namespace twinslam::cli

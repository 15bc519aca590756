// The paper code's registration recipe as the benchmark's baseline (see keyframes.hpp).
#include <chrono>
#include <map>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/registration/icp.h>

#include "keyframes.hpp"
#include "twinslam/twin/store.hpp"

namespace twinslam::registration::bench {

// Decoded tiles stay in memory (the paper's code holds the map), so the timed part is the crop, the KD-tree and ICP.
struct PclBaseline::Impl {
  std::string dir;
  twin::TwinIndex store;
  std::map<twin::TileKey, twin::Mesh> tiles;
};

PclBaseline::PclBaseline(const std::string& twin_dir) : impl(new Impl{twin_dir, twin::read_twin_index(twin_dir), {}}) {}
PclBaseline::~PclBaseline() { delete impl; }

double PclBaseline::run(const Keyframe& k, double crop_half_m, int iterations, double max_corr_m,
                        Eigen::Vector3d& p_corrected, std::size_t& crop_points) {
  const Eigen::Vector3d c = k.drift * k.p_WB_true;     // the estimate's keyframe position: crop centre and pivot
  for (const twin::TileInfo& t : impl->store.tiles) {  // load (untimed) what the crop needs
    if (t.bounds_W.max().x() < c.x() - crop_half_m || t.bounds_W.min().x() > c.x() + crop_half_m ||
        t.bounds_W.max().y() < c.y() - crop_half_m || t.bounds_W.min().y() > c.y() + crop_half_m)
      continue;
    if (!impl->tiles.count(t.key)) impl->tiles[t.key] = twin::load_tile(impl->dir, impl->store, t.key).points_W;
  }
  const auto t0 = std::chrono::steady_clock::now();
  auto target = std::make_shared<pcl::PointCloud<pcl::PointNormal>>();
  for (const auto& [key, m] : impl->tiles) {
    for (std::size_t i = 0; i < m.p_W.size(); ++i) {
      const Eigen::Vector3d d = m.p_W[i] - c;
      if (std::abs(d.x()) > crop_half_m || std::abs(d.y()) > crop_half_m) continue;
      pcl::PointNormal q;
      q.getVector3fMap() = d.cast<float>();
      q.getNormalVector3fMap() = m.n_W[i].cast<float>();
      target->push_back(q);
    }
  }
  auto source = std::make_shared<pcl::PointCloud<pcl::PointNormal>>();
  for (const auto& p : k.p_guess_W) {
    pcl::PointNormal q;
    q.getVector3fMap() = (p - c).cast<float>();
    q.getNormalVector3fMap().setZero();
    source->push_back(q);
  }
  pcl::IterativeClosestPointWithNormals<pcl::PointNormal, pcl::PointNormal> icp;
  icp.setInputSource(source);
  icp.setInputTarget(target);
  icp.setMaxCorrespondenceDistance(max_corr_m);
  icp.setMaximumIterations(iterations);
  pcl::PointCloud<pcl::PointNormal> aligned;
  icp.align(aligned);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  p_corrected = c + icp.getFinalTransformation().topRightCorner<3, 1>().cast<double>();
  crop_points = target->size();
  return ms;
}

}  // namespace twinslam::registration::bench

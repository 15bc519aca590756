// Source-cloud preprocessing (see preprocess.hpp). Includes PCL for StatisticalOutlierRemoval only.
#include "twinslam/registration/preprocess.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <tuple>

#include <pcl/filters/statistical_outlier_removal.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "twinslam/core/error.hpp"

namespace twinslam::registration {
namespace {

void check_input(const SourceInput& in) {
  if (!in.T_WL.matrix().allFinite() || !in.T_LB.matrix().allFinite()) {
    throw InputError("registration source: T_WL or T_LB is not finite");
  }
  for (std::size_t i = 0; i < in.landmarks.size(); ++i) {
    const Landmark& l = in.landmarks[i];
    if (!l.p_L.allFinite()) throw InputError("registration source: landmark " + std::to_string(i) + " is not finite");
    if (!(l.quality >= 0.0 && l.quality <= 1.0)) {
      throw InputError("registration source: landmark " + std::to_string(i) + " quality " + std::to_string(l.quality) +
                       " outside [0, 1]");
    }
  }
}

// One centroid per occupied voxel, voxels in key order (deterministic). Coordinates relative to `pivot` so the
// voxel keys stay small integers wherever W's origin is.
std::vector<Eigen::Vector3d> voxel_downsample(const std::vector<Eigen::Vector3d>& p, const Eigen::Vector3d& pivot,
                                              double voxel) {
  if (voxel <= 0.0) return p;
  std::map<std::tuple<long, long, long>, std::pair<Eigen::Vector3d, int>> cells;
  for (const Eigen::Vector3d& x : p) {
    const Eigen::Vector3d v = (x - pivot) / voxel;
    auto& cell =
        cells[{std::lround(std::floor(v.x())), std::lround(std::floor(v.y())), std::lround(std::floor(v.z()))}];
    if (cell.second == 0) cell.first.setZero();
    cell.first += x;
    ++cell.second;
  }
  std::vector<Eigen::Vector3d> out;
  out.reserve(cells.size());
  for (const auto& [key, cell] : cells) out.push_back(cell.first / cell.second);
  return out;
}

std::vector<Eigen::Vector3d> remove_outliers(const std::vector<Eigen::Vector3d>& p, const Eigen::Vector3d& pivot,
                                             int neighbors, double stddev) {
  if (neighbors <= 0 || p.size() <= static_cast<std::size_t>(neighbors)) return p;
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  for (const Eigen::Vector3d& x : p) {
    const Eigen::Vector3f q = (x - pivot).cast<float>();  // float relative to the keyframe: no precision loss
    cloud->push_back(pcl::PointXYZ(q.x(), q.y(), q.z()));
  }
  pcl::StatisticalOutlierRemoval<pcl::PointXYZ> sor;
  sor.setInputCloud(cloud);
  sor.setMeanK(neighbors);
  sor.setStddevMulThresh(stddev);
  pcl::Indices kept;
  sor.filter(kept);  // indices in input order
  std::vector<Eigen::Vector3d> out;
  out.reserve(kept.size());
  for (const auto i : kept) out.push_back(p[static_cast<std::size_t>(i)]);
  return out;
}

}  // namespace

SourceCloud preprocess(const RegistrationConfig& config, const SourceInput& input) {
  check_input(input);
  SourceCloud out;
  out.input = input.landmarks.size();
  out.p_WB = (input.T_WL * input.T_LB).translation();
  std::vector<Eigen::Vector3d> p_W;
  p_W.reserve(input.landmarks.size());
  for (const Landmark& l : input.landmarks) {
    if (l.quality >= config.min_quality) p_W.push_back(input.T_WL * l.p_L);
  }
  out.after_quality = p_W.size();
  p_W = voxel_downsample(p_W, out.p_WB, config.voxel_size_m);
  out.after_voxel = p_W.size();
  out.p_W = remove_outliers(p_W, out.p_WB, config.outlier_neighbors, config.outlier_stddev);
  return out;
}

}  // namespace twinslam::registration

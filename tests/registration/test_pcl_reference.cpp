// Reference: PCL's point-to-plane ICP (IterativeClosestPointWithNormals) on the same preprocessed cloud and the same
// twin points reaches the same correction as ours; PCL's StatisticalOutlierRemoval keeps the same points as our
// statistical_inliers. Its own binary: PCL's registration headers cost ~24 s to compile.
#include <gtest/gtest.h>

#include <pcl/filters/statistical_outlier_removal.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/registration/icp.h>

#include "synthetic_twin.hpp"
#include "twinslam/geometry/so3.hpp"
#include "twinslam/registration/registration.hpp"

namespace twinslam::registration {
namespace {

pcl::PointCloud<pcl::PointNormal>::Ptr to_pcl(const std::vector<Eigen::Vector3d>& p,
                                              const std::vector<Eigen::Vector3d>* n, const Eigen::Vector3d& pivot) {
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointNormal>>();
  for (std::size_t i = 0; i < p.size(); ++i) {
    pcl::PointNormal q;
    q.getVector3fMap() = (p[i] - pivot).cast<float>();  // relative to the pivot: float precision is fine
    q.getNormalVector3fMap() = n ? Eigen::Vector3f((*n)[i].cast<float>()) : Eigen::Vector3f::Zero();
    cloud->push_back(q);
  }
  return cloud;
}

TEST(RegistrationPclReference, StatisticalOutlierRemovalKeepsTheSamePointsAsPcl) {
  const Eigen::Vector3d body = test::kCentre + Eigen::Vector3d(0.0, -5.0, 15.0);
  for (const int seed : {31, 32, 33}) {
    auto p = test::sample_noisy(test::city_surfaces(), 1200, 0.1, seed);
    const auto o = test::sample_outliers(150, seed + 100);
    p.insert(p.end(), o.begin(), o.end());
    for (const int k : {4, 8, 16}) {
      auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
      for (const auto& x : p) {
        const Eigen::Vector3f q = (x - body).cast<float>();
        cloud->push_back(pcl::PointXYZ(q.x(), q.y(), q.z()));
      }
      pcl::StatisticalOutlierRemoval<pcl::PointXYZ> sor;
      sor.setInputCloud(cloud);
      sor.setMeanK(k);
      sor.setStddevMulThresh(2.0);
      pcl::Indices pcl_kept;
      sor.filter(pcl_kept);
      const std::vector<std::size_t> ours = statistical_inliers(p, body, k, 2.0);
      ASSERT_LT(ours.size(), p.size()) << "the outliers must remove something";
      // Same definition, same float input; the two KD-trees may order equidistant neighbours differently, which
      // cannot change a mean distance: the kept sets must be equal.
      ASSERT_EQ(ours.size(), pcl_kept.size()) << "seed " << seed << " k " << k;
      for (std::size_t i = 0; i < ours.size(); ++i) EXPECT_EQ(ours[i], static_cast<std::size_t>(pcl_kept[i]));
    }
  }
}

TEST(RegistrationPclReference, PointToPlaneIcpWithNormalsAgreesWithOurs) {
  const Eigen::Vector3d body = test::kCentre + Eigen::Vector3d(0.0, -5.0, 15.0);
  const test::PointSet twin = test::sample_grid(test::city_surfaces(), 0.5);
  const TwinTileIndex index = test::make_index(twin);
  const Eigen::Isometry3d error = test::offset_about(body, {0.3, -0.2, 1.0}, 3.0, {0.6, -0.7, 0.4});
  auto p = test::sample_noisy(test::city_surfaces(), 3000, 0.1, 21);
  const auto o = test::sample_outliers(750, 22);  // 20 %
  p.insert(p.end(), o.begin(), o.end());
  const SourceInput in = test::make_source(p, error, body);
  RegistrationConfig config;
  config.voxel_size_m = 0.0;
  const RegistrationResult ours = register_cloud(config, index, in);
  ASSERT_TRUE(ours.accepted()) << ours.reason;

  const SourceCloud source = preprocess(config, in);
  pcl::IterativeClosestPointWithNormals<pcl::PointNormal, pcl::PointNormal> icp;
  icp.setInputSource(to_pcl(source.p_W, nullptr, source.p_WB));
  icp.setInputTarget(to_pcl(twin.p_W, &twin.n_W, source.p_WB));
  icp.setMaxCorrespondenceDistance(1.5);  // no adaptive gate in PCL: between the initial error and the noise
  icp.setMaximumIterations(60);
  icp.setTransformationEpsilon(1e-12);
  icp.setEuclideanFitnessEpsilon(1e-12);
  pcl::PointCloud<pcl::PointNormal> aligned;
  icp.align(aligned);
  ASSERT_TRUE(icp.hasConverged());
  const Eigen::Matrix4d T = icp.getFinalTransformation().cast<double>();  // about the pivot, like ours
  const Eigen::Matrix3d R_pcl = geometry::so3_normalize(T.topLeftCorner<3, 3>());
  const Eigen::Vector3d t_pcl = T.topRightCorner<3, 1>();
  const Eigen::Matrix3d dR = ours.correction_W.linear();
  const Eigen::Vector3d dp = ours.correction_xi.tail<3>();
  const double rot_deg = geometry::so3_angle_between(R_pcl, dR) * 180.0 / M_PI;
  const double trans_m = (t_pcl - dp).norm();
  std::printf("ours vs PCL: %.4f deg, %.4f m at the keyframe; vs truth at the keyframe: PCL %.4f m, ours %.4f m\n",
              rot_deg, trans_m, (source.p_WB + t_pcl - body).norm(), (ours.correction_W * source.p_WB - body).norm());
  EXPECT_LT(rot_deg, 0.05);
  EXPECT_LT(trans_m, 0.02);  // measured 0.015 m: PCL has no robust kernel, its outliers bias it (1.8 cm vs 0.4 cm)
}

}  // namespace
}  // namespace twinslam::registration

#pragma once
// A feature's appearance at its first frame, and the affine alignment of that patch to a later image.
//
// Why: frame-to-frame KLT measures each step against the previous frame's (already slightly wrong) position and
// re-samples the template there, so sub-pixel errors add up as a random walk, and perspective change (a translation-only
// window on a scaling, shearing facade) adds a bias per step; on the simulated city-loops a quarter of the tracks were
// more than 2 px off after 35 frames. Aligning the ORIGINAL patch to the current image under an affine warp (Shi and
// Tomasi 1994, "Good features to track", sec. 4; solved by inverse-compositional Gauss-Newton, Baker and Matthews 2004)
// puts every observation back on the first frame's point, so the error no longer grows with track length; the
// zero-mean normalized cross-correlation after alignment says when the patch no longer looks like its reference
// (occlusion, a silhouette whose background slid, a wrong match), and the track is dropped.
#include <memory>

#include <Eigen/Core>
#include <opencv2/core.hpp>

namespace twinslam::tracking {

class ReferencePatch {
 public:
  // The patch of side 2 * half_px + 1 around `px` (the detection, normally a whole pixel) of a mono8 image.
  ReferencePatch(const cv::Mat& mono8, const cv::Point2f& px, int half_px);

  // Warp from patch coordinates (relative to the reference centre) [px] to image pixels: x_img = A x + t.
  struct Warp {
    Eigen::Matrix2d A = Eigen::Matrix2d::Identity();
    Eigen::Vector2d t = Eigen::Vector2d::Zero();
  };

  // Aligns the patch to `mono8` starting from `warp` (its translation normally KLT's answer, its linear part the
  // previous frame's). Returns false if the patch left the image, Gauss-Newton did not settle, the linear part
  // degenerated (scale outside [1/3, 3]) or the normalized cross-correlation is below min_zncc; else updates `warp`.
  bool align(const cv::Mat& mono8, double min_zncc, Warp* warp) const;

 private:
  int half_;
  int n_;                              // pixels in the patch
  Eigen::VectorXf ref_;                // zero-mean reference intensities, unit norm
  Eigen::Matrix<float, Eigen::Dynamic, 6> sd_;  // steepest-descent images (inverse compositional, affine)
  Eigen::Matrix<double, 6, 6> h_inv_;  // inverse Gauss-Newton Hessian of sd_
  bool ok_ = false;                    // false for a flat patch (nothing to align)
};

}  // namespace twinslam::tracking

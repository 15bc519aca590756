#pragma once
// The tracking frontend's one config struct: detection, KLT, outlier rejection, exposure normalization.
// Defaults suit 640x400 .. 752x480 images at 20 Hz; validate() is the one place the values are checked.
#include <string>

namespace twinslam::tracking {

struct FrontendConfig {
  // --- Detection (Shi-Tomasi, bucketed on a grid for an even spread) ---
  int max_features = 180;           // tracks kept per frame; detection tops up to this count
  int grid_cols = 8;                // buckets across the image
  int grid_rows = 5;                // buckets down the image
  double min_distance_px = 20.0;    // no new feature closer than this to another one; tracks closer than half of
                                    // it to a longer track are dropped as duplicates [px]
  double quality_level = 0.01;      // Shi-Tomasi: keep corners with min eigenvalue >= quality * best of the bucket
  double min_eigenvalue = 2e-4;     // absolute floor on the min eigenvalue (OpenCV's normalized units; 0 = none),
                                    // so flat buckets (sky, white walls) do not get noise corners
  int border_px = 10;               // no features this close to the image edge [px]

  // --- Pyramidal KLT (Bouguet's pyramidal Lucas-Kanade, as in cv::calcOpticalFlowPyrLK) ---
  int klt_window_px = 15;           // square window side [px], odd
  int klt_levels = 3;               // pyramid levels above the full image (0 = no pyramid)
  int klt_max_iterations = 20;      // per level
  double klt_epsilon_px = 0.03;     // stop when the update is below this [px]
  double fb_threshold_px = 0.5;     // forward-backward check: max |x_prev - backward(forward(x_prev))| [px];
                                    // only with ref_window_px = 0 (else the reference alignment checks each track)

  // --- Alignment to the first frame's patch (affine, see reference_patch.hpp) ---
  int ref_window_px = 21;           // square patch side [px], odd; 0 = off (plain frame-to-frame KLT, which drifts)
  // Drop a track whose aligned patch correlates less than this with its reference. A corner formed by a near edge
  // over a far surface changes its look as the background slides: 0.95 instead of 0.9 halved those wrong tracks on
  // city-loops (diag_tracking_sim 30 80: 155 -> 70 wrong observations) at a median track length still >= 12.
  double ref_min_zncc = 0.95;

  // --- RANSAC on bearings (see ransac.hpp) ---
  // kEssential: 8-point essential matrix on bearings; needs no gyro, so a gyro bias cannot reject good tracks (EuRoC
  //   V1_01's gyro bias, ~0.08 rad/s, turns the rotation by ~4 mrad = 1.8 px per frame at 20 Hz).
  // kKnownRotation: 2-point translation RANSAC with the gyro rotation given to track(); ~10x fewer draws, but the
  //   gyro must be bias-corrected to well below ransac_threshold_px per frame. Without a rotation, kEssential is used.
  enum class RansacModel { kEssential, kKnownRotation };
  RansacModel ransac_model = RansacModel::kEssential;
  // Residual threshold as an angle, given in px-equivalent: divided by the focal length fu [px/rad at the centre],
  // so 1 px ~ 2.2 mrad for EuRoC (fu = 459 px).
  double ransac_threshold_px = 1.0;
  double ransac_confidence = 0.999;  // probability of drawing at least one all-inlier sample
  int ransac_max_iterations = 200;
  // A second RANSAC between each frame and the frame this many frames back, on the tracks seen in both (ransac_model
  // as above, kKnownRotation only if the gyro rotation came with every frame of the span; 0 = off, at most 7): a point sliding along an occlusion edge (a corner formed by a near edge over a far surface)
  // moves off its epipolar line by a fraction of a pixel per frame, which the frame-to-frame test cannot see but
  // the longer baseline can.
  int ransac_span_frames = 7;
  unsigned ransac_seed = 42;         // fixed seed: same input -> same tracks

  // --- Exposure normalization ---
  bool clahe = false;               // contrast-limited adaptive histogram equalization before detection and KLT
  double clahe_clip_limit = 3.0;    // OpenCV's clip limit (contrast amplification cap)
  int clahe_tiles = 8;              // tiles per image side

  // --- Smoothing before detection and tracking ---
  // Gaussian sigma [px]; 0 = off. Hard, point-sampled edges (the simulator casts one ray per pixel, so edges are
  // staircases; also sharp, oversampled-lens cameras) give Shi-Tomasi corners on the stairs and let KLT's answer hop
  // by a pixel fraction from frame to frame; sigma 1 suppresses that at a small cost in precision on smooth images.
  double presmooth_sigma_px = 1.0;

  // Throws twinslam::InputError "SOURCE: tracking key 'K': what" naming the first bad field.
  void validate(const std::string& source = "FrontendConfig") const;
};

}  // namespace twinslam::tracking

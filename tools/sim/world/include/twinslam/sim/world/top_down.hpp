#pragma once
// A top-down (orthographic, looking down -z) picture of the world for `twinslam sim --preview` (issue 3, item 10):
// textured and lit like the camera images, brighter with height so blocks and the tower stand out.
#include <opencv2/core.hpp>

#include "twinslam/sim/world/renderer.hpp"

namespace twinslam::sim {

struct TopDownImage {
  cv::Mat image;                 // CV_8UC1; 0 where no surface is below
  double min_e_m = 0;            // W east of the left edge of pixel column 0 [m]
  double max_n_m = 0;            // W north of the top edge of pixel row 0 [m]
  double metres_per_pixel = 1;

  // Pixel (u, v) of a W position (east, north) [m] -> [px], for drawing trajectories on the map.
  cv::Point2d pixel(double e_m, double n_m) const {
    return {(e_m - min_e_m) / metres_per_pixel - 0.5, (max_n_m - n_m) / metres_per_pixel - 0.5};
  }
};

// Covers the mesh's horizontal bounds. Throws InputError if metres_per_pixel <= 0 or the image would exceed
// 8000 px on a side.
TopDownImage render_top_down(const Renderer& renderer, double metres_per_pixel);

}  // namespace twinslam::sim

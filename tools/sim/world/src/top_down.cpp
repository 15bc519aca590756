#include "twinslam/sim/world/top_down.hpp"

#include <algorithm>
#include <cmath>

#include "twinslam/core/error.hpp"
#include "twinslam/sim/world/texture.hpp"

namespace twinslam::sim {

TopDownImage render_top_down(const Renderer& renderer, double metres_per_pixel) {
  if (!(metres_per_pixel > 0)) throw InputError("top-down preview: metres_per_pixel must be > 0");
  const TriMesh& mesh = renderer.scene().mesh();
  Eigen::Vector3d lo, hi;
  mesh.bounds(&lo, &hi);
  const int w = static_cast<int>(std::ceil((hi.x() - lo.x()) / metres_per_pixel));
  const int h = static_cast<int>(std::ceil((hi.y() - lo.y()) / metres_per_pixel));
  if (w > 8000 || h > 8000) throw InputError("top-down preview: image larger than 8000 px; use more metres_per_pixel");
  TopDownImage out;
  out.min_e_m = lo.x();
  out.max_n_m = hi.y();
  out.metres_per_pixel = metres_per_pixel;
  out.image = cv::Mat(std::max(h, 1), std::max(w, 1), CV_8UC1, cv::Scalar(0));
  const Eigen::Vector3d down(0, 0, -1), sun = Eigen::Vector3d(0.5, 0.3, 0.81).normalized();
  const double top = hi.z() + 10.0, height = std::max(hi.z() - lo.z(), 1.0);
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      const Eigen::Vector3d o(out.min_e_m + (u + 0.5) * metres_per_pixel, out.max_n_m - (v + 0.5) * metres_per_pixel,
                              top);
      RayHit hit;
      if (!renderer.scene().intersect(o, down, 0.0, top - lo.z() + 1.0, &hit)) continue;
      const Eigen::Vector3d p = o + hit.t_m * down;
      const float a = albedo(p, hit.n_W, mesh.kind[hit.triangle], mesh.building_id[hit.triangle], metres_per_pixel);
      const double lit = a * (0.45 + 0.55 * std::max(0.0, hit.n_W.dot(sun)));
      const double value = 255.0 * (0.55 * lit + 0.45 * (0.2 + 0.8 * (p.z() - lo.z()) / height));
      out.image.at<std::uint8_t>(v, u) = static_cast<std::uint8_t>(std::clamp(value + 0.5, 1.0, 255.0));
    }
  }
  return out;
}

}  // namespace twinslam::sim

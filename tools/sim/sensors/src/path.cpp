#include "path.hpp"

#include <algorithm>
#include <cmath>

namespace twinslam::sim::detail {

void PlanarPath::add_line(const Eigen::Vector3d& a_W, const Eigen::Vector3d& b_W) {
  Piece p;
  p.a_W = a_W;
  p.b_W = b_W;
  p.length = (b_W - a_W).head<2>().norm();
  if (p.length < 1e-9) return;
  p.s0 = total_;
  total_ += p.length;
  pieces_.push_back(p);
}

void PlanarPath::add_arc(const Eigen::Vector2d& center_EN, double radius, double start, double sweep, double z_start,
                         double z_end) {
  Piece p;
  p.arc = true;
  p.center = center_EN;
  p.radius = radius;
  p.start = start;
  p.sweep = sweep;
  p.z0 = z_start;
  p.z1 = z_end;
  p.length = radius * std::abs(sweep);
  if (p.length < 1e-9) return;
  p.s0 = total_;
  total_ += p.length;
  pieces_.push_back(p);
}

PathPoint PlanarPath::at(double s) const {
  s = std::clamp(s, 0.0, total_);
  auto it = std::upper_bound(pieces_.begin(), pieces_.end(), s, [](double v, const Piece& p) { return v < p.s0; });
  const Piece& p = *std::prev(it == pieces_.begin() ? std::next(it) : it);
  const double f = std::clamp((s - p.s0) / p.length, 0.0, 1.0);
  PathPoint out;
  if (!p.arc) {
    out.p_W = p.a_W + f * (p.b_W - p.a_W);
    out.heading = std::atan2(p.b_W.y() - p.a_W.y(), p.b_W.x() - p.a_W.x());
  } else {
    const double angle = p.start + f * p.sweep;
    out.p_W = Eigen::Vector3d(p.center.x() + p.radius * std::cos(angle), p.center.y() + p.radius * std::sin(angle),
                              p.z0 + f * (p.z1 - p.z0));
    out.heading = angle + (p.sweep > 0 ? M_PI / 2 : -M_PI / 2);
  }
  return out;
}

PlanarPath PlanarPath::filleted_polyline(const std::vector<Eigen::Vector3d>& pts, double radius) {
  PlanarPath path;
  Eigen::Vector3d from = pts.front();
  for (std::size_t i = 1; i + 1 < pts.size(); ++i) {
    const Eigen::Vector3d in = pts[i] - pts[i - 1], out = pts[i + 1] - pts[i];
    const double len_in = in.head<2>().norm(), len_out = out.head<2>().norm();
    if (len_in < 1e-9 || len_out < 1e-9) continue;
    const Eigen::Vector2d d_in = in.head<2>() / len_in, d_out = out.head<2>() / len_out;
    const double turn = std::atan2(d_in.x() * d_out.y() - d_in.y() * d_out.x(), d_in.dot(d_out));  // signed [rad]
    if (std::abs(turn) < 1e-6) continue;
    // Tangent length T = r tan(|turn|/2), at most half of either leg (so consecutive fillets do not overlap).
    const double T = std::min(radius * std::tan(std::abs(turn) / 2), 0.5 * std::min(len_in, len_out));
    const double r = T / std::tan(std::abs(turn) / 2);
    const Eigen::Vector3d a = pts[i] - in * (T / len_in);   // fillet start on the incoming leg
    const Eigen::Vector3d b = pts[i] + out * (T / len_out);  // fillet end on the outgoing leg
    const Eigen::Vector2d left(-d_in.y(), d_in.x());
    const Eigen::Vector2d center = a.head<2>() + (turn > 0 ? 1.0 : -1.0) * r * left;
    path.add_line(from, a);
    path.add_arc(center, r, std::atan2(a.y() - center.y(), a.x() - center.x()), turn, a.z(), b.z());
    from = b;
  }
  path.add_line(from, pts.back());
  return path;
}

}  // namespace twinslam::sim::detail

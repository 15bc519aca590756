#include "twinslam/sim/world/traffic.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <embree3/rtcore.h>

#include "twinslam/core/error.hpp"
#include "twinslam/sim/world/random.hpp"

namespace twinslam::sim {

struct Traffic::Impl {
  RTCDevice device = nullptr;
  ~Impl() {
    if (device) rtcReleaseDevice(device);
  }
};

namespace {

// The one-way street grid: nodes at the crossings of the street centrelines, edges along the streets between
// neighbouring crossings.
class StreetNetwork {
 public:
  StreetNetwork(const SceneHints& hints) : e_(hints.streets.east_m), n_(hints.streets.north_m) {
    std::sort(e_.begin(), e_.end());
    std::sort(n_.begin(), n_.end());
    const int ne = static_cast<int>(e_.size()), nn = static_cast<int>(n_.size());
    // North-south street i: the westernmost runs north, the easternmost south, the others alternate; east-west street
    // j: the southernmost runs west, the northernmost east. The grid's rim thus circulates clockwise.
    for (int i = 0; i < ne; ++i) north_.push_back(i == 0 ? 1 : i == ne - 1 ? -1 : (i % 2 == 0 ? 1 : -1));
    for (int j = 0; j < nn; ++j) east_.push_back(j == 0 ? -1 : j == nn - 1 ? 1 : (j % 2 == 0 ? -1 : 1));
    centre_ = hints.tall_building_center_W;
    // The procedural city leaves clear_radius_m unknown (0): its tower block's ring street is what loops fly over.
    clear_m_ = hints.clear_radius_m > 0 ? hints.clear_radius_m : hints.tall_building_radius_m + hints.streets.width_m;
  }

  int size() const { return static_cast<int>(e_.size() * n_.size()); }
  Eigen::Vector2d position(int node) const { return {e_[node % e_.size()], n_[node / e_.size()]}; }

  // The open street pieces leaving `node` the right way; if there are none (a dead end the closure made), the open
  // ones either way.
  std::vector<int> next(int node) const {
    const int ne = static_cast<int>(e_.size()), nn = static_cast<int>(n_.size());
    const int i = node % ne, j = node / ne;
    std::vector<int> out;
    const auto add = [&](int i2, int j2) {
      if (i2 < 0 || i2 >= ne || j2 < 0 || j2 >= nn) return;
      const int to = j2 * ne + i2;
      if (open(node, to)) out.push_back(to);
    };
    add(i, j + north_[i]);
    add(i + east_[j], j);
    if (out.empty()) {
      add(i, j - north_[i]);
      add(i - east_[j], j);
    }
    return out;
  }

  // Every open piece the right way, as (from, to).
  std::vector<std::pair<int, int>> edges() const {
    std::vector<std::pair<int, int>> out;
    const int ne = static_cast<int>(e_.size()), nn = static_cast<int>(n_.size());
    for (int node = 0; node < size(); ++node) {
      const int i = node % ne, j = node / ne;
      const int candidates[2][2] = {{i, j + north_[i]}, {i + east_[j], j}};
      for (const auto& c : candidates) {
        if (c[0] < 0 || c[0] >= ne || c[1] < 0 || c[1] >= nn) continue;
        const int to = c[1] * ne + c[0];
        if (open(node, to)) out.emplace_back(node, to);
      }
    }
    return out;
  }

 private:
  bool open(int a, int b) const {
    return clear_m_ <= 0 || (0.5 * (position(a) + position(b)) - centre_).norm() > clear_m_;
  }

  std::vector<double> e_, n_;
  std::vector<int> north_, east_;  // +1 / -1 per street
  Eigen::Vector2d centre_;
  double clear_m_ = 0;
};

double heading(const Eigen::Vector2d& d) { return std::atan2(d.y(), d.x()); }

TriMesh car_body(double length, double width, double height) {
  TriMesh m;
  const double l = length / 2, w = width / 2;
  add_box(&m, {-l, -w, 0.25}, {l, w, 1.0}, SurfaceKind::kDetail, SurfaceKind::kDetail, kCarBody);
  add_box(&m, {-0.7 * l, -0.92 * w, 1.0}, {0.4 * l, 0.92 * w, height}, SurfaceKind::kDetail, SurfaceKind::kDetail,
          kCarCabin);
  for (const double x : {-0.6 * l, 0.6 * l})
    for (const double side : {-1.0, 1.0}) {
      const double y0 = side * (w - 0.22), y1 = side * (w - 0.02);
      add_box(&m, {x - 0.32, std::min(y0, y1), 0.0}, {x + 0.32, std::max(y0, y1), 0.64}, SurfaceKind::kDetail,
              SurfaceKind::kDetail, kCarWheel);
    }
  return m;
}

}  // namespace

Traffic::Traffic(const SceneHints& hints, const TrafficSimConfig& config, double duration_s, std::uint64_t seed)
    : impl_(std::make_unique<Impl>()) {
  if (!(config.cars >= 0)) throw InputError("traffic.cars: must be >= 0 (0 turns traffic off)");
  if (!(config.speed_mps >= 0 && std::isfinite(config.speed_mps)))
    throw InputError("traffic.speed_mps: must be a finite number >= 0");
  const StreetNetwork net(hints);
  const std::vector<std::pair<int, int>> edges = net.edges();
  if (config.cars == 0 || edges.empty()) return;
  const double radius = std::max(0.5 * hints.streets.width_m, 1.0);  // corners [m]
  // Planned along the street centrelines; the rounded corners make the driven route up to 22 % shorter.
  const double route_m = 1.3 * config.speed_mps * (std::max(duration_s, 0.0) + 2.0) + 100.0;

  Rng rng(hash64(seed ^ 0x7261666669630000ULL));  // "traffic": a stream of its own
  const float paints[] = {0.07f, 0.16f, 0.30f, 0.45f, 0.62f, 0.24f};  // black, dark grey, red, silver, white, blue
  std::vector<std::pair<std::size_t, double>> starts;                 // (edge, distance from its start node)
  for (int k = 0; k < config.cars; ++k) {
    Car car;
    car.speed_mps = config.speed_mps;
    // A start at least 8 m from the others on the same piece (a few tries, then wherever it falls).
    std::size_t e = 0;
    double along = 0;
    for (int attempt = 0; attempt < 20; ++attempt) {
      e = static_cast<std::size_t>(rng.integer(static_cast<int>(edges.size())));
      const double len = (net.position(edges[e].second) - net.position(edges[e].first)).norm();
      along = rng.uniform(0.0, std::max(len - radius, 0.0));
      const bool crowded = std::any_of(starts.begin(), starts.end(), [&](const auto& s) {
        return s.first == e && std::abs(s.second - along) < 8.0;
      });
      if (!crowded) break;
    }
    starts.emplace_back(e, along);

    // The nodes it passes, then the pieces: straight runs between quarter circles at the turns.
    std::vector<int> nodes{edges[e].first, edges[e].second};
    double planned = (net.position(nodes[1]) - net.position(nodes[0])).norm();
    while (planned < along + route_m) {
      std::vector<int> options = net.next(nodes.back());
      if (options.size() > 1) {  // never straight back the way it came while there is another way
        const int previous = nodes[nodes.size() - 2];
        options.erase(std::remove(options.begin(), options.end(), previous), options.end());
      }
      if (options.empty()) break;  // an isolated piece: the car stops at its end
      nodes.push_back(options[static_cast<std::size_t>(rng.integer(static_cast<int>(options.size())))]);
      planned += (net.position(nodes.back()) - net.position(nodes[nodes.size() - 2])).norm();
    }
    Eigen::Vector2d at = net.position(nodes[0]);
    double s = 0;
    const auto add_line = [&](const Eigen::Vector2d& to) {
      const double len = (to - at).norm();
      if (len > 1e-9) car.route.push_back({s, len, at, heading(to - at), 0, 0});
      s += len;
      at = to;
    };
    for (std::size_t i = 1; i + 1 < nodes.size(); ++i) {
      const Eigen::Vector2d p0 = net.position(nodes[i - 1]), p1 = net.position(nodes[i]),
                            p2 = net.position(nodes[i + 1]);
      const Eigen::Vector2d d_in = (p1 - p0).normalized(), d_out = (p2 - p1).normalized();
      const double cross = d_in.x() * d_out.y() - d_in.y() * d_out.x();
      if (std::abs(cross) < 0.5) {  // straight on (or, at a dead end, straight back: it turns on the spot)
        add_line(p1);
        continue;
      }
      const double r = std::min({radius, 0.5 * (p1 - p0).norm(), 0.5 * (p2 - p1).norm()});
      add_line(p1 - r * d_in);
      const double turn = cross > 0 ? 1.0 : -1.0;  // left = counter-clockwise
      const Eigen::Vector2d left(-d_in.y(), d_in.x());
      const Eigen::Vector2d centre = at + turn * r * left;
      car.route.push_back({s, 0.5 * M_PI * r, centre, heading(at - centre), turn, r});
      s += 0.5 * M_PI * r;
      at = p1 + r * d_out;
    }
    add_line(net.position(nodes.back()));
    if (car.route.empty()) continue;
    car.s0_m = along;
    car.mesh_V = car_body(rng.uniform(4.2, 4.8), rng.uniform(1.75, 1.85), rng.uniform(1.42, 1.55));
    Eigen::Vector3d lo, hi;
    car.mesh_V.bounds(&lo, &hi);
    car.centre_V = 0.5 * (lo + hi);
    car.radius_m = 0.5 * (hi - lo).norm();
    car.paint = paints[rng.integer(6)];
    cars_.push_back(std::move(car));
  }
  impl_->device = rtcNewDevice(nullptr);
  if (!impl_->device) throw std::runtime_error("Embree: cannot create a device for the traffic");
}

Traffic::~Traffic() = default;

Eigen::Isometry3d Traffic::T_WV(std::size_t k, double t_s) const {
  const Car& car = cars_[k];
  const Piece& last = car.route.back();
  const double s = std::clamp(car.s0_m + car.speed_mps * t_s, 0.0, last.s_m + last.length_m);
  const auto it = std::upper_bound(car.route.begin(), car.route.end(), s,
                                   [](double v, const Piece& p) { return v < p.s_m; });
  const Piece& p = *(it == car.route.begin() ? it : it - 1);
  const double u = s - p.s_m;
  Eigen::Vector2d xy;
  double yaw;
  if (p.turn == 0) {
    yaw = p.angle_rad;
    xy = p.a_W + u * Eigen::Vector2d(std::cos(yaw), std::sin(yaw));
  } else {
    const double phi = p.angle_rad + p.turn * u / p.radius_m;
    xy = p.a_W + p.radius_m * Eigen::Vector2d(std::cos(phi), std::sin(phi));
    yaw = phi + p.turn * 0.5 * M_PI;
  }
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(xy.x(), xy.y(), 0.0);
  return T;
}

std::pair<Eigen::Vector3d, double> Traffic::bounding_sphere(std::size_t k, double t0_s, double t1_s) const {
  // The car's own sphere at the middle of the window, grown by how far it can drive in half the window.
  const Car& car = cars_[k];
  return {T_WV(k, 0.5 * (t0_s + t1_s)) * car.centre_V,
          car.radius_m + 0.5 * car.speed_mps * std::abs(t1_s - t0_s) + 1e-3};
}

std::unique_ptr<TrafficSnapshot> Traffic::snapshot(double t0_s, double t1_s,
                                                   const std::vector<std::size_t>* only) const {
  std::vector<std::size_t> cars;
  if (only) {
    cars = *only;
  } else {
    for (std::size_t k = 0; k < size(); ++k) cars.push_back(k);
  }
  return std::unique_ptr<TrafficSnapshot>(new TrafficSnapshot(*this, t0_s, std::max(t0_s, t1_s), std::move(cars)));
}

TrafficSnapshot::TrafficSnapshot(const Traffic& traffic, double t0_s, double t1_s, std::vector<std::size_t> cars)
    : traffic_(traffic), t0_s_(t0_s), t1_s_(t1_s), cars_(std::move(cars)) {
  // One geometry for all its cars: Embree's cost per geometry would dominate a scene of a few thousand triangles.
  std::size_t vertices = 0;
  first_.push_back(0);
  for (const std::size_t k : cars_) {
    vertices += traffic.mesh_V(k).p_W.size();
    first_.push_back(first_.back() + static_cast<std::uint32_t>(traffic.mesh_V(k).triangles.size()));
  }
  if (cars_.empty()) return;
  RTCDevice device = traffic.impl_->device;
  RTCScene scene = rtcNewScene(device);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_LOW);  // rebuilt every frame, traced by one frame's rays
  const unsigned steps = t1_s > t0_s ? 2 : 1;
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetGeometryTimeStepCount(geom, steps);
  for (unsigned step = 0; step < steps; ++step) {
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, step, RTC_FORMAT_FLOAT3,
                                                           3 * sizeof(float), vertices));
    for (const std::size_t k : cars_) {
      const Eigen::Isometry3d T = traffic.T_WV(k, step == 0 ? t0_s : t1_s);
      for (const Eigen::Vector3d& p_V : traffic.mesh_V(k).p_W) {
        const Eigen::Vector3d p = T * p_V;
        for (int c = 0; c < 3; ++c) *v++ = static_cast<float>(p[c]);
      }
    }
  }
  auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                              3 * sizeof(unsigned), first_.back()));
  unsigned base = 0;
  for (const std::size_t k : cars_) {
    const TriMesh& m = traffic.mesh_V(k);
    for (const Eigen::Vector3i& t : m.triangles)
      for (int c = 0; c < 3; ++c) *idx++ = base + static_cast<unsigned>(t[c]);
    base += static_cast<unsigned>(m.p_W.size());
  }
  rtcCommitGeometry(geom);
  rtcAttachGeometryByID(scene, geom, 0);
  rtcReleaseGeometry(geom);
  rtcCommitScene(scene);
  if (const RTCError error = rtcGetDeviceError(device); error != RTC_ERROR_NONE) {
    rtcReleaseScene(scene);
    throw std::runtime_error("Embree: building the traffic scene failed with error " + std::to_string(error));
  }
  scene_ = scene;
}

TrafficSnapshot::~TrafficSnapshot() {
  if (scene_) rtcReleaseScene(static_cast<RTCScene>(scene_));
}

float TrafficSnapshot::ray_time(double t_s) const {
  if (!(t1_s_ > t0_s_)) return 0.0f;
  return static_cast<float>(std::clamp((t_s - t0_s_) / (t1_s_ - t0_s_), 0.0, 1.0));
}

namespace {
void init_ray(RTCRay& ray, const Eigen::Vector3d& o, const Eigen::Vector3d& d, float time, double t_max) {
  ray.org_x = static_cast<float>(o.x());
  ray.org_y = static_cast<float>(o.y());
  ray.org_z = static_cast<float>(o.z());
  ray.dir_x = static_cast<float>(d.x());
  ray.dir_y = static_cast<float>(d.y());
  ray.dir_z = static_cast<float>(d.z());
  ray.tnear = 0.0f;
  ray.tfar = static_cast<float>(std::min<double>(t_max, std::numeric_limits<float>::max()));
  ray.time = time;
  ray.mask = 0xFFFFFFFF;
  ray.id = 0;
  ray.flags = 0;
}
}  // namespace

bool TrafficSnapshot::intersect(const Eigen::Vector3d& origin_W, const Eigen::Vector3d& dir_W, double t_s,
                                double t_max, CarHit* hit) const {
  if (!scene_ || !(t_max > 0)) return false;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  init_ray(rh.ray, origin_W, dir_W, ray_time(t_s), t_max);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(static_cast<RTCScene>(scene_), &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  hit->t_m = rh.ray.tfar;
  local_hit(rh.hit.primID, rh.hit.u, rh.hit.v, hit);
  return true;
}

bool TrafficSnapshot::occluded(const Eigen::Vector3d& origin_W, const Eigen::Vector3d& dir_W, double t_s,
                               double t_max) const {
  if (!scene_ || !(t_max > 0)) return false;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray;
  init_ray(ray, origin_W, dir_W, ray_time(t_s), t_max);
  rtcOccluded1(static_cast<RTCScene>(scene_), &context, &ray);
  return ray.tfar < 0;
}

void TrafficSnapshot::local_hit(std::uint32_t primitive, float u, float v, CarHit* hit) const {
  const auto i =
      static_cast<std::size_t>(std::upper_bound(first_.begin(), first_.end(), primitive) - first_.begin() - 1);
  const std::size_t car = cars_[i];
  const std::uint32_t triangle = primitive - first_[i];
  const TriMesh& m = traffic_.mesh_V(car);
  const Eigen::Vector3i& t = m.triangles[triangle];
  hit->car = car;
  hit->p_V = (1.0 - u - v) * m.p_W[t[0]] + static_cast<double>(u) * m.p_W[t[1]] + static_cast<double>(v) * m.p_W[t[2]];
  hit->n_V = m.normal(triangle);
  hit->part = m.building_id[triangle];
}

}  // namespace twinslam::sim

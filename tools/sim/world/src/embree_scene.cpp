#include "twinslam/sim/world/embree_scene.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <embree3/rtcore.h>

#include "twinslam/twin/mesh.hpp"

namespace twinslam::sim {

struct EmbreeScene::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
};

EmbreeScene::EmbreeScene(const TriMesh& mesh) : mesh_(mesh), impl_(std::make_unique<Impl>()) {
  impl_->device = rtcNewDevice(nullptr);
  if (!impl_->device) throw std::runtime_error("Embree: cannot create a device");
  impl_->scene = rtcNewScene(impl_->device);
  rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);  // static scene, traced many times
  if (!mesh.triangles.empty()) {  // an empty scene is valid (every ray misses); an empty buffer is not
    RTCGeometry geom = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                           3 * sizeof(float), mesh.p_W.size()));
    for (std::size_t i = 0; i < mesh.p_W.size(); ++i)
      for (int k = 0; k < 3; ++k) v[3 * i + k] = static_cast<float>(mesh.p_W[i][k]);
    auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                3 * sizeof(unsigned), mesh.triangles.size()));
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
      for (int k = 0; k < 3; ++k) idx[3 * i + k] = static_cast<unsigned>(mesh.triangles[i][k]);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(impl_->scene, geom);
    rtcReleaseGeometry(geom);
  }
  rtcCommitScene(impl_->scene);
  if (const RTCError error = rtcGetDeviceError(impl_->device); error != RTC_ERROR_NONE) {
    rtcReleaseScene(impl_->scene);
    rtcReleaseDevice(impl_->device);
    throw std::runtime_error("Embree: building the scene failed with error " + std::to_string(error));
  }
}

EmbreeScene::~EmbreeScene() {
  if (impl_->scene) rtcReleaseScene(impl_->scene);
  if (impl_->device) rtcReleaseDevice(impl_->device);
}

void* EmbreeScene::rtc_scene() const { return impl_->scene; }

bool EmbreeScene::intersect(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t_min, double t_max,
                            RayHit* hit) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  rh.ray.org_x = static_cast<float>(o.x());
  rh.ray.org_y = static_cast<float>(o.y());
  rh.ray.org_z = static_cast<float>(o.z());
  rh.ray.dir_x = static_cast<float>(d.x());
  rh.ray.dir_y = static_cast<float>(d.y());
  rh.ray.dir_z = static_cast<float>(d.z());
  rh.ray.tnear = static_cast<float>(t_min);
  rh.ray.tfar = static_cast<float>(std::min<double>(t_max, std::numeric_limits<float>::max()));
  rh.ray.time = 0;
  rh.ray.mask = 0xFFFFFFFF;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  hit->t_m = rh.ray.tfar;
  hit->triangle = rh.hit.primID;
  Eigen::Vector3d n(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
  n.normalize();
  hit->n_W = n.dot(d) > 0 ? Eigen::Vector3d(-n) : n;
  return true;
}

namespace {

struct ClosestQuery {
  const TriMesh* mesh;
  Eigen::Vector3d p_W;
  double best_m;
  std::uint32_t best_triangle = 0;
};

bool closest_callback(RTCPointQueryFunctionArguments* args) {
  auto* q = static_cast<ClosestQuery*>(args->userPtr);
  const auto& t = q->mesh->triangles[args->primID];
  const Eigen::Vector3d c =
      twin::closest_point_on_triangle(q->p_W, q->mesh->p_W[t[0]], q->mesh->p_W[t[1]], q->mesh->p_W[t[2]]);
  const double d = (c - q->p_W).norm();
  if (d < q->best_m) {
    q->best_m = d;
    q->best_triangle = args->primID;
    args->query->radius = static_cast<float>(d);  // shrink the search ball
    return true;
  }
  return false;
}

}  // namespace

double EmbreeScene::closest_distance(const Eigen::Vector3d& p_W, double max_m, std::uint32_t* triangle) const {
  ClosestQuery q{&mesh_, p_W, std::numeric_limits<double>::infinity()};
  RTCPointQuery query;
  query.x = static_cast<float>(p_W.x());
  query.y = static_cast<float>(p_W.y());
  query.z = static_cast<float>(p_W.z());
  query.time = 0;
  query.radius = static_cast<float>(max_m);
  RTCPointQueryContext context;
  rtcInitPointQueryContext(&context);
  rtcPointQuery(impl_->scene, &query, &context, closest_callback, &q);
  if (triangle != nullptr && q.best_m <= max_m) *triangle = q.best_triangle;
  return q.best_m <= max_m ? q.best_m : std::numeric_limits<double>::infinity();
}

}  // namespace twinslam::sim

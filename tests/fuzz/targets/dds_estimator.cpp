// The estimator service's message handlers (estimator_handler.hpp) fed arbitrary samples: IMU samples, GNSS fixes,
// Registrations (any status, correction, information - non-symmetric, NaN, indefinite - and keyframe stamp, known or
// not) and FeatureFrames (any ids and bearings), in the order the worker hands them over. The handler must never
// throw (the worker would die) and never publish a non-finite pose: an Odometry is either finite or not sent.
// Well formed (all-zero input): a vehicle at rest looking at a fixed set of points, at 20 Hz with 200 Hz IMU, in a
// twin mode started by --initial-pose, so the estimator initializes, publishes LocalMaps and fuses registrations.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <spdlog/spdlog.h>

#include "estimator_handler.hpp"
#include "harness.hpp"
#include "sample_reader.hpp"
#include "twinslam/dds/convert.hpp"

namespace {

namespace est = twinslam::estimator;
namespace msg = twinslam::msg;
using twinslam::fuzz::SampleReader;

constexpr std::int64_t kFrame_ns = 50'000'000, kImu_ns = 5'000'000;
constexpr int kMaxFrames = 40;  // 2 s of data per input: initialization, keyframes and registrations, kept quick

est::EstimatorNodeOptions options() {
  est::EstimatorNodeOptions o;
  o.fusion.fuse_registrations = true;
  o.fusion.align_from_gnss = true;
  o.initial_pose = est::InitialPose{Eigen::Vector3d(0, 0, 2), 0.0, std::nullopt};
  o.origin = twinslam::twin::GeoOrigin{47.3769, 8.5417, 408.0};
  return o;
}

// The fixed scene: 60 points 4-12 m in front of the camera, seen from the origin.
Eigen::Vector3d scene_bearing(std::size_t k) {
  const double a = 0.37 * static_cast<double>(k), depth = 4.0 + static_cast<double>(k % 9);
  return Eigen::Vector3d(std::cos(a) * 0.6, std::sin(a) * 0.45, 1.0).normalized() * depth / depth;
}

msg::FeatureFrame read_frame(SampleReader& in, std::int64_t stamp_ns) {
  msg::FeatureFrame f;
  f.vehicle_id("uav1");
  f.stamp_ns(stamp_ns);
  const std::size_t count = in.u8() % 4 == 3 ? in.u8() : 60;
  for (std::size_t k = 0; k < count; ++k) {
    msg::Feature x;
    x.id(in.u8() % 8 == 7 ? static_cast<unsigned long long>(in.i64()) : k);
    const Eigen::Vector3d b = scene_bearing(k);
    x.bearing_C(twinslam::dds::to_msg(Eigen::Vector3d(in.value(b.x()), in.value(b.y()), in.value(b.z()))));
    f.features().push_back(x);
  }
  return f;
}

std::vector<est::ImuSample> read_imu(SampleReader& in, std::int64_t from_ns, std::int64_t to_ns) {
  std::vector<est::ImuSample> out;
  for (std::int64_t t = from_ns; t < to_ns; t += kImu_ns) {
    const std::int64_t stamp = in.u8() % 16 == 15 ? t - in.u8() * kImu_ns : t;  // now and then out of order
    out.push_back({stamp, Eigen::Vector3d(in.value(0.0), in.value(0.0), in.value(0.0)),
                   Eigen::Vector3d(in.value(0.0), in.value(0.0), in.value(9.81))});
  }
  return out;
}

msg::GnssFix read_fix(SampleReader& in, std::int64_t stamp_ns) {
  msg::GnssFix g;
  g.vehicle_id("uav1");
  g.stamp_ns(stamp_ns);
  g.latitude_deg(in.value(47.3769));
  g.longitude_deg(in.value(8.5417));
  g.altitude_m(in.value(410.0));
  for (int i = 0; i < 9; ++i) g.covariance_enu_m2()[static_cast<std::size_t>(i)] = in.value(i % 4 == 0 ? 4.0 : 0.0);
  return g;
}

msg::Registration read_registration(SampleReader& in, const std::vector<std::int64_t>& keyframes) {
  msg::Registration r;
  r.vehicle_id("uav1");
  const std::size_t pick = in.u8();
  r.keyframe_stamp_ns(!keyframes.empty() && pick % 8 != 7 ? keyframes[pick % keyframes.size()] : in.i64());
  r.status(in.u8() % 4 == 3 ? static_cast<msg::RegistrationStatus>(in.u8() % 9) : msg::REG_ACCEPTED);
  msg::Pose c = twinslam::dds::to_msg(Eigen::Isometry3d::Identity());
  c.q().w(in.value(1.0));
  c.q().x(in.value(0.0));
  c.q().y(in.value(0.0));
  c.q().z(in.value(0.0));
  c.p().x(in.value(0.0));
  c.p().y(in.value(0.0));
  c.p().z(in.value(0.0));
  r.correction_W(c);
  for (int i = 0; i < 36; ++i) r.information()[static_cast<std::size_t>(i)] = in.value(i % 7 == 0 ? 100.0 : 0.0);
  r.readmitted(in.u8() % 8 == 7);
  return r;
}

void check_finite(const msg::Odometry& o) {
  const Eigen::Isometry3d T = twinslam::dds::from_msg(o.T_WB());
  if (!T.matrix().allFinite() || !twinslam::dds::from_msg(o.T_LB()).matrix().allFinite()) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool quiet = [] {
    spdlog::set_level(spdlog::level::off);  // refusals are logged per sample: expected here, not news
    return true;
  }();
  (void)quiet;
  SampleReader in(data, size);
  twinslam::dds::Counters counters;
  est::EstimatorHandler handler(counters, options());
  std::vector<std::int64_t> keyframes;
  const std::int64_t t0 = 1'000'000'000'000'000'000LL;
  for (int k = 0; k < kMaxFrames; ++k) {
    const std::int64_t stamp = t0 + k * kFrame_ns;
    std::vector<est::GlobalInput> global;
    const std::uint8_t side = in.u8();
    if (side % 4 == 1) global.emplace_back(read_fix(in, stamp - kImu_ns));
    if (side % 4 == 2) global.emplace_back(read_registration(in, keyframes));
    const est::EstimatorHandler::Output out =
        handler.handle(read_frame(in, stamp), read_imu(in, stamp - kFrame_ns + kImu_ns, stamp + kImu_ns), std::move(global));
    if (out.odometry) check_finite(*out.odometry);
    if (out.local_map) keyframes.push_back(out.local_map->keyframe_stamp_ns());
  }
  if (std::getenv("FUZZ_DDS_VERBOSE")) {
    for (const auto& [name, n] : counters.snapshot()) std::fprintf(stderr, "%s=%llu ", name.c_str(), n);
    std::fprintf(stderr, "\n");
  }
  return 0;
}

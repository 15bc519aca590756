// The tracking service's frame handler (tracking_handler.hpp) fed arbitrary samples: Images of any size, step,
// encoding, stamp and bytes, with IMU samples of any value in between, in the order the worker hands them over. The
// handler must never throw (the worker would die) and never publish a feature outside the image or with a
// non-finite bearing. Well formed (all-zero input): a 160 x 100 camera panning slowly over a fixed texture at 20 Hz
// with 200 Hz IMU, so the frontend detects, tracks and predicts with the gyro.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <spdlog/spdlog.h>

#include "harness.hpp"
#include "sample_reader.hpp"
#include "tracking_handler.hpp"
#include "twinslam/dds/convert.hpp"

namespace {

namespace trk = twinslam::tracking;
namespace msg = twinslam::msg;
using twinslam::fuzz::SampleReader;

constexpr std::int64_t kFrame_ns = 50'000'000, kImu_ns = 5'000'000;
constexpr int kMaxFrames = 12, kWidth = 160, kHeight = 100;

trk::TrackingNodeOptions options() {
  trk::TrackingNodeOptions o;
  o.camera.intrinsics.width = kWidth;
  o.camera.intrinsics.height = kHeight;
  o.camera.intrinsics.fu = o.camera.intrinsics.fv = 100.0;
  o.camera.intrinsics.cu = 79.5;
  o.camera.intrinsics.cv = 49.5;
  return o;
}

// A fixed texture seen 1 px further right every frame.
std::uint8_t texture(int u, int v, int frame) {
  const int x = u + frame, y = v;
  return static_cast<std::uint8_t>((x * 37 + y * 91 + ((x / 7) ^ (y / 5)) * 53) & 0xff);
}

msg::Image read_image(SampleReader& in, std::int64_t stamp_ns, int frame) {
  msg::Image m;
  m.vehicle_id("uav1");
  m.stamp_ns(in.u8() % 16 == 15 ? in.i64() : stamp_ns);  // now and then a stamp from anywhere
  m.encoding(in.u8() % 16 == 15 ? "rgb8" : "mono8");
  const std::uint8_t shape = in.u8();
  m.width(shape % 16 == 15 ? static_cast<std::uint32_t>(in.i64()) : kWidth);
  m.height(shape % 16 == 14 ? static_cast<std::uint32_t>(in.i64()) : kHeight);
  m.step(shape % 16 == 13 ? static_cast<std::uint32_t>(in.i64()) : kWidth);
  const std::size_t bytes = shape % 16 == 12 ? in.u8() * 64u : static_cast<std::size_t>(kWidth) * kHeight;
  m.data().resize(bytes);
  for (std::size_t i = 0; i < bytes; ++i) {
    m.data()[i] = texture(static_cast<int>(i % kWidth), static_cast<int>(i / kWidth), frame);
  }
  for (std::size_t k = in.u8() % 8 == 7 ? in.u8() : 0; k > 0 && bytes > 0; --k) {  // overwritten bytes
    m.data()[static_cast<std::size_t>(in.i64() & 0x7fffffff) % bytes] = in.u8();
  }
  return m;
}

std::vector<twinslam::imu::ImuSample> read_imu(SampleReader& in, std::int64_t from_ns, std::int64_t to_ns) {
  std::vector<twinslam::imu::ImuSample> out;  // in stamp order: the worker refuses the others before the handler
  for (std::int64_t t = from_ns; t < to_ns; t += kImu_ns) {
    out.push_back({t, Eigen::Vector3d(in.value(0.0), in.value(-0.01), in.value(0.0)),
                   Eigen::Vector3d(in.value(0.0), in.value(0.0), in.value(9.81))});
  }
  return out;
}

void check(const msg::FeatureFrame& f) {
  for (const msg::Feature& x : f.features()) {
    const Eigen::Vector3d b = twinslam::dds::from_msg(x.bearing_C());
    if (!b.allFinite() || !(x.u() >= -1.0f && x.u() <= kWidth + 1.0f && x.v() >= -1.0f && x.v() <= kHeight + 1.0f)) {
      __builtin_trap();
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool quiet = [] {
    spdlog::set_level(spdlog::level::off);  // skipped frames are logged per sample: expected here, not news
    return true;
  }();
  (void)quiet;
  SampleReader in(data, size);
  twinslam::dds::Counters counters;
  trk::TrackingHandler handler(counters, options());
  const std::int64_t t0 = 1'000'000'000'000'000'000LL;
  for (int k = 0; k < kMaxFrames; ++k) {
    const std::int64_t stamp = t0 + k * kFrame_ns;
    auto imu = read_imu(in, stamp - kFrame_ns + kImu_ns, stamp + kImu_ns);
    if (const auto out = handler.handle(read_image(in, stamp, k), std::move(imu))) check(*out);
  }
  return 0;
}

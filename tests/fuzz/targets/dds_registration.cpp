// The registration service's message handlers (registration_handler.hpp) fed arbitrary samples, as any peer on the
// link may send them: MapTiles with any key, bounds and Draco bytes (a real tile of a synthetic street, flipped, cut,
// or raw bytes), then LocalMaps with any pose, landmark count, positions (NaN, inf, huge), qualities, landmark
// covariances and keyframe covariance. The handler must answer every LocalMap without throwing (the service's worker
// would die), and an accepted Registration must be one the estimator can fuse: a finite rigid correction and a
// finite, symmetric, positive semi-definite information (registration_problem).
// Input: bytes read by SampleReader below, each choice byte 0 meaning "well formed" (an all-zero input is a valid
// tile set and a LocalMap near it); the reader returns zeros when the input runs out.
#include <Eigen/Eigenvalues>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include <spdlog/spdlog.h>

#include "harness.hpp"
#include "sample_reader.hpp"
#include "registration_handler.hpp"
#include "synthetic_twin.hpp"
#include "twinslam/dds/convert.hpp"
#include "twinslam/twin/store.hpp"

namespace {

namespace msg = twinslam::msg;
namespace twin = twinslam::twin;
namespace registration = twinslam::registration;
namespace tdds = twinslam::dds;

using twinslam::fuzz::SampleReader;

struct Tile {
  std::string key;
  Eigen::AlignedBox3d bounds;
  std::vector<std::uint8_t> draco;
};

const std::vector<Tile>& street_tiles() {
  static const std::vector<Tile> tiles = [] {
    std::vector<Tile> out;
    for (const auto& [key, t] : registration::test::split_tiles(registration::test::sample_grid(registration::test::city_surfaces(), 1.0))) {
      twin::Mesh m;
      m.p_W = t.p_W;
      m.n_W = t.n_W;
      Eigen::AlignedBox3d b;
      for (const auto& p : t.p_W) b.extend(p);
      out.push_back({"street/" + key.str(), b, twin::encode_points(m, twin::StoreConfig{})});
    }
    return out;
  }();
  return tiles;
}

// The i-th tile sent: by default the i-th street tile.
msg::MapTile read_tile(SampleReader& in, std::size_t i) {
  const Tile& real = street_tiles()[(i + in.u8()) % street_tiles().size()];
  msg::MapTile t;
  t.tile_key(in.text(real.key));
  for (int k = 0; k < 3; ++k) {
    t.bounds_W()[k] = in.value(real.bounds.min()[k]);
    t.bounds_W()[3 + k] = in.value(real.bounds.max()[k]);
  }
  std::vector<std::uint8_t> bytes = real.draco;
  switch (in.u8() % 4) {
    case 1:  // flipped bytes
      for (int n = 1 + in.u8() % 8; n > 0; --n) bytes[in.u16() % bytes.size()] ^= static_cast<std::uint8_t>(1 + in.u8() % 255);
      break;
    case 2:  // cut
      bytes.resize(in.u16() % bytes.size());
      break;
    case 3:  // raw
      bytes.assign(in.u8() % 64, 0);
      for (auto& b : bytes) b = in.u8();
      break;
    default: break;
  }
  t.points_draco(bytes);
  return t;
}

msg::Pose read_pose(SampleReader& in, const Eigen::Vector3d& p) {
  msg::Pose m = tdds::to_msg(Eigen::Isometry3d(Eigen::Translation3d(p)));
  m.q().w(in.value(1.0));
  m.q().x(in.value(0.0));
  m.q().y(in.value(0.0));
  m.q().z(in.value(0.0));
  m.p().x(in.value(p.x()));
  m.p().y(in.value(p.y()));
  m.p().z(in.value(p.z()));
  return m;
}

msg::LocalMap read_local_map(SampleReader& in) {
  msg::LocalMap m;
  m.vehicle_id(in.text("uav1"));
  m.keyframe_stamp_ns(in.u8() % 4 == 3 ? in.i64() : 1'000'000'000LL * (1 + in.u8()));
  const Eigen::Vector3d body = registration::test::kCentre + Eigen::Vector3d(0, -45, 8);
  m.T_LB(read_pose(in, body));
  m.T_WL(read_pose(in, Eigen::Vector3d::Zero()));
  const auto surface = registration::test::sample_noisy(registration::test::city_surfaces(), 400, 0.1, in.u8());
  const std::size_t count = in.u8() % 4 == 3 ? in.u16() : 60 + 4 * std::size_t{in.u8()};
  for (std::size_t k = 0; k < count && (k < 400 || !in.done()); ++k) {
    msg::Landmark l;
    l.id(k);
    const Eigen::Vector3d& p = surface[k % surface.size()];
    l.p_L(tdds::to_msg(Eigen::Vector3d(in.value(p.x()), in.value(p.y()), in.value(p.z()))));
    l.quality(static_cast<float>(in.value(1.0)));
    l.cov_L({0.01f, 0.0f, 0.0f, 0.01f, 0.0f, 0.01f});
    if (in.u8() % 8 == 7) {
      for (auto& c : l.cov_L()) c = static_cast<float>(in.value(0.01));
    }
    m.landmarks().push_back(l);
  }
  const std::size_t n_cov = in.u8() % 4 == 0 ? 36 : in.u8() % 40;
  for (std::size_t k = 0; k < n_cov; ++k) m.T_WB_covariance().push_back(in.value(k % 7 == 0 ? 1.0 : 0.0));
  return m;
}

// What the estimator requires of an accepted registration (map_registration_factor.cpp registration_problem).
void check_fusable(const msg::Registration& r) {
  if (r.status() != msg::REG_ACCEPTED) return;
  const Eigen::Isometry3d T = tdds::from_msg(r.correction_W());
  const Eigen::Matrix3d R = T.linear();
  Eigen::Matrix<double, 6, 6> H;
  for (int i = 0; i < 36; ++i) H(i / 6, i % 6) = r.information()[static_cast<std::size_t>(i)];
  const double scale = std::max(H.cwiseAbs().maxCoeff(), 1e-300);
  const bool ok = T.matrix().allFinite() && (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < 1e-6 &&
                  H.allFinite() && (H - H.transpose()).cwiseAbs().maxCoeff() <= 1e-6 * scale &&
                  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>>(H).eigenvalues().minCoeff() >= -1e-9 * scale;
  if (!ok) __builtin_trap();  // an accepted registration the estimator would have to refuse as invalid
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool quiet = [] {
    spdlog::set_level(spdlog::level::off);  // a malformed key per input is expected here, not news
    return true;
  }();
  (void)quiet;
  SampleReader in(data, size);
  tdds::Counters counters;
  registration::RegistrationNodeOptions options;
  options.max_landmarks = 5000;  // the cap's path, at a size a fuzzer iterates quickly
  registration::RegistrationHandler handler(counters, options);
  const std::size_t tiles = street_tiles().size() - in.u8() % (street_tiles().size() + 1);
  for (std::size_t i = 0; i < tiles; ++i) handler.on_tile(read_tile(in, i));
  for (int n = 1 + in.u8() % 3; n > 0; --n) {
    const msg::Registration r = handler.on_local_map(read_local_map(in));
    if (std::getenv("FUZZ_DDS_VERBOSE")) std::fprintf(stderr, "status %d: %s\n", static_cast<int>(r.status()), r.reason().c_str());
    check_fusable(r);
  }
  return 0;
}

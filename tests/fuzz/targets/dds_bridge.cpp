// What the bridge (and an MCAP recording) makes of arbitrary samples, as any peer on the link may send them: Odometry,
// GnssFix, LocalMap, Registration and MapTile for a few vehicles, in any order, through common/foxglove's
// DerivedChannels. Any sample must give messages that are JSON whose keys are exactly those their schema requires,
// on a topic of the vehicle that sent it ("/twin/tiles" for tiles, latched by the tile's key); the path never holds
// more poses than its limit; a tile whose mesh does not decode gives nothing, counted — never an exception (a Fast
// DDS listener thread would die). MapTile meshes are a valid Draco box, that box cut or with bytes flipped, or raw
// input bytes. Input: choice bytes (0: well formed) read by SampleReader.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "harness.hpp"
#include "sample_reader.hpp"
#include "twinslam/foxglove/derived_channels.hpp"
#include "twinslam/twin/store.hpp"

namespace {

namespace msg = twinslam::msg;
namespace foxglove = twinslam::foxglove;
using twinslam::fuzz::SampleReader;

constexpr int kMaxMessages = 24;
constexpr std::size_t kMaxPath = 16;

const std::vector<std::uint8_t>& box_draco() {
  static const std::vector<std::uint8_t> bytes = [] {
    twinslam::twin::Mesh box;
    box.p_W = {{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 12}};
    box.triangles = {{0, 1, 2}, {0, 2, 3}};
    return twinslam::twin::encode_mesh(box, twinslam::twin::StoreConfig{});
  }();
  return bytes;
}

msg::Pose pose(SampleReader& in, double x) {
  msg::Pose p;
  p.q().w(in.value(1.0)); p.q().x(in.value(0.0)); p.q().y(in.value(0.0)); p.q().z(in.value(0.0));
  p.p().x(in.value(x)); p.p().y(in.value(0.0)); p.p().z(in.value(10.0));
  return p;
}

std::string vehicle(SampleReader& in) { return in.text(in.u8() % 2 ? "uav1" : "uav0"); }

std::vector<foxglove::DerivedMessage> one_sample(SampleReader& in, foxglove::DerivedChannels& channels, int i,
                                                 std::string* sender) {
  switch (in.u8() % 5) {
    case 0: {
      msg::Odometry m;
      m.vehicle_id(*sender = vehicle(in));
      m.stamp_ns(in.i64());
      m.status(static_cast<msg::OdometryStatus>(in.u8() % 5));
      m.T_WB(pose(in, 3.0 * i));
      return channels.on(m);
    }
    case 1: {
      msg::GnssFix m;
      m.vehicle_id(*sender = vehicle(in));
      m.latitude_deg(in.value(47.0));
      m.longitude_deg(in.value(8.0));
      for (double& c : m.covariance_enu_m2()) c = in.value(1.0);
      return channels.on(m);
    }
    case 2: {
      msg::LocalMap m;
      m.vehicle_id(*sender = vehicle(in));
      m.keyframe_stamp_ns(in.u8());
      m.T_WL(pose(in, 0.0));
      m.landmarks().resize(in.u8() % 40);
      for (msg::Landmark& l : m.landmarks()) {
        l.p_L().x(in.value(1.0)); l.p_L().y(in.value(2.0)); l.p_L().z(in.value(3.0));
        l.quality(static_cast<float>(in.value(0.5)));
      }
      return channels.on(m);
    }
    case 3: {
      msg::Registration m;
      m.vehicle_id(*sender = vehicle(in));
      m.keyframe_stamp_ns(in.u8());
      m.status(static_cast<msg::RegistrationStatus>(in.u8() % 11));
      m.reason(in.text(""));
      m.correction_W(pose(in, 0.0));
      for (double& e : m.information_eigenvalues()) e = in.value(1.0);
      m.rmse_m(in.value(0.1));
      return channels.on(m);
    }
    default: {
      msg::MapTile m;
      m.tile_key(in.text("twin/0_0"));
      *sender = "";
      const std::uint8_t kind = in.u8() % 4;
      if (kind != 3) m.mesh_draco(box_draco());
      if (kind == 1) m.mesh_draco().resize(in.u8() % m.mesh_draco().size());
      if (kind == 2) m.mesh_draco()[in.u8() % m.mesh_draco().size()] ^= static_cast<std::uint8_t>(in.u8() | 1);
      if (kind == 3) m.mesh_draco().resize(in.u8() % 64, in.u8());
      return channels.on(m);
    }
  }
}

void check(const foxglove::DerivedMessage& d, const std::string& sender) {
  const auto j = nlohmann::json::parse(d.json, nullptr, /*allow_exceptions=*/false);
  if (!j.is_object() || d.schema == nullptr) __builtin_trap();  // not JSON
  const auto schema = nlohmann::json::parse(d.schema->jsonschema);
  std::set<std::string> keys, required;
  for (const auto& [k, v] : j.items()) keys.insert(k);
  for (const auto& k : schema["required"]) required.insert(k.get<std::string>());
  if (keys != required) __builtin_trap();  // a message its schema does not describe
  const bool tile = d.topic == "/twin/tiles";
  if (tile != d.latch_key.has_value()) __builtin_trap();  // tiles, and only tiles, are latched (even keyless)
  if (!tile && d.topic.rfind(foxglove::DerivedChannels::prefix(sender) + "/", 0) != 0) __builtin_trap();
  if (d.schema->name == foxglove::poses_in_frame_schema().name && j["poses"].size() > kMaxPath) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  SampleReader in(data, size);
  foxglove::DerivedChannelsConfig config;
  config.max_path_poses = kMaxPath;
  config.kept_local_maps = 4;
  foxglove::DerivedChannels channels(config);
  for (int i = 0; i < kMaxMessages && !(i > 0 && in.done()); ++i) {
    std::string sender;
    for (const foxglove::DerivedMessage& d : one_sample(in, channels, i, &sender)) check(d, sender);
  }
  return 0;
}

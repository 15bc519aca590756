// The ingest service's lockstep handlers (ack_book.hpp) fed arbitrary samples: FrameAcks and Heartbeats of any
// vehicle, service, state and stamp, in any order. Checked against a model written here from the contract: a
// service's acknowledged frame is the newest stamp it acknowledged for this vehicle (never taken back by a late
// sample), and a service is ready once it said READY or RUNNING for this vehicle or for every vehicle (empty id).
// Input: choice bytes (0: well formed) read by SampleReader; an all-zero input is the estimator acknowledging frames.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "ack_book.hpp"
#include "harness.hpp"
#include "sample_reader.hpp"

namespace {

namespace msg = twinslam::msg;
using twinslam::fuzz::SampleReader;

constexpr int kMaxMessages = 64;
const std::vector<std::string> kServices = {"estimator", "tracking", ""};

std::string pick(SampleReader& in, const std::vector<std::string>& names, const std::string& fallback) {
  const std::uint8_t c = in.u8();
  return c % 16 == 15 ? in.text(fallback) : names[c % names.size()];
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  SampleReader in(data, size);
  twinslam::ingest::AckBook book("uav1");
  std::map<std::string, std::int64_t> acked;  // the model
  std::set<std::string> ready, seen = {kServices.begin(), kServices.end()};
  for (int k = 0; k < kMaxMessages && !in.done(); ++k) {
    const std::string vehicle = pick(in, {"uav1", "uav1", "uav2", ""}, "uav1");
    const std::string service = pick(in, kServices, "estimator");
    seen.insert(service);
    if (in.u8() % 4 != 3) {
      msg::FrameAck a;
      a.vehicle_id(vehicle);
      a.service(service);
      a.stamp_ns(in.u8() % 8 == 7 ? in.i64() : 1'000'000'000LL + 50'000'000LL * k);
      a.seq(static_cast<unsigned long long>(k));
      book.on_ack(a);
      if (vehicle == "uav1") {
        const auto [it, inserted] = acked.try_emplace(service, a.stamp_ns());
        if (!inserted) it->second = std::max(it->second, a.stamp_ns());
      }
    } else {
      msg::Heartbeat hb;
      hb.service(service);
      hb.vehicle_id(vehicle);
      hb.state(static_cast<msg::ServiceState>(in.u8() % 7));  // 6: outside the enum
      book.on_heartbeat(hb);
      if ((vehicle.empty() || vehicle == "uav1") &&
          (hb.state() == msg::SVC_READY || hb.state() == msg::SVC_RUNNING)) {
        ready.insert(service);
      }
    }
    for (const std::string& s : seen) {
      const auto it = acked.find(s);
      const std::int64_t want = it == acked.end() ? std::numeric_limits<std::int64_t>::min() : it->second;
      if (book.last_acked(s) != want || book.all_ready({s}) != (ready.count(s) > 0)) __builtin_trap();
      if (it != acked.end() && (!book.all_acked({s}, want) || (want < std::numeric_limits<std::int64_t>::max() &&
                                                               book.all_acked({s}, want + 1)))) {
        __builtin_trap();
      }
    }
    if (!book.all_acked({}, std::numeric_limits<std::int64_t>::max()) || !book.all_ready({})) __builtin_trap();
  }
  return 0;
}

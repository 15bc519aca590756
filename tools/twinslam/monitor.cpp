#include "monitor.hpp"

#include <algorithm>
#include <type_traits>

#include "twinslam/dds/cdr.hpp"
#include "twinslam/dds/dispatch.hpp"
#include "twinslam/dds/msg_json.hpp"

namespace twinslam::cli {

namespace {
template <class T>
const std::function<void(const T&)>* hook_for(const MonitorHooks& h) {
  if constexpr (std::is_same_v<T, msg::Image>) return &h.image;
  if constexpr (std::is_same_v<T, msg::FeatureFrame>) return &h.features;
  if constexpr (std::is_same_v<T, msg::Odometry>) return &h.odometry;
  if constexpr (std::is_same_v<T, msg::Registration>) return &h.registration;
  if constexpr (std::is_same_v<T, msg::LocalMap>) return &h.local_map;
  return nullptr;
}
}  // namespace

TopicMonitor::~TopicMonitor() { node_.close_readers(); }

TopicMonitor::TopicMonitor(dds::Node& node, bool reliable, MonitorHooks hooks) : node_(node), hooks_(std::move(hooks)) {
  for (const auto& spec : dds::topics::kAll) {
    const auto profile = reliable ? dds::reader_profile(spec.family) : dds::kMonitorReaderProfile;
    if (spec.name == dds::topics::kHeartbeat.name) {
      const auto& st = node.subscribe<msg::Heartbeat>(spec, [this, &spec](const msg::Heartbeat& hb) {
        if (hooks_.cdr) hooks_.cdr(spec, dds::to_cdr(hb));
        if (hooks_.well_known) hooks_.well_known(well_known_.on(hb));
        ServiceInfo info{hb.service(), hb.instance(), hb.vehicle_id(), dds::to_string(hb.state()), hb.uptime_ms(), {}};
        for (const auto& c : hb.counters()) info.counters[c.name()] = c.value();
        std::lock_guard lock(mutex_);
        services_[hb.instance()] = std::move(info);
      }, dds::reader_profile(spec.family));
      entries_.push_back({&spec, &st});
      continue;
    }
    dds::with_message_type(spec, [&]<class T>() {
      const auto* hook = hook_for<T>(hooks_);
      const auto& st = node.subscribe<T>(spec, [this, hook, &spec](const T& m) {
        if (hooks_.cdr) hooks_.cdr(spec, dds::to_cdr(m));
        if (hooks_.well_known) hooks_.well_known(well_known_.on(m));
        if (hook == nullptr || !*hook) return;
        if constexpr (requires { m.vehicle_id(); }) {  // every per-vehicle message (not MapTile)
          if (hooks_.vehicle && m.vehicle_id() != *hooks_.vehicle) return;
        }
        (*hook)(m);
      }, profile);
      entries_.push_back({&spec, &st});
    });
  }
}

std::vector<TopicStats> TopicMonitor::stats() const {
  std::vector<TopicStats> out;
  for (const auto& e : entries_) {
    out.push_back({std::string(e.spec->name), std::string(e.spec->type_name), e.status->received.load(),
                   e.status->matched_writers.load()});
  }
  return out;
}

std::vector<ServiceInfo> TopicMonitor::services() const {
  std::lock_guard lock(mutex_);
  std::vector<ServiceInfo> out;
  for (const auto& [_, info] : services_) out.push_back(info);
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
    return a.service != b.service ? a.service < b.service : a.instance < b.instance;
  });
  return out;
}

bool TopicMonitor::all_ready(const std::vector<std::string>& wanted) const {
  std::lock_guard lock(mutex_);
  for (const auto& w : wanted) {
    bool found = false;
    for (const auto& [_, info] : services_) {
      found = found || (info.service == w && (info.state == "ready" || info.state == "running" || info.state == "done"));
    }
    if (!found) return false;
  }
  return true;
}

}  // namespace twinslam::cli

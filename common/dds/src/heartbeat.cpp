#include "twinslam/dds/heartbeat.hpp"

#include <unistd.h>

#include "twinslam/core/wall_clock.hpp"

namespace twinslam::dds {

void Counters::add(const std::string& name, unsigned long long n) {
  std::lock_guard lock(mutex_);
  values_[name] += n;
}

unsigned long long Counters::get(const std::string& name) const {
  std::lock_guard lock(mutex_);
  const auto it = values_.find(name);
  return it == values_.end() ? 0 : it->second;
}

std::map<std::string, unsigned long long> Counters::snapshot() const {
  std::lock_guard lock(mutex_);
  return values_;
}

namespace {
std::string instance_name() {
  char host[256] = {0};
  gethostname(host, sizeof(host) - 1);
  return std::string(host) + ":" + std::to_string(getpid());
}
}  // namespace

HeartbeatPublisher::HeartbeatPublisher(Node& node, const Counters& counters, std::chrono::milliseconds period)
    : node_(node),
      counters_(counters),
      writer_(node.writer<msg::Heartbeat>(topics::kHeartbeat)),
      instance_(instance_name()),
      start_(std::chrono::steady_clock::now()) {
  thread_ = std::thread([this, period] {
    while (!stop_.load()) {
      beat();
      const auto until = std::chrono::steady_clock::now() + period;
      while (!stop_.load() && std::chrono::steady_clock::now() < until) {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      }
    }
  });
}

HeartbeatPublisher::~HeartbeatPublisher() {
  stop_.store(true);
  thread_.join();
  state_.store(msg::SVC_STOPPING);
  beat();
}

void HeartbeatPublisher::set_state(msg::ServiceState state) {
  if (state_.exchange(state) != state) beat();
}

void HeartbeatPublisher::beat() {
  std::lock_guard lock(beat_mutex_);
  msg::Heartbeat hb;
  hb.service(node_.config().service);
  hb.instance(instance_);
  hb.vehicle_id(node_.config().vehicle_id);
  hb.state(state_.load());
  hb.wall_ns(static_cast<long long>(unix_time_ns()));
  hb.uptime_ms(static_cast<unsigned long long>(
      std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - start_).count()));
  for (const auto& [name, value] : counters_.snapshot()) {
    msg::Counter c;
    c.name(name);
    c.value(value);
    hb.counters().push_back(c);
  }
  writer_.publish(hb);
}

}  // namespace twinslam::dds

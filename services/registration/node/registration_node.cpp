#include "registration_node.hpp"

#include <spdlog/spdlog.h>

namespace twinslam::registration {

RegistrationNode::RegistrationNode(dds::Node& node, dds::Counters& counters, const RegistrationNodeOptions& options)
    : counters_(counters),
      writer_(node.writer<msg::Registration>(dds::topics::kRegistration)),
      handler_(counters, options),
      worker_([this] { run(); }) {
  node.subscribe<msg::LocalMap>(dds::topics::kLocalMap, [this](const msg::LocalMap& m) {
    counters_.add("local_maps_in");
    std::lock_guard lock(mutex_);
    ++local_maps_of_[m.vehicle_id()];
    auto& slot = pending_[m.vehicle_id()];
    if (slot.map) counters_.add("skipped");  // the previous cloud of this vehicle was never served: newest wins
    slot = {std::make_shared<const msg::LocalMap>(m), std::chrono::steady_clock::now()};
    wake_.notify_one();
  });
  node.subscribe<msg::MapTile>(dds::topics::kMapTile, [this](const msg::MapTile& t) {
    counters_.add("tiles_in");
    std::lock_guard lock(mutex_);
    tiles_in_.push_back(std::make_shared<const msg::MapTile>(t));
    wake_.notify_one();
  });
}

RegistrationNode::~RegistrationNode() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_one();
  worker_.join();
  // Which vehicles this instance served: with a fleet split over instances by DDS partition, each names only its own.
  for (const auto& [vehicle, n] : local_maps_of_) spdlog::info("served vehicle '{}': {} local maps", vehicle, n);
}

void RegistrationNode::run() {
  std::unique_lock lock(mutex_);
  while (!stop_) {
    // Tiles first: a cloud is registered against everything received before it.
    while (!tiles_in_.empty()) {
      const auto t = tiles_in_.front();
      tiles_in_.pop_front();
      lock.unlock();
      handler_.on_tile(*t);
      lock.lock();
    }
    if (pending_.empty()) {
      wake_.wait(lock);
      continue;
    }
    // Round robin: the first vehicle after the one served last.
    auto it = pending_.upper_bound(last_served_);
    if (it == pending_.end()) it = pending_.begin();
    const Pending p = it->second;
    last_served_ = it->first;
    pending_.erase(it);
    lock.unlock();
    serve(p);
    lock.lock();
  }
}

void RegistrationNode::serve(const Pending& p) {
  msg::Registration out = handler_.on_local_map(*p.map);
  out.latency_ms(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - p.arrived).count());
  writer_.publish(out);
}

}  // namespace twinslam::registration

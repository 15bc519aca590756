#include "ack_book.hpp"

#include <algorithm>
#include <limits>

namespace twinslam::ingest {

void AckBook::on_ack(const msg::FrameAck& ack) {
  if (ack.vehicle_id() != vehicle_id_) return;
  std::lock_guard lock(mutex_);
  // Acks are monotonic per service: a late or repeated sample (reliable history, a restarted peer) never takes
  // back a frame already acknowledged.
  const auto [it, inserted] = acked_.try_emplace(ack.service(), ack.stamp_ns());
  if (!inserted) it->second = std::max(it->second, ack.stamp_ns());
}

void AckBook::on_heartbeat(const msg::Heartbeat& hb) {
  if (!hb.vehicle_id().empty() && hb.vehicle_id() != vehicle_id_) return;
  if (hb.state() != msg::SVC_READY && hb.state() != msg::SVC_RUNNING) return;
  std::lock_guard lock(mutex_);
  ready_.insert(hb.service());
}

bool AckBook::all_acked(const std::vector<std::string>& services, std::int64_t stamp_ns) const {
  std::lock_guard lock(mutex_);
  return std::all_of(services.begin(), services.end(), [&](const std::string& s) {
    const auto it = acked_.find(s);
    return it != acked_.end() && it->second >= stamp_ns;
  });
}

bool AckBook::all_ready(const std::vector<std::string>& services) const {
  std::lock_guard lock(mutex_);
  return std::all_of(services.begin(), services.end(), [&](const std::string& s) { return ready_.count(s) > 0; });
}

std::vector<std::string> AckBook::not_ready(const std::vector<std::string>& services) const {
  std::lock_guard lock(mutex_);
  std::vector<std::string> missing;
  for (const auto& s : services) {
    if (ready_.count(s) == 0) missing.push_back(s);
  }
  return missing;
}

std::int64_t AckBook::last_acked(const std::string& service) const {
  std::lock_guard lock(mutex_);
  const auto it = acked_.find(service);
  return it == acked_.end() ? std::numeric_limits<std::int64_t>::min() : it->second;
}

}  // namespace twinslam::ingest

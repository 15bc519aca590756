// The delay line of one link direction: a Bernoulli loss draw per packet, then a FIFO released at arrival + delay
// (+ jitter, never before the packet ahead of it, so order is kept as DDS's reliable protocol would see on a queue).
#include "twinslam/netem/impairment.hpp"

#include <algorithm>
#include <cstdio>

#include "twinslam/core/error.hpp"

namespace twinslam::netem {

void NetemConfig::validate() const {
  if (!(loss_pct >= 0.0 && loss_pct < 100.0)) throw UsageError("--loss must be a percentage in [0, 100)");
  if (!(delay_ms >= 0.0 && delay_ms <= 60'000.0)) throw UsageError("--delay must be in [0, 60000] ms");
  if (!(jitter_ms >= 0.0 && jitter_ms <= delay_ms)) throw UsageError("--jitter must be in [0, --delay] ms");
  if (queue_limit_bytes == 0) throw UsageError("--queue-limit must be > 0 bytes");
}

DelayLine::DelayLine(const NetemConfig& config, std::uint64_t stream)
    : config_(config), rng_(config.seed * 0x9E3779B97F4A7C15ull + stream) {}

bool DelayLine::offer(Packet packet, Clock::time_point now) {
  ++counts_.packets_in;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  if (config_.loss_pct > 0.0 && unit(rng_) * 100.0 < config_.loss_pct) {
    ++counts_.lost;
    return false;
  }
  if (queued_bytes_ + packet.size() > config_.queue_limit_bytes) {
    ++counts_.overflowed;
    return false;
  }
  double delay_ms = config_.delay_ms;
  if (config_.jitter_ms > 0.0) delay_ms += (2.0 * unit(rng_) - 1.0) * config_.jitter_ms;
  const auto delay = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double, std::milli>(delay_ms));
  const Clock::time_point due = std::max(now + delay, last_due_);
  last_due_ = due;
  queued_bytes_ += packet.size();
  queue_.push_back({due, std::move(packet)});
  return true;
}

std::vector<DelayLine::Packet> DelayLine::release(Clock::time_point now) {
  std::vector<Packet> out;
  while (!queue_.empty() && queue_.front().due <= now) {
    queued_bytes_ -= queue_.front().packet.size();
    ++counts_.packets_out;
    counts_.bytes_out += queue_.front().packet.size();
    out.push_back(std::move(queue_.front().packet));
    queue_.pop_front();
  }
  return out;
}

std::optional<DelayLine::Clock::time_point> DelayLine::next_due() const {
  if (queue_.empty()) return std::nullopt;
  return queue_.front().due;
}

std::string describe(const DirectionCounts& counts) {
  char line[160];
  std::snprintf(line, sizeof line, "in %llu (lost %llu, overflow %llu) out %llu packets %.1f MB",
                static_cast<unsigned long long>(counts.packets_in), static_cast<unsigned long long>(counts.lost),
                static_cast<unsigned long long>(counts.overflowed), static_cast<unsigned long long>(counts.packets_out),
                static_cast<double>(counts.bytes_out) / 1e6);
  return line;
}

}  // namespace twinslam::netem

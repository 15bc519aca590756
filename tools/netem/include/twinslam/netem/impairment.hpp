#pragma once
// One direction of an impaired link (issue 14 item 3): each packet is dropped with a fixed probability or held for
// the configured delay, like Linux netem's `delay D [J] loss random P`, which this kernel lacks. Pure logic (no
// sockets, no clock of its own): the relay feeds it packets and the time, and sends what it releases.
#include <chrono>
#include <cstdint>
#include <deque>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace twinslam::netem {

struct NetemConfig {
  double loss_pct = 0.0;    // share of packets dropped, % in [0, 100), each drawn independently
  double delay_ms = 0.0;    // one-way delay added to every packet, ms
  double jitter_ms = 0.0;   // uniform extra delay in [-jitter, +jitter], ms (<= delay); packets keep their order
  std::uint64_t seed = 1;   // the loss and jitter draws: the same seed drops the same packets of the same stream
  std::size_t queue_limit_bytes = 64u << 20;  // packets waiting beyond this are dropped and counted (bounded memory)

  // Throws UsageError naming the option (`--loss`, ...) that is out of range.
  void validate() const;
};

struct DirectionCounts {
  std::uint64_t packets_in = 0;
  std::uint64_t lost = 0;        // dropped by the loss draw
  std::uint64_t overflowed = 0;  // dropped because the queue was full
  std::uint64_t packets_out = 0;
  std::uint64_t bytes_out = 0;
};

class DelayLine {
 public:
  using Clock = std::chrono::steady_clock;
  using Packet = std::vector<std::uint8_t>;

  // `stream` separates the random draws of the two directions of one link.
  DelayLine(const NetemConfig& config, std::uint64_t stream);

  // A packet that arrived at `now`; false when it was dropped (lost or queue full).
  bool offer(Packet packet, Clock::time_point now);
  // Every packet whose time has come by `now`, in arrival order.
  std::vector<Packet> release(Clock::time_point now);
  // When the oldest waiting packet is due; nullopt when none waits.
  std::optional<Clock::time_point> next_due() const;

  const DirectionCounts& counts() const { return counts_; }
  std::size_t queued_bytes() const { return queued_bytes_; }

 private:
  struct Held {
    Clock::time_point due;
    Packet packet;
  };
  NetemConfig config_;
  std::mt19937_64 rng_;
  std::deque<Held> queue_;
  std::size_t queued_bytes_ = 0;
  Clock::time_point last_due_{};
  DirectionCounts counts_;
};

// "in 1200 (lost 118, overflow 0) out 1082 packets 1.4 MB" — the relay's summary line of a direction.
std::string describe(const DirectionCounts& counts);

}  // namespace twinslam::netem

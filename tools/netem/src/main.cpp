// twinslam-netem: a userspace netem between two TUN devices (issue 14 item 3). Packets read from device A leave
// through device B after the impairment of the A->B direction, and the other way round. scripts/two-hosts.sh routes
// the drone-edge link through it (policy routing in a namespace between the two) when the kernel has no netem qdisc.
// Ends on SIGINT/SIGTERM with one summary line per direction.
#include <poll.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <thread>

#include "tun.hpp"
#include "twinslam/core/main_guard.hpp"
#include "twinslam/core/shutdown.hpp"
#include "twinslam/netem/impairment.hpp"

namespace {
namespace netem = twinslam::netem;
using Clock = netem::DelayLine::Clock;

// Takes what waits on `from` into `line`, at most a batch so the other direction is served too.
void take(netem::Tun& from, netem::DelayLine& line) {
  std::vector<std::uint8_t> packet;
  for (int i = 0; i < 256 && from.read(packet); ++i) line.offer(std::move(packet), Clock::now());
}

void give(netem::DelayLine& line, netem::Tun& to, std::uint64_t& refused) {
  for (const auto& packet : line.release(Clock::now())) {
    if (!to.write(packet)) ++refused;
  }
}

int poll_timeout_ms(const netem::DelayLine& ab, const netem::DelayLine& ba) {
  std::optional<Clock::time_point> due = ab.next_due();
  if (const auto other = ba.next_due(); other && (!due || *other < *due)) due = other;
  if (!due) return 100;  // wake now and then to see a stop request
  const auto wait = std::chrono::duration_cast<std::chrono::milliseconds>(*due - Clock::now()).count();
  return static_cast<int>(std::clamp<long long>(wait, 0, 100));
}

int relay(const std::string& a_name, const std::string& b_name, const netem::NetemConfig& config) {
  netem::Tun a(a_name), b(b_name);
  netem::DelayLine ab(config, 1), ba(config, 2);
  std::uint64_t refused_ab = 0, refused_ba = 0;
  std::printf("twinslam-netem: %s <-> %s, delay %.1f ms (jitter %.1f), loss %.2f %%, seed %llu\n", a_name.c_str(),
              b_name.c_str(), config.delay_ms, config.jitter_ms, config.loss_pct,
              static_cast<unsigned long long>(config.seed));
  std::fflush(stdout);
  while (!twinslam::shutdown_requested()) {
    pollfd fds[2] = {{a.fd(), POLLIN, 0}, {b.fd(), POLLIN, 0}};
    // Sub-millisecond due times: poll's resolution is 1 ms, so the delay is met to within about a millisecond.
    ::poll(fds, 2, poll_timeout_ms(ab, ba));
    if (fds[0].revents & POLLIN) take(a, ab);
    if (fds[1].revents & POLLIN) take(b, ba);
    give(ab, b, refused_ab);
    give(ba, a, refused_ba);
  }
  std::printf("twinslam-netem: %s -> %s %s, refused by the kernel %llu\n", a_name.c_str(), b_name.c_str(),
              netem::describe(ab.counts()).c_str(), static_cast<unsigned long long>(refused_ab));
  std::printf("twinslam-netem: %s -> %s %s, refused by the kernel %llu\n", b_name.c_str(), a_name.c_str(),
              netem::describe(ba.counts()).c_str(), static_cast<unsigned long long>(refused_ba));
  return twinslam::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"twinslam-netem: delay and loss between two TUN devices (a userspace netem)"};
  std::string a_name, b_name;
  netem::NetemConfig config;
  app.add_option("--a", a_name, "First TUN device (e.g. the drone side)")->required();
  app.add_option("--b", b_name, "Second TUN device (e.g. the edge side)")->required();
  app.add_option("--loss", config.loss_pct, "Packets dropped, % per direction")->capture_default_str();
  app.add_option("--delay", config.delay_ms, "One-way delay [ms]")->capture_default_str();
  app.add_option("--jitter", config.jitter_ms, "Uniform +- jitter on the delay [ms]")->capture_default_str();
  app.add_option("--seed", config.seed, "Seed of the loss and jitter draws")->capture_default_str();
  app.add_option("--queue-limit", config.queue_limit_bytes, "Bytes held per direction before tail drop")
      ->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? twinslam::kExitOk : twinslam::kExitBadInput;
  }
  return twinslam::guarded_main("twinslam-netem", [&] {
    config.validate();
    twinslam::install_shutdown_handlers();
    return relay(a_name, b_name, config);
  });
}

// DDS transport benchmark between two processes on this host, with the project's own QoS profiles and types:
//  1. small-message round trip (Ping 16 B payload -> echo -> back): median and p99 latency
//  2. 752x480 mono8 Image messages per second (lockstep reliable profile, every sample delivered)
//  3. 1 MB LocalMap point clouds per second (same profile)
// Usage: bench_dds [--rounds N] [--images N] [--clouds N]. The parent forks the echo/sink process before either
// creates a DDS participant; both run on a private domain.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <thread>
#include <vector>

#include "twinslam/core/log.hpp"
#include "twinslam/dds/node.hpp"

namespace twinslam {
namespace {
using Clock = std::chrono::steady_clock;
constexpr dds::TopicSpec kPing{"twinslam/bench/ping", "twinslam::msg::Ping", dds::QosFamily::Control};
constexpr dds::TopicSpec kPong{"twinslam/bench/pong", "twinslam::msg::Ping", dds::QosFamily::Control};
constexpr dds::TopicSpec kDone{"twinslam/bench/done", "twinslam::msg::Ping", dds::QosFamily::Control};
constexpr std::string_view kBulkWriter = "sensor.lockstep.writer";
constexpr std::string_view kBulkReader = "sensor.reader";

std::int64_t now_ns() { return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch()).count(); }

dds::NodeConfig config(const char* name, int domain) {
  dds::NodeConfig c;
  c.service = name;
  c.domain = domain;
  return c;
}

// Child: echoes pings, counts images and clouds, reports counts on "done" when asked.
int echo_process(int domain) {
  dds::Node node(config("bench-echo", domain));
  auto pong = node.writer<msg::Ping>(kPong);
  auto done = node.writer<msg::Ping>(kDone);
  std::atomic<unsigned long long> images{0}, clouds{0};
  std::atomic<bool> quit{false};
  node.subscribe<msg::Ping>(kPing, [&](const msg::Ping& p) {
    if (p.seq() == ~0ULL) {  // report and quit
      msg::Ping r;
      r.seq(images.load() * 1000000ULL + clouds.load());
      done.publish(r);
      quit.store(true);
      return;
    }
    pong.publish(p);
  });
  node.subscribe<msg::Image>(dds::topics::kImage, [&](const msg::Image&) { images.fetch_add(1); }, kBulkReader);
  node.subscribe<msg::LocalMap>(dds::topics::kLocalMap, [&](const msg::LocalMap&) { clouds.fetch_add(1); },
                                kBulkReader);
  while (!quit.load()) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  done.wait_acknowledged(std::chrono::milliseconds(2000));
  return 0;
}

template <class W>
void wait_matched(const W& w, int n) {
  while (w.matched_readers() < n) std::this_thread::sleep_for(std::chrono::milliseconds(5));
}

template <class T>
double throughput(const char* name, dds::Writer<T>& w, const T& sample, int count, std::size_t bytes) {
  wait_matched(w, 1);
  const auto t0 = Clock::now();
  for (int i = 0; i < count; ++i) {
    if (!w.publish(sample)) std::fprintf(stderr, "write %d failed\n", i);
    // At most a few in flight, as the lockstep pipeline does; measures sustained delivery, not queueing.
    if (i % 4 == 3) w.wait_acknowledged(std::chrono::milliseconds(10000));
  }
  w.wait_acknowledged(std::chrono::milliseconds(10000));
  const double s = std::chrono::duration<double>(Clock::now() - t0).count();
  std::printf("  %-26s %8.1f msg/s  %8.1f MB/s  (%d messages of %.2f MB in %.2f s)\n",
              name, count / s, count * bytes / s / 1e6, count, bytes / 1e6, s);
  return count / s;
}

int main_process(int domain, int rounds, int images, int clouds) {
  dds::Node node(config("bench", domain));
  auto ping = node.writer<msg::Ping>(kPing);
  auto image_w = node.writer<msg::Image>(dds::topics::kImage, kBulkWriter);
  auto cloud_w = node.writer<msg::LocalMap>(dds::topics::kLocalMap, kBulkWriter);
  std::vector<double> rtt_us;
  std::atomic<unsigned long long> got{0}, report{0};
  std::atomic<bool> reported{false};
  node.subscribe<msg::Ping>(kPong, [&](const msg::Ping& p) {
    rtt_us.push_back((now_ns() - p.sent_ns()) / 1000.0);
    got.fetch_add(1);
  });
  node.subscribe<msg::Ping>(kDone, [&](const msg::Ping& p) {
    report.store(p.seq());
    reported.store(true);
  });
  wait_matched(ping, 1);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // let both sides finish discovery
  msg::Ping p;
  p.payload().resize(16);
  for (int i = 0; i < rounds; ++i) {
    p.seq(static_cast<unsigned long long>(i));
    p.sent_ns(now_ns());
    ping.publish(p);
    while (got.load() <= static_cast<unsigned long long>(i)) std::this_thread::yield();  // one in flight
  }
  std::sort(rtt_us.begin(), rtt_us.end());
  const auto pct = [&](double q) { return rtt_us[static_cast<std::size_t>(q * (rtt_us.size() - 1))]; };
  std::printf("round trip (16 B payload, %d rounds): median %.1f us, p99 %.1f us, max %.1f us\n", rounds, pct(0.5),
              pct(0.99), rtt_us.back());

  msg::Image img;
  img.width(752);
  img.height(480);
  img.step(752);
  img.encoding("mono8");
  img.data().assign(752 * 480, 0x5a);
  msg::LocalMap cloud;
  cloud.landmarks().resize(1000000 / 36);  // 36 B per landmark on the wire -> ~1 MB
  std::printf("throughput (reliable lockstep profile, every message delivered):\n");
  throughput("752x480 mono8 Image", image_w, img, images, img.data().size());
  throughput("1 MB LocalMap cloud", cloud_w, cloud, clouds, cloud.landmarks().size() * 36);

  p.seq(~0ULL);
  ping.publish(p);
  while (!reported.load()) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  const auto r = report.load();
  std::printf("receiver counted %llu images and %llu clouds\n", r / 1000000ULL, r % 1000000ULL);
  return (r / 1000000ULL == static_cast<unsigned long long>(images) &&
          r % 1000000ULL == static_cast<unsigned long long>(clouds)) ? 0 : 1;
}
}  // namespace
}  // namespace twinslam

int main(int argc, char** argv) {
  int rounds = 5000, images = 400, clouds = 200;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    const int v = std::atoi(argv[i + 1]);
    if (a == "--rounds") rounds = v;
    else if (a == "--images") images = v;
    else if (a == "--clouds") clouds = v;
  }
  twinslam::init_logging("warn");
  const int domain = 200 + static_cast<int>(getpid() % 30);
  const pid_t child = fork();
  if (child == 0) return twinslam::echo_process(domain);
  const int rc = twinslam::main_process(domain, rounds, images, clouds);
  int status = 0;
  waitpid(child, &status, 0);
  return rc;
}

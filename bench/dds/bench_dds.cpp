// DDS transport benchmark between two processes on this host, with the project's own QoS profiles and types, on the
// drone -> edge path as deployed (the parent is the drone, the forked child the edge):
//  1. small-message round trip (an empty LocalMap -> the edge answers with a Registration): median and p99 latency
//  2. 752x480 mono8 Image messages per second (lockstep reliable profile, every sample delivered)
//  3. 1 MB LocalMap point clouds per second (same profile)
// Usage: bench_dds [--rounds N] [--images N] [--clouds N] [--secure DIR]. --secure: both sides under DDS-Security
// with the drone and edge identities of DIR (scripts/security/make-pki.sh DIR), to measure what security costs.
// The parent forks the edge process before either creates a DDS participant; both run on a private domain.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "twinslam/core/log.hpp"
#include "twinslam/dds/node.hpp"

namespace twinslam {
namespace {
using Clock = std::chrono::steady_clock;
constexpr std::string_view kBulkWriter = "sensor.lockstep.writer";
constexpr std::string_view kBulkReader = "sensor.reader";
constexpr unsigned long long kReport = ~0ULL;       // the LocalMap seq that asks the edge for its counts
constexpr unsigned long long kAnswerMe = 1ULL << 40;  // clouds from this seq on are answered (1 MB round trip)

std::int64_t now_ns() { return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch()).count(); }

dds::NodeConfig config(const char* role, int domain, const std::string& security_dir) {
  dds::NodeConfig c;
  c.service = std::string("bench-") + role;
  c.domain = domain;
  if (!security_dir.empty()) {
    c.participant_profile = std::string("twinslam.secure.") + role;
    c.security_dir = security_dir;
  }
  return c;
}

// Child (the edge): answers each empty LocalMap with a Registration carrying its stamp, counts images and clouds,
// and reports the counts when asked.
int edge_process(int domain, const std::string& security_dir) {
  dds::Node node(config("edge", domain, security_dir));
  auto answer = node.writer<msg::Registration>(dds::topics::kRegistration);
  std::atomic<unsigned long long> images{0}, clouds{0};
  std::atomic<bool> quit{false};
  node.subscribe<msg::LocalMap>(dds::topics::kLocalMap, [&](const msg::LocalMap& m) {
    if (!m.landmarks().empty() && m.seq() < kAnswerMe) {
      clouds.fetch_add(1);
      return;
    }
    msg::Registration r;
    r.keyframe_stamp_ns(m.keyframe_stamp_ns());
    r.seq(m.seq());
    if (m.seq() == kReport) {
      r.seq(images.load() * 1000000ULL + clouds.load());
      r.reason("report");
      quit.store(true);
    }
    answer.publish(r);
  }, kBulkReader);
  node.subscribe<msg::Image>(dds::topics::kImage, [&](const msg::Image&) { images.fetch_add(1); }, kBulkReader);
  while (!quit.load()) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  answer.wait_acknowledged(std::chrono::milliseconds(2000));
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

int drone_process(int domain, const std::string& security_dir, int rounds, int images, int clouds) {
  dds::Node node(config("drone", domain, security_dir));
  auto map_w = node.writer<msg::LocalMap>(dds::topics::kLocalMap, kBulkWriter);
  auto image_w = node.writer<msg::Image>(dds::topics::kImage, kBulkWriter);
  std::vector<double> rtt_us, cloud_rtt_us;
  std::atomic<unsigned long long> got{0}, report{0};
  std::atomic<bool> reported{false};
  node.subscribe<msg::Registration>(dds::topics::kRegistration, [&](const msg::Registration& r) {
    if (r.reason() == "report") {
      report.store(r.seq());
      reported.store(true);
      return;
    }
    (r.seq() >= kAnswerMe ? cloud_rtt_us : rtt_us).push_back((now_ns() - r.keyframe_stamp_ns()) / 1000.0);
    got.fetch_add(1);
  });
  wait_matched(map_w, 1);
  wait_matched(image_w, 1);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // let both sides finish discovery
  msg::LocalMap ping;
  for (int i = 0; i < rounds; ++i) {
    ping.seq(static_cast<unsigned long long>(i));
    ping.keyframe_stamp_ns(now_ns());
    map_w.publish(ping);
    while (got.load() <= static_cast<unsigned long long>(i)) std::this_thread::yield();  // one in flight
  }
  std::sort(rtt_us.begin(), rtt_us.end());
  const auto pct = [](const std::vector<double>& v, double q) { return v[static_cast<std::size_t>(q * (v.size() - 1))]; };
  std::printf("security: %s\n", security_dir.empty() ? "none (twinslam.local)"
                                                      : ("DDS-Security, drone and edge identities of " + security_dir)
                                                            .c_str());
  std::printf("round trip (empty LocalMap -> Registration, %d rounds): median %.1f us, p99 %.1f us, max %.1f us\n",
              rounds, pct(rtt_us, 0.5), pct(rtt_us, 0.99), rtt_us.back());

  msg::Image img;
  img.width(752);
  img.height(480);
  img.step(752);
  img.encoding("mono8");
  img.data().assign(752 * 480, 0x5a);
  msg::LocalMap cloud;
  cloud.landmarks().resize(1000000 / 36);  // 36 B per landmark on the wire -> ~1 MB
  const int cloud_rounds = std::max(10, clouds / 4);
  for (int i = 0; i < cloud_rounds; ++i) {
    cloud.seq(kAnswerMe + static_cast<unsigned long long>(i));
    cloud.keyframe_stamp_ns(now_ns());
    const auto before = got.load();
    map_w.publish(cloud);
    while (got.load() <= before) std::this_thread::yield();
  }
  std::sort(cloud_rtt_us.begin(), cloud_rtt_us.end());
  std::printf("round trip (1 MB LocalMap -> Registration, %d rounds): median %.1f us, p99 %.1f us\n", cloud_rounds,
              pct(cloud_rtt_us, 0.5), pct(cloud_rtt_us, 0.99));
  cloud.seq(0);
  std::printf("throughput (reliable lockstep profile, every message delivered):\n");
  throughput("752x480 mono8 Image", image_w, img, images, img.data().size());
  throughput("1 MB LocalMap cloud", map_w, cloud, clouds, cloud.landmarks().size() * 36);

  ping.seq(kReport);
  map_w.publish(ping);
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
  std::string security_dir;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    const int v = std::atoi(argv[i + 1]);
    if (a == "--rounds") rounds = v;
    else if (a == "--images") images = v;
    else if (a == "--clouds") clouds = v;
    else if (a == "--secure") security_dir = argv[i + 1];
    else {
      std::fprintf(stderr, "bench_dds: unknown option %s\n", a.c_str());
      return 2;
    }
  }
  twinslam::init_logging("warn");
  const int domain = 200 + static_cast<int>(getpid() % 30);
  const pid_t child = fork();
  if (child == 0) return twinslam::edge_process(domain, security_dir);
  const int rc = twinslam::drone_process(domain, security_dir, rounds, images, clouds);
  int status = 0;
  waitpid(child, &status, 0);
  // What security costs in CPU: user + system time of each side over the whole benchmark.
  const auto cpu_s = [](int who) {
    rusage u{};
    getrusage(who, &u);
    return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
  };
  std::printf("CPU time over the benchmark: drone %.2f s, edge %.2f s\n", cpu_s(RUSAGE_SELF), cpu_s(RUSAGE_CHILDREN));
  return rc;
}

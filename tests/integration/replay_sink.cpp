// Test subscriber process: records every Imu and Image it receives into binary files, and exits when the publisher
// it was matched with goes away (or after --timeout). The replay test compares these files with the dataset.
//   imu.bin:    per sample  int64 stamp_ns, uint64 seq, 6 x double (gyro xyz, accel xyz)
//   images.bin: per image   int64 stamp_ns, uint64 seq, uint32 width, uint32 height, width*height bytes
#include <cstdio>
#include <fstream>
#include <mutex>
#include <thread>

#include "twinslam/core/shutdown.hpp"
#include "twinslam/dds/heartbeat.hpp"
#include "twinslam/dds/service_main.hpp"

namespace twinslam {
int sink_main(int argc, char** argv) {
  CLI::App app{"replay sink for tests"};
  dds::ServiceOptions service;
  dds::add_service_options(app, service);
  std::string out_dir;
  double timeout_s = 120;
  app.add_option("--out", out_dir)->required();
  app.add_option("--timeout", timeout_s);
  return dds::service_main("sink", app, service, argc, argv, [&] {
    std::ofstream imu_out(out_dir + "/imu.bin", std::ios::binary);
    std::ofstream img_out(out_dir + "/images.bin", std::ios::binary);
    std::mutex mutex;
    dds::Node node(service.node);
    auto write = [](std::ofstream& f, const auto& v) { f.write(reinterpret_cast<const char*>(&v), sizeof(v)); };
    const auto& imu_status = node.subscribe<msg::Imu>(dds::topics::kImu, [&](const msg::Imu& m) {
      std::lock_guard lock(mutex);
      write(imu_out, m.stamp_ns());
      write(imu_out, m.seq());
      for (const auto* v : {&m.gyro_radps(), &m.accel_mps2()}) {
        write(imu_out, v->x());
        write(imu_out, v->y());
        write(imu_out, v->z());
      }
    });
    node.subscribe<msg::Image>(dds::topics::kImage, [&](const msg::Image& m) {
      std::lock_guard lock(mutex);
      write(img_out, m.stamp_ns());
      write(img_out, m.seq());
      write(img_out, m.width());
      write(img_out, m.height());
      img_out.write(reinterpret_cast<const char*>(m.data().data()), static_cast<std::streamsize>(m.data().size()));
    });
    std::fprintf(stderr, "sink ready\n");
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(long(timeout_s * 1000));
    // Done when the ingest writer, once matched, has gone (it exits only after all its samples were acknowledged).
    while (!shutdown_requested() && std::chrono::steady_clock::now() < deadline) {
      if (imu_status.ever_matched.load() && imu_status.matched_writers.load() == 0) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return 0;
  });
}
}  // namespace twinslam

int main(int argc, char** argv) { return twinslam::sink_main(argc, argv); }

// EuRoC CSV files (IMU, ground truth, TUM trajectory, ideal feature tracks); the first byte picks the reader.
#include <cstddef>
#include <cstdint>

#include "harness.hpp"
#include "twinslam/ingest/dataset.hpp"
#include "twinslam/ingest/features.hpp"
#include "twinslam/trajectory/io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace twinslam;
  if (size == 0) return 0;
  const auto path = fuzz::write_scratch("data.csv", data + 1, size - 1);
  return fuzz::expect_input_error_only([&] {
    switch (data[0] % 4) {
      case 0: ingest::load_imu_csv(path); break;
      case 1: read_euroc_groundtruth(path); break;
      case 2: read_tum(path); break;
      default: ingest::load_feature_tracks(path, data[0] & 0x80); break;
    }
  });
}

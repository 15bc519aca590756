// A whole EuRoC ASL dataset folder: parts imu0/data.csv, cam0/data.csv, gnss0/data.csv (split at "\n@@@\n").
#include <cstddef>
#include <cstdint>

#include "harness.hpp"
#include <filesystem>
#include "twinslam/ingest/dataset.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace twinslam;
  const auto parts = fuzz::split_parts(data, size, 3);
  std::filesystem::remove_all(fuzz::scratch_dir() / "ds");
  const char* files[] = {"ds/mav0/imu0/data.csv", "ds/mav0/cam0/data.csv", "ds/mav0/gnss0/data.csv"};
  for (std::size_t i = 0; i < parts.size(); ++i) fuzz::write_scratch(files[i], parts[i]);
  return fuzz::expect_input_error_only([&] { ingest::load_dataset(fuzz::scratch_dir() / "ds"); });
}

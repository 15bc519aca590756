#pragma once
// Test fixtures: the shared EuRoC excerpt, and broken copies of it (images are symlinked, CSVs copied) so each test
// can damage one file without touching ../shared.
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "twinslam/core/error.hpp"
#include "scratch_dir.hpp"
#include "twinslam/ingest/dataset.hpp"

namespace twinslam::test {
namespace fs = std::filesystem;

inline fs::path euroc_dir() { return fs::path(TWINSLAM_SHARED_DIR) / "data/euroc-v1-01-micro"; }

inline void replace_line(const fs::path& file, std::size_t line_no, const std::string& text) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  lines.at(line_no - 1) = text;
  std::ofstream out(file);
  for (const auto& l : lines) out << l << '\n';
}

inline fs::path broken_copy(const std::string& tag, const std::function<void(const fs::path&)>& damage) {
  const fs::path dir = scratch_dir() / ("ds_" + tag);
  fs::remove_all(dir);
  const fs::path src = euroc_dir();
  fs::create_directories(dir / "mav0/cam0/data");
  fs::create_directories(dir / "mav0/imu0");
  fs::copy_file(src / "mav0/imu0/data.csv", dir / "mav0/imu0/data.csv");
  fs::copy_file(src / "mav0/cam0/data.csv", dir / "mav0/cam0/data.csv");
  for (const auto& e : fs::directory_iterator(src / "mav0/cam0/data")) {
    fs::copy_file(e.path(), dir / "mav0/cam0/data" / e.path().filename());
  }
  damage(dir);
  return dir;
}

inline std::string load_error(const fs::path& dir) {
  try {
    ingest::load_dataset(dir);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace twinslam::test

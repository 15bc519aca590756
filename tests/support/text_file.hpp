#pragma once
// A whole text file as a string ("" when it cannot be read): what the multi-process tests read back from runs.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace twinslam::test {

inline std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace twinslam::test

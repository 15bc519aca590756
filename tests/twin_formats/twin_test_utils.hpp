#pragma once
// Helpers of the twin-format tests: a scratch folder per test and a check that an InputError names the file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include <unistd.h>

#include "twinslam/core/error.hpp"

namespace twin_test {

// A scratch folder for the current test, removed again when the test ends.
struct Scratch {
  std::filesystem::path dir;
  Scratch() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir = std::filesystem::temp_directory_path() / ("twinslam_twin_formats_" + std::to_string(::getpid())) /
          (std::string(info->test_suite_name()) + "." + info->name());
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
  }
  ~Scratch() { std::filesystem::remove_all(dir.parent_path()); }
  std::filesystem::path operator/(const std::string& name) const { return dir / name; }
};

inline std::string write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path.string();
}

// Runs `load` and expects an InputError whose one-line message names `file` and contains `reason`.
inline void expect_input_error(const std::function<void()>& load, const std::string& file, const std::string& reason) {
  try {
    load();
    ADD_FAILURE() << "no InputError for " << file;
  } catch (const twinslam::InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(file), std::string::npos) << what;
    EXPECT_NE(what.find(reason), std::string::npos) << "expected '" << reason << "' in: " << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

}  // namespace twin_test

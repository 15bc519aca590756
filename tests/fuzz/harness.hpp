#pragma once
// Shared pieces of the fuzz targets (issue 15). A target feeds libFuzzer's bytes to one reader of the project; the
// only outcome allowed besides success is twinslam::InputError (the one-line "file: problem" of the contract) —
// anything else (another exception, a crash, a sanitizer report, a hang) is a bug. Readers that take a path get the
// bytes through a scratch file; inputs made of several files are split at kPartSeparator.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "twinslam/core/error.hpp"

namespace twinslam::fuzz {

inline constexpr std::string_view kPartSeparator = "\n@@@\n";

// A scratch folder per process (tmpfs when there is one), emptied at exit.
const std::filesystem::path& scratch_dir();

// Writes bytes to scratch_dir()/name (sub-folders created) and returns the path.
std::filesystem::path write_scratch(const std::string& name, const std::uint8_t* data, std::size_t size);
std::filesystem::path write_scratch(const std::string& name, std::string_view text);

// The input cut at kPartSeparator into at most max_parts parts (the last keeps any further separators).
std::vector<std::string_view> split_parts(const std::uint8_t* data, std::size_t size, std::size_t max_parts);

// The message of the InputError the last input ended with ("" when it was read fine): the replay prints it.
std::string& last_input_error();

// Runs f; InputError is the contract's answer to bad input and is swallowed, everything else propagates.
template <class F>
int expect_input_error_only(F&& f) {
  last_input_error().clear();
  try {
    f();
  } catch (const twinslam::InputError& e) {
    last_input_error() = e.what();
  }
  return 0;
}

}  // namespace twinslam::fuzz

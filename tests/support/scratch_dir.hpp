#pragma once
// A directory of this test process's own under the system's temp directory, removed with everything in it when the
// process ends normally: for tests that write small files (malformed inputs, outputs) and would otherwise leave them.
#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace twinslam::test {

inline const std::filesystem::path& scratch_dir() {
  struct Dir {
    std::filesystem::path path;
    Dir() : path(std::filesystem::temp_directory_path() / ("twinslam_scratch_" + std::to_string(::getpid()))) {
      std::filesystem::create_directories(path);
    }
    ~Dir() {
      std::error_code ignored;  // nothing to report at exit: a leftover is the only harm
      std::filesystem::remove_all(path, ignored);
    }
  };
  static const Dir dir;
  return dir.path;
}

}  // namespace twinslam::test

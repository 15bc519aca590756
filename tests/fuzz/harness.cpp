// Scratch files of the fuzz targets.
#include "harness.hpp"

#include <fstream>
#include <system_error>
#include <unistd.h>

namespace twinslam::fuzz {
namespace fs = std::filesystem;

namespace {
struct Scratch {
  fs::path dir;
  Scratch() {
    const fs::path base = fs::is_directory("/dev/shm") ? fs::path("/dev/shm") : fs::temp_directory_path();
    dir = base / ("twinslam_fuzz_" + std::to_string(::getpid()));
    fs::create_directories(dir);
  }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
};
}  // namespace

std::string& last_input_error() {
  static std::string message;
  return message;
}

const fs::path& scratch_dir() {
  static const Scratch scratch;
  return scratch.dir;
}

fs::path write_scratch(const std::string& name, const std::uint8_t* data, std::size_t size) {
  const fs::path path = scratch_dir() / name;
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

fs::path write_scratch(const std::string& name, std::string_view text) {
  return write_scratch(name, reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
}

std::vector<std::string_view> split_parts(const std::uint8_t* data, std::size_t size, std::size_t max_parts) {
  std::string_view rest(reinterpret_cast<const char*>(data), size);
  std::vector<std::string_view> parts;
  while (parts.size() + 1 < max_parts) {
    const std::size_t at = rest.find(kPartSeparator);
    if (at == std::string_view::npos) break;
    parts.push_back(rest.substr(0, at));
    rest.remove_prefix(at + kPartSeparator.size());
  }
  parts.push_back(rest);
  return parts;
}

}  // namespace twinslam::fuzz

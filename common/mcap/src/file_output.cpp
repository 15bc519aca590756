#include "file_output.hpp"

#include <cerrno>
#include <cstring>
#include <utility>

#include "twinslam/core/error.hpp"

namespace twinslam::mcap::detail {

FileOutput::FileOutput(std::string path) : path_(std::move(path)) {
  file_ = std::fopen(path_.c_str(), "wb");
  if (file_ == nullptr) fail(errno);
}

FileOutput::~FileOutput() { abandon(); }

void FileOutput::write(const std::uint8_t* p, std::size_t n) {
  if (file_ == nullptr) fail(error_ != 0 ? error_ : EBADF);
  if (n == 0) return;
  if (std::fwrite(p, 1, n, file_) != n) fail(errno);
  offset_ += n;
  crc_ = crc32(crc_, p, n);
}

void FileOutput::flush() {
  if (file_ == nullptr) fail(error_ != 0 ? error_ : EBADF);
  if (std::fflush(file_) != 0) fail(errno);
}

void FileOutput::close() {
  if (error_ != 0) fail(error_);
  if (file_ == nullptr) return;
  flush();
  std::FILE* file = std::exchange(file_, nullptr);
  if (std::fclose(file) != 0) fail(errno);  // e.g. a network file system reporting a delayed write error
}

void FileOutput::abandon() {
  if (file_ != nullptr) std::fclose(std::exchange(file_, nullptr));
}

void FileOutput::fail(int error) {
  if (error == 0) error = EIO;
  if (error_ == 0) error_ = error;
  abandon();
  throw InputError(where(path_, 0, std::string("cannot write: ") + std::strerror(error)));
}

}  // namespace twinslam::mcap::detail

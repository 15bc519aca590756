#pragma once
// The output file: appends bytes, knows the offset of the next byte (every index in MCAP is a file offset) and keeps
// a running CRC32 of what was written since restart_crc() (Data End covers the data section, the Footer the
// summary). Any failed write throws InputError naming the path.
#include <cstdint>
#include <cstdio>
#include <string>

#include "bytes.hpp"

namespace twinslam::mcap::detail {

class FileOutput {
 public:
  explicit FileOutput(std::string path);  // opens (truncates) the file: throws InputError
  ~FileOutput();                          // closes without checking (close() reports errors)
  FileOutput(const FileOutput&) = delete;
  FileOutput& operator=(const FileOutput&) = delete;

  void write(const std::uint8_t* p, std::size_t n);
  void write(const Bytes& bytes) { write(bytes.data(), bytes.size()); }
  void flush();
  void close();    // flushes and closes; throws InputError if the data did not reach the file
  void abandon();  // closes after a failure, ignoring further errors

  std::uint64_t offset() const { return offset_; }
  std::uint32_t crc() const { return crc_; }
  void restart_crc() { crc_ = 0; }

 private:
  // Gives the file up and throws; later calls throw the same error, so no record lands after a lost one.
  [[noreturn]] void fail(int error);

  std::string path_;
  int error_ = 0;
  std::FILE* file_ = nullptr;
  std::uint64_t offset_ = 0;
  std::uint32_t crc_ = 0;
};

}  // namespace twinslam::mcap::detail

#include "bytes.hpp"

#include <zlib.h>

#include <cstring>
#include <limits>
#include <stdexcept>

namespace twinslam::mcap::detail {

void Bytes::le(std::uint64_t v, int width) {
  for (int i = 0; i < width; ++i) data_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}

void Bytes::string(const std::string& s) {
  // The spec's String and Array/Map lengths are uint32: a longer field cannot be encoded.
  if (s.size() > std::numeric_limits<std::uint32_t>::max()) throw std::length_error("mcap: string over 4 GiB");
  u32(static_cast<std::uint32_t>(s.size()));
  raw(reinterpret_cast<const std::uint8_t*>(s.data()), s.size());
}

// resize + memcpy rather than vector::insert: GCC 12 reports a false -Wstringop-overflow on the inlined insert.
void Bytes::raw(const std::uint8_t* p, std::size_t n) {
  if (n == 0) return;
  const std::size_t old = data_.size();
  data_.resize(old + n);
  std::memcpy(data_.data() + old, p, n);
}

std::size_t Bytes::begin_record(std::uint8_t opcode) {
  u8(opcode);
  const std::size_t mark = data_.size();
  u64(0);
  return mark;
}

std::size_t Bytes::begin_u32_length() {
  const std::size_t mark = data_.size();
  u32(0);
  return mark;
}

void Bytes::patch(std::size_t mark, int width) {
  const std::uint64_t length = data_.size() - mark - static_cast<std::size_t>(width);
  if (width == 4 && length > std::numeric_limits<std::uint32_t>::max()) {
    throw std::length_error("mcap: array or map over 4 GiB");
  }
  for (int i = 0; i < width; ++i) {
    data_[mark + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(length >> (8 * i));
  }
}

std::uint32_t crc32(std::uint32_t crc, const std::uint8_t* p, std::size_t n) {
  return static_cast<std::uint32_t>(crc32_z(crc, p, n));  // crc32_z: a size_t length, no 4 GiB split needed
}

}  // namespace twinslam::mcap::detail

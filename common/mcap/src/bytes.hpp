#pragma once
// A growable little-endian byte buffer with the spec's primitive encodings (https://mcap.dev/spec#serialization):
// fixed-width integers little-endian, String = uint32 length + UTF-8 bytes, and length prefixes (records, Arrays,
// Maps) patched in place so records are built without temporaries.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace twinslam::mcap::detail {

class Bytes {
 public:
  void u8(std::uint8_t v) { data_.push_back(v); }
  void u16(std::uint16_t v) { le(v, 2); }
  void u32(std::uint32_t v) { le(v, 4); }
  void u64(std::uint64_t v) { le(v, 8); }
  void string(const std::string& s);
  void raw(const std::uint8_t* p, std::size_t n);

  // `<opcode><uint64 content length>`: returns the mark to pass to end_record() once the content is appended.
  std::size_t begin_record(std::uint8_t opcode);
  void end_record(std::size_t mark) { patch(mark, 8); }
  // uint32 byte-length prefix of an Array or Map.
  std::size_t begin_u32_length();
  void end_u32_length(std::size_t mark) { patch(mark, 4); }

  const std::uint8_t* data() const { return data_.data(); }
  std::size_t size() const { return data_.size(); }
  void clear() { data_.clear(); }

 private:
  void le(std::uint64_t v, int width);
  // Writes (size() - mark - width) as a little-endian `width`-byte length at `mark`.
  void patch(std::size_t mark, int width);

  std::vector<std::uint8_t> data_;
};

// zlib's CRC-32 (the spec's CRC32: ISO-HDLC polynomial, as `crc32` of zlib), continued from `crc` (0 to start).
std::uint32_t crc32(std::uint32_t crc, const std::uint8_t* p, std::size_t n);

}  // namespace twinslam::mcap::detail

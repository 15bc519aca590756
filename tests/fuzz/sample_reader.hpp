#pragma once
// Arbitrary DDS samples from fuzz bytes (issue 15: "every DDS message handler fed arbitrary samples"). The targets
// build each field from the input: most reads give the field's well-formed value unless the input says otherwise
// (choice bytes: 0 means well formed), so an all-zero input is a valid sample and the fuzzer mutates from there; once
// the input runs out every read returns 0, i.e. well-formed values.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

namespace twinslam::fuzz {

class SampleReader {
 public:
  SampleReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  std::uint8_t u8() { return pos_ < size_ ? data_[pos_++] : 0; }
  std::uint16_t u16() {
    const std::uint16_t low = u8();  // two statements: the order of reads is the format
    return static_cast<std::uint16_t>(low | (u8() << 8));
  }
  std::int64_t i64() {
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= static_cast<std::uint64_t>(u8()) << (8 * i);
    return static_cast<std::int64_t>(v);
  }
  // `nominal` most of the time; otherwise a nearby value, a special one or raw bits.
  double value(double nominal) {
    switch (u8() % 8) {
      case 0: case 1: case 2: return nominal;
      case 3: return nominal + (static_cast<int>(u8()) - 128) * 0.25;
      case 4: return std::numeric_limits<double>::quiet_NaN();
      case 5: return (u8() & 1 ? 1.0 : -1.0) * std::numeric_limits<double>::infinity();
      case 6: return (static_cast<int>(u8()) - 128) * 1e100;
      default: {
        const std::int64_t bits = i64();
        double d;
        std::memcpy(&d, &bits, sizeof d);
        return d;
      }
    }
  }
  // `nominal`, or up to 31 arbitrary bytes.
  std::string text(const std::string& nominal) {
    if (u8() % 4 != 3) return nominal;
    std::string s(u8() % 32, ' ');
    for (char& c : s) c = static_cast<char>(u8());
    return s;
  }
  bool done() const { return pos_ >= size_; }

 private:
  const std::uint8_t* data_;
  std::size_t size_, pos_ = 0;
};

}  // namespace twinslam::fuzz

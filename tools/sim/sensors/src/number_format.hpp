#pragma once
// Shortest round-trip text of a double (std::to_chars): "0.1" not "0.10000000000000001", and reads back exactly.
#include <charconv>
#include <string>

namespace twinslam::sim::detail {

inline void append_number(std::string& out, double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

}  // namespace twinslam::sim::detail

#pragma once
// A Linux TUN device (layer 3, no packet information header) opened by name in the caller's network namespace.
#include <cstdint>
#include <string>
#include <vector>

namespace twinslam::netem {

class Tun {
 public:
  // Attaches to the persistent device `name` (`ip tuntap add dev NAME mode tun`) or creates it; non-blocking.
  // Throws InputError naming the device and the system's reason.
  explicit Tun(const std::string& name);
  ~Tun();
  Tun(const Tun&) = delete;
  Tun& operator=(const Tun&) = delete;

  int fd() const { return fd_; }
  const std::string& name() const { return name_; }
  // Reads one packet into `packet`; false when none is waiting.
  bool read(std::vector<std::uint8_t>& packet);
  // Sends one packet into the kernel as if it arrived on this device; false when the kernel refused it (device down).
  bool write(const std::vector<std::uint8_t>& packet);

 private:
  std::string name_;
  int fd_ = -1;
  std::vector<std::uint8_t> buffer_;  // one read's room (the largest IP packet)
};

}  // namespace twinslam::netem

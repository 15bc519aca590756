// TUN devices through /dev/net/tun (Documentation/networking/tuntap.rst): IFF_TUN carries bare IP packets.
#include "tun.hpp"

#include <fcntl.h>
#include <linux/if.h>
#include <linux/if_tun.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "twinslam/core/error.hpp"

namespace twinslam::netem {

Tun::Tun(const std::string& name) : name_(name) {
  if (name.empty() || name.size() >= IFNAMSIZ) throw InputError("TUN device name '" + name + "' is empty or too long");
  fd_ = ::open("/dev/net/tun", O_RDWR | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) throw InputError(std::string("/dev/net/tun: ") + std::strerror(errno) + " (needs root or CAP_NET_ADMIN)");
  ifreq request{};
  request.ifr_flags = IFF_TUN | IFF_NO_PI;
  std::strncpy(request.ifr_name, name.c_str(), IFNAMSIZ - 1);
  if (::ioctl(fd_, TUNSETIFF, &request) < 0) {
    const std::string reason = std::strerror(errno);
    ::close(fd_);
    throw InputError("TUN device " + name + ": " + reason);
  }
}

Tun::~Tun() {
  if (fd_ >= 0) ::close(fd_);
}

bool Tun::read(std::vector<std::uint8_t>& packet) {
  // Read into one reusable buffer and copy out exactly the packet: a packet vector resized down from 64 KiB would keep
  // that capacity while it waits in the delay line, which counts only its size against the queue limit.
  buffer_.resize(65536);
  const ssize_t n = ::read(fd_, buffer_.data(), buffer_.size());
  if (n <= 0) return false;
  packet.assign(buffer_.begin(), buffer_.begin() + n);
  return true;
}

bool Tun::write(const std::vector<std::uint8_t>& packet) {
  return ::write(fd_, packet.data(), packet.size()) == static_cast<ssize_t>(packet.size());
}

}  // namespace twinslam::netem

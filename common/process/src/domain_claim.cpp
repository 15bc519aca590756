// DomainClaims (see domain_claim.hpp).
#include "twinslam/process/domain_claim.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace twinslam::process {

DomainClaims::~DomainClaims() {
  for (const auto& [domain, fd] : held_) ::close(fd);
}

bool DomainClaims::lock(int domain) {
  if (held_.count(domain) != 0) return true;
  std::error_code ec;
  const std::filesystem::path dir = std::filesystem::temp_directory_path(ec);
  if (ec) return false;
  const std::string file = (dir / ("twinslam-dds-domain-" + std::to_string(domain) + ".lock")).string();
  // Not O_CLOEXEC: the services this process starts keep the claim (domain_claim.hpp).
  const int fd = ::open(file.c_str(), O_RDWR | O_CREAT, 0666);
  if (fd < 0) return false;  // e.g. another user's lock file: the id counts as taken
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    ::close(fd);
    return false;
  }
  held_[domain] = fd;
  return true;
}

int DomainClaims::claim(int first, int count, unsigned hint) {
  const std::lock_guard<std::mutex> guard(mutex_);
  if (claimed_ >= first && claimed_ < first + count) return claimed_;
  const int start = static_cast<int>(hint % static_cast<unsigned>(count));
  for (int i = 0; i < count; ++i) {
    const int domain = first + (start + i) % count;
    if (lock(domain)) {
      claimed_ = domain;
      return domain;
    }
  }
  return first + start;
}

int claim_dds_domain(int first, int count, unsigned hint) {
  static DomainClaims* const claims = new DomainClaims();  // never destroyed: the claim lasts until exit
  return claims->claim(first, count, hint);
}

}  // namespace twinslam::process

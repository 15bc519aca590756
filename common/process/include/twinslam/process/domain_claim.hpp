#pragma once
// A DDS domain id of its own for a pipeline on this host. `twinslam run`/`bench` and the multi-process tests start
// their services on a private domain so that parallel runs never see each other's samples; picking it from the pid
// alone (pid % 100) let two benches whose pids agreed modulo 100 share one, and each then consumed the other's frames
// ("timestamp not increasing", a mode with no trajectory). Here the id is claimed with an advisory lock on
// TMPDIR/twinslam-dds-domain-<id>.lock. The lock's descriptor is inherited by the service processes this process
// starts (it is not close-on-exec), so the claim lasts while any of them lives, even if this process was killed.
// POSIX only, no DDS.
#include <map>
#include <mutex>

namespace twinslam::process {

// The locks one process holds. Use claim_dds_domain(); a second instance stands for another process in tests.
class DomainClaims {
 public:
  DomainClaims() = default;
  DomainClaims(const DomainClaims&) = delete;
  DomainClaims& operator=(const DomainClaims&) = delete;
  ~DomainClaims();  // releases the locks (the process-wide instance never dies before exit)

  // The first id of [first, first + count) whose lock it holds or gets, starting at first + (hint % count); the first
  // claim in range is kept and returned again. None free (or no writable temp folder): first + (hint % count).
  int claim(int first, int count, unsigned hint);

 private:
  bool lock(int domain);

  std::mutex mutex_;
  std::map<int, int> held_;  // domain -> descriptor of its lock file
  int claimed_ = -1;
};

// claim() on this process's DomainClaims.
int claim_dds_domain(int first, int count, unsigned hint);

}  // namespace twinslam::process

// DomainClaims: two processes on one host never get the same DDS domain, even with the same hint (pids that agree
// modulo the range); one process keeps the domain it claimed; a released domain is free again.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>

#include "twinslam/process/domain_claim.hpp"

namespace twinslam::process {
namespace {

// Runs `f` in a forked child; returns its exit status (f's value, 0-255).
template <typename F>
int in_child(F f) {
  const pid_t pid = fork();
  if (pid == 0) std::_Exit(f());
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// A range of its own keeps parallel runs of this test apart from each other and from real runs (100-199, 10-89).
int first_of_range() { return 200 + static_cast<int>(getpid() % 4) * 8; }

TEST(DomainClaim, AnotherProcessWithTheSameHintGetsAnotherDomain) {
  const int first = first_of_range();
  DomainClaims mine;
  const int d = mine.claim(first, 8, 3);
  ASSERT_GE(d, first);
  ASSERT_LT(d, first + 8);
  EXPECT_EQ(mine.claim(first, 8, 5), d);  // one process keeps its domain
  // Another process (its own DomainClaims, its own lock descriptors) with the same hint.
  const int other = in_child([&] {
    DomainClaims theirs;
    return theirs.claim(first, 8, 3);
  });
  EXPECT_GE(other, first);
  EXPECT_LT(other, first + 8);
  EXPECT_NE(other, d);
}

TEST(DomainClaim, AReleasedDomainIsFreeAgain) {
  const int first = first_of_range();
  int d = -1;
  {
    DomainClaims mine;
    d = mine.claim(first, 8, 6);
  }
  EXPECT_EQ(in_child([&] {
              DomainClaims theirs;
              return theirs.claim(first, 8, 6);
            }),
            d);
}

}  // namespace
}  // namespace twinslam::process

#pragma once
// Error kinds that map to the CLI exit codes of CONTRACTS.md: bad usage or bad input -> 2, internal failure -> 1.
#include <stdexcept>
#include <string>

namespace twinslam {

// Bad input: a missing or malformed file, an out-of-range value. The message is one line and names the file
// (and line, where there is one) and what is wrong, e.g. "imu0/data.csv:17: timestamp goes backwards".
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Bad command line or configuration: unknown option, unknown profile, conflicting flags.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// "FILE:LINE: what" (or "FILE: what" when line is 0) — the one format for input errors.
std::string where(const std::string& file, std::size_t line, const std::string& what);

}  // namespace twinslam

#include "run_security.hpp"

#include <sys/wait.h>

#include <cstdlib>
#include <iostream>

#include "twinslam/core/error.hpp"

namespace twinslam::cli {
namespace fs = std::filesystem;

std::string security_role(const std::string& service) {
  if (service == "ingest" || service == "tracking" || service == "estimator") return "drone";
  if (service == "tiles" || service == "registration") return "edge";
  if (service == "run" || service == "bridge" || service == "record") return "ops";
  throw UsageError("no DDS-Security role for service '" + service + "'");
}

std::string secure_profile(const std::string& service) { return "twinslam.secure." + security_role(service); }

namespace {
fs::path default_security_dir() {
  if (const char* env = std::getenv("TWINSLAM_SECURITY_DIR"); env != nullptr && *env != '\0') return env;
  if (const char* state = std::getenv("XDG_STATE_HOME"); state != nullptr && *state != '\0') {
    return fs::path(state) / "twinslam/pki";
  }
  const char* home = std::getenv("HOME");
  if (home == nullptr || *home == '\0') throw UsageError("--secure: no HOME; name the files with --security-dir DIR");
  return fs::path(home) / ".local/state/twinslam/pki";
}

// Single-quoted for the shell: the directory may hold spaces.
std::string quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}
}  // namespace

fs::path ensure_security_files(const std::string& configured, bool quiet) {
  const fs::path dir = fs::absolute(configured.empty() ? default_security_dir() : fs::path(configured));
  if (fs::is_regular_file(dir / "ca.pem") && fs::is_regular_file(dir / "governance.p7s")) return dir;
  if (!quiet) std::cerr << "twinslam: making DDS-Security files in " << dir.string() << std::endl;
  // The script keeps whatever exists and makes what is missing; its own messages name the problem.
  const std::string command = "bash " + quoted(TWINSLAM_PKI_SCRIPT) + " " + quoted(dir.string()) + " >/dev/null";
  const int status = std::system(command.c_str());
  if (status != 0 || !fs::is_regular_file(dir / "ca.pem")) {
    throw UsageError(dir.string() + ": cannot make the DDS-Security files (" + std::string(TWINSLAM_PKI_SCRIPT) +
                     " exited " + std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")");
  }
  return dir;
}

}  // namespace twinslam::cli

#include "run_config_dir.hpp"

#include <fstream>
#include <stdexcept>

#include <yaml-cpp/yaml.h>

#include "twinslam/core/error.hpp"
#include "twinslam/core/main_guard.hpp"
#include "twinslam/ingest/ingest_config.hpp"

namespace twinslam::cli {
namespace fs = std::filesystem;

void check_config_dir(const std::string& dir) {
  if (dir.empty()) return;
  if (!fs::exists(dir)) throw InputError(where(dir, 0, "config directory does not exist"));
  if (!fs::is_directory(dir)) throw InputError(where(dir, 0, "config directory is not a directory"));
  if (const fs::path ingest = fs::path(dir) / "ingest.yaml"; fs::exists(ingest)) {
    ingest::load_ingest_config(ingest.string());
  }
}

std::vector<std::string> config_args(const std::string& dir, const std::string& service) {
  if (dir.empty()) return {};
  const fs::path file = fs::path(dir) / (service + ".yaml");
  if (!fs::exists(file)) return {};
  return {"--config", file.string()};
}

bool config_sets_key(const std::string& dir, const std::string& service, const std::string& key) {
  const auto args = config_args(dir, service);
  if (args.empty()) return false;
  try {
    const YAML::Node root = YAML::LoadFile(args.back());
    return root.IsMap() && root[key].IsDefined();
  } catch (const YAML::Exception&) {
    return false;
  }
}

namespace {

// The service's error line ("twinslam-estimator: FILE:LINE: ..."), without the program prefix; empty if none.
std::string error_line(const fs::path& log, const std::string& service) {
  std::ifstream in(log);
  const std::string prefix = "twinslam-" + service + ": ";
  std::string line, found;
  while (std::getline(in, line)) {
    if (line.rfind(prefix, 0) == 0) found = line.substr(prefix.size());
  }
  return found;
}

}  // namespace

void throw_startup_failure(const std::vector<process::ChildResult>& results, const fs::path& log_dir) {
  for (const auto& r : results) {
    if (!r.exit_code || *r.exit_code != kExitBadInput) continue;
    const std::string line = error_line(log_dir / (r.name + ".log"), r.name);
    if (!line.empty()) throw InputError(r.name + ": " + line);
  }
  std::string why;
  for (const auto& line : failed_service_lines(results, log_dir)) why += "; " + line;
  throw std::runtime_error("a service stopped during start-up (logs in " + log_dir.string() + ")" + why);
}

std::vector<std::string> failed_service_lines(const std::vector<process::ChildResult>& results,
                                              const fs::path& log_dir) {
  std::vector<std::string> lines;
  for (const auto& r : results) {
    if (r.ok()) continue;
    const std::string line = error_line(log_dir / (r.name + ".log"), r.name);
    lines.push_back(r.name + " (" + process::describe_end(r.exit_code, r.signal) +
                    "): " + (line.empty() ? "see " + (log_dir / (r.name + ".log")).string() : line));
  }
  return lines;
}

}  // namespace twinslam::cli

#include "modes.hpp"

#include <algorithm>
#include <map>

#include "twinslam/core/error.hpp"

namespace twinslam::cli {
namespace {

// Where each missing mode is being built, for the refusal message.
const std::map<std::string, std::string>& missing() {
  static const std::map<std::string, std::string> m{};
  return m;
}

}  // namespace

const std::vector<std::string>& all_modes() {
  static const std::vector<std::string> modes{"vio", "vio-gnss", "vio-gnss-loose", "vio-twin", "vio-twin-gnss"};
  return modes;
}

namespace {
bool all_modes_has(const std::string& mode) {
  return std::find(all_modes().begin(), all_modes().end(), mode) != all_modes().end();
}
}  // namespace

bool mode_implemented(const std::string& mode) { return all_modes_has(mode) && missing().count(mode) == 0; }

std::string implemented_modes_text() {
  std::string out;
  for (const auto& m : all_modes()) {
    if (mode_implemented(m)) out += (out.empty() ? "" : ", ") + m;
  }
  return out;
}

void require_implemented_mode(const std::string& mode) {
  if (mode_implemented(mode)) return;
  const auto it = missing().find(mode);
  const std::string why = it == missing().end() ? "unknown mode" : "not implemented yet (" + it->second + ")";
  throw UsageError("mode '" + mode + "': " + why + "; implemented: " + implemented_modes_text());
}

bool uses_twin(const std::string& mode) { return mode.rfind("vio-twin", 0) == 0; }
bool fuses_gnss(const std::string& mode) { return mode == "vio-gnss" || mode == "vio-twin-gnss"; }
bool fuses_gnss_loose(const std::string& mode) { return mode == "vio-gnss-loose"; }
bool needs_gnss(const std::string& mode) { return fuses_gnss(mode) || fuses_gnss_loose(mode); }

}  // namespace twinslam::cli

#include "security.hpp"

#include <cstdlib>
#include <filesystem>
#include <string_view>

#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>

#include "twinslam/core/error.hpp"

namespace twinslam::dds::detail {

namespace {
bool starts_with(std::string_view s, std::string_view prefix) { return s.substr(0, prefix.size()) == prefix; }

bool is_plugin_selection(std::string_view name) {
  return starts_with(name, "dds.sec.") && name.size() > 7 && name.substr(name.size() - 7) == ".plugin";
}

std::string security_dir(const std::string& configured, const std::string& profile) {
  if (!configured.empty()) return configured;
  if (const char* env = std::getenv("TWINSLAM_SECURITY_DIR"); env != nullptr && *env != '\0') return env;
  throw UsageError("participant profile '" + profile +
                   "' is secured (DDS-Security) but no security directory is set: pass --security DIR or set "
                   "TWINSLAM_SECURITY_DIR (make one with scripts/security/make-pki.sh DIR)");
}
}  // namespace

bool resolve_security_files(eprosima::fastdds::dds::DomainParticipantQos& qos, const std::string& profile,
                            const std::string& configured_dir) {
  auto& properties = qos.properties().properties();
  bool secured = false;
  for (const auto& p : properties) secured = secured || is_plugin_selection(p.name());
  if (!secured) return false;
  const std::filesystem::path dir = security_dir(configured_dir, profile);
  for (auto& p : properties) {
    // Fast DDS reads only `file://PATH` (PKIDH.cpp, Permissions.cpp), PATH absolute or relative to the process.
    if (!starts_with(p.name(), "dds.sec.") || !starts_with(p.value(), "file://")) continue;
    std::filesystem::path file = p.value().substr(7);
    if (file.is_relative()) file = dir / file;
    if (!std::filesystem::is_regular_file(file)) {
      throw UsageError(file.string() + ": missing (" + p.name() + " of participant profile '" + profile +
                       "'; make the files with scripts/security/make-pki.sh " + dir.string() + ")");
    }
    p.value("file://" + std::filesystem::absolute(file).string());
  }
  return true;
}

}  // namespace twinslam::dds::detail

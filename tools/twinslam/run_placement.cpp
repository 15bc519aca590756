#include "run_placement.hpp"

#include "run_security.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/core/text.hpp"

namespace twinslam::cli {

process::ProcessSpec place_service(process::ProcessSpec spec, const RunOptions& o,
                                   const std::filesystem::path& security_dir) {
  if (o.secure) {
    spec.args.insert(spec.args.end(), {"--profile", secure_profile(spec.name), "--security", security_dir.string()});
  }
  if (o.edge_netns.empty() || (spec.name != "tiles" && spec.name != "registration")) return spec;
  const auto exe = process::resolve_executable(spec.exec);
  if (exe.empty()) throw UsageError("service '" + spec.name + "': executable '" + spec.exec + "' not found");
  if (process::resolve_executable("ip").empty()) throw UsageError("--edge-netns: the `ip` command is not found");
  spec.args.insert(spec.args.begin(), {"netns", "exec", o.edge_netns, exe.string()});
  spec.exec = "ip";
  return spec;
}

std::set<std::string> restart_set(const RunOptions& o) {
  std::set<std::string> services;
  if (o.restart == "none") return services;
  for (const auto name : split(o.restart, ',')) {
    const std::string s(name);
    if (s != "tracking" && s != "estimator" && s != "tiles" && s != "registration" && s != "bridge") {
      throw UsageError("--restart: '" + s + "' is not a service of the run (tracking, estimator, tiles, registration, "
                       "bridge, or none)");
    }
    if ((s == "tracking" || s == "estimator") && !o.realtime) {
      throw UsageError("--restart " + s + " needs --realtime: in lockstep replay ingest waits for " + s +
                       "'s acknowledgement of every frame");
    }
    services.insert(s);
  }
  return services;
}

}  // namespace twinslam::cli

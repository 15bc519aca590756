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

void check_shared_edge(const RunOptions& o, bool twin_mode, bool domain_given) {
  if (!o.shared_edge) return;
  if (!twin_mode) throw UsageError("--shared-edge: mode '" + o.mode + "' uses no edge (a twin mode does)");
  if (!domain_given) {
    throw UsageError("--shared-edge: give the edge's DDS domain (--domain or TWINSLAM_DOMAIN); a private one would "
                     "never meet it");
  }
  if (o.vehicle.empty() || o.vehicle.find_first_of("*?[],") != std::string::npos) {
    throw UsageError("--shared-edge: the vehicle id '" + o.vehicle + "' names this vehicle's DDS partition: give a "
                     "plain name, not empty, no pattern or comma");
  }
  if (!o.edge_netns.empty()) throw UsageError("--shared-edge: the edge is not the run's, --edge-netns cannot place it");
  if (o.secure) throw UsageError("--shared-edge with --secure is not implemented (the permissions name no partitions)");
}

std::set<std::string> external_set(const RunOptions& o, bool twin_mode, bool domain_given) {
  std::set<std::string> services;
  if (o.external.empty()) return services;
  for (const auto name : split(o.external, ',')) {
    const std::string s(name);
    if (s != "tracking" && s != "estimator" && s != "tiles" && s != "registration") {
      throw UsageError("--external: '" + s + "' is not a service the run can leave to others (tracking, estimator, "
                       "tiles, registration)");
    }
    if (s == "tracking" && o.features) throw UsageError("--external tracking: with --features the run has no tracking");
    if ((s == "tiles" || s == "registration") && !twin_mode) {
      throw UsageError("--external " + s + ": mode '" + o.mode + "' uses no " + s + " (a twin mode does)");
    }
    services.insert(s);
  }
  if (!domain_given) {
    throw UsageError("--external: give the DDS domain the services run in (--domain or TWINSLAM_DOMAIN); a private one "
                     "would never meet them");
  }
  if (o.secure) throw UsageError("--external with --secure is not implemented (the run cannot hand out identities)");
  if (o.shared_edge) throw UsageError("--external and --shared-edge: name the edge's services in --external instead");
  if (!o.edge_netns.empty() && (services.contains("tiles") || services.contains("registration"))) {
    throw UsageError("--external: tiles and registration run elsewhere, --edge-netns cannot place them");
  }
  return services;
}

bool started_by_run(const RunOptions& o, const std::set<std::string>& external, const std::string& s) {
  if (o.shared_edge && (s == "tiles" || s == "registration")) return false;
  return !external.contains(s);
}

}  // namespace twinslam::cli

#include "launch_file.hpp"

#include <set>

#include <yaml-cpp/yaml.h>

#include "twinslam/core/error.hpp"
#include "twinslam/core/text.hpp"

namespace twinslam::cli {
namespace fs = std::filesystem;

namespace {
void check_keys(const fs::path& file, const YAML::Node& node, const std::set<std::string>& allowed,
                const std::string& context) {
  for (const auto& kv : node) {
    const auto key = kv.first.as<std::string>();
    if (allowed.count(key) == 0) throw InputError(file.string() + ": unknown key '" + context + key + "'");
  }
}

std::map<std::string, std::string> read_env(const fs::path& file, const YAML::Node& node, const std::string& ctx) {
  std::map<std::string, std::string> env;
  if (!node) return env;
  if (!node.IsMap()) throw InputError(file.string() + ": '" + ctx + "' must be a map of NAME: value");
  for (const auto& kv : node) env[kv.first.as<std::string>()] = expand_env(kv.second.as<std::string>());
  return env;
}
}  // namespace

LaunchFile load_launch_file(const fs::path& file) {
  if (!fs::is_regular_file(file)) throw InputError(file.string() + ": launch file not found");
  YAML::Node root;
  try {
    root = YAML::LoadFile(file.string());
  } catch (const YAML::Exception& e) {
    throw InputError(file.string() + ":" + std::to_string(e.mark.line + 1) + ": invalid YAML: " + e.msg);
  }
  if (!root.IsMap()) throw InputError(file.string() + ": expected a map with 'services'");
  try {
    check_keys(file, root, {"name", "env", "services"}, "");
    LaunchFile out;
    out.name = root["name"] ? root["name"].as<std::string>() : file.stem().string();
    const auto common_env = read_env(file, root["env"], "env");
    const auto services = root["services"];
    if (!services || !services.IsSequence() || services.size() == 0) {
      throw InputError(file.string() + ": 'services' must be a non-empty list");
    }
    std::set<std::string> names;
    const fs::path base = fs::absolute(file).parent_path();
    for (std::size_t i = 0; i < services.size(); ++i) {
      const auto s = services[i];
      const std::string ctx = "services[" + std::to_string(i) + "].";
      if (!s.IsMap()) throw InputError(file.string() + ": '" + ctx + "' must be a map");
      check_keys(file, s, {"name", "exec", "args", "env", "required", "cwd", "restart", "max_restarts"}, ctx);
      if (!s["name"] || !s["exec"]) throw InputError(file.string() + ": '" + ctx + "' needs 'name' and 'exec'");
      process::ProcessSpec spec;
      spec.name = s["name"].as<std::string>();
      if (!names.insert(spec.name).second) {
        throw InputError(file.string() + ": duplicate service name '" + spec.name + "'");
      }
      spec.exec = expand_env(s["exec"].as<std::string>());
      if (s["args"]) {
        if (!s["args"].IsSequence()) throw InputError(file.string() + ": '" + ctx + "args' must be a list");
        for (const auto& a : s["args"]) spec.args.push_back(expand_env(a.as<std::string>()));
      }
      spec.env = common_env;
      for (const auto& [k, v] : read_env(file, s["env"], ctx + "env")) spec.env[k] = v;
      spec.required = s["required"] ? s["required"].as<bool>() : false;
      spec.cwd = s["cwd"] ? base / expand_env(s["cwd"].as<std::string>()) : base;
      const std::string restart = s["restart"] ? s["restart"].as<std::string>() : "never";
      if (restart != "never" && restart != "on-failure") {
        throw InputError(file.string() + ": '" + ctx + "restart' must be never or on-failure, not '" + restart + "'");
      }
      spec.restart_on_failure = restart == "on-failure";
      if (s["max_restarts"]) spec.max_restarts = s["max_restarts"].as<int>();
      if (spec.max_restarts < 0 || spec.max_restarts > 1000) {
        throw InputError(file.string() + ": '" + ctx + "max_restarts' must lie in [0, 1000]");
      }
      out.services.push_back(std::move(spec));
    }
    return out;
  } catch (const YAML::Exception& e) {
    throw InputError(file.string() + ":" + std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
}

}  // namespace twinslam::cli

#pragma once
// Strict typed access to one YAML mapping of the scenario file: every error names the file, the line and the dotted
// key ("scen.yaml:12: imu.rate_hz: expected a number"). Private to the scenario library.
#include <array>
#include <initializer_list>
#include <map>
#include <string>

#include <yaml-cpp/yaml.h>

namespace twinslam::sim::detail {

class YamlReader {
 public:
  YamlReader(const std::string& file, std::map<std::string, std::size_t>& lines) : file_(file), lines_(lines) {}

  // Throws on a key of `map` (a mapping at `prefix`) that is not in `allowed`.
  void check_keys(const YAML::Node& map, const std::string& prefix, std::initializer_list<const char*> allowed) const;
  // `node` must be a mapping (or absent); `key` names it in the message.
  void expect_map(const YAML::Node& node, const std::string& key) const;

  // Each reads map[name] into `out` when present (absent keys keep the base value) and records its line.
  void read(const YAML::Node& map, const std::string& prefix, const char* name, double& out) const;
  void read(const YAML::Node& map, const std::string& prefix, const char* name, int& out) const;
  void read(const YAML::Node& map, const std::string& prefix, const char* name, std::uint64_t& out) const;
  void read(const YAML::Node& map, const std::string& prefix, const char* name, std::string& out) const;
  template <std::size_t N>
  void read(const YAML::Node& map, const std::string& prefix, const char* name, std::array<double, N>& out) const {
    const YAML::Node n = map[name];
    if (!n) return;
    const std::string key = prefix + name;
    record(key, n);
    if (!n.IsSequence() || n.size() != N) fail(n, key, "expected a list of " + std::to_string(N) + " numbers");
    for (std::size_t i = 0; i < N; ++i) out[i] = number(n[i], key);
  }

  double number(const YAML::Node& n, const std::string& key) const;
  long long integer(const YAML::Node& n, const std::string& key) const;
  [[noreturn]] void fail(const YAML::Node& n, const std::string& key, const std::string& what) const;
  void record(const std::string& key, const YAML::Node& n) const;

 private:
  const std::string& file_;
  std::map<std::string, std::size_t>& lines_;  // dotted key -> 1-based line, for range errors found later
};

}  // namespace twinslam::sim::detail

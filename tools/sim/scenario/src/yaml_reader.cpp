#include "yaml_reader.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "twinslam/core/error.hpp"

namespace twinslam::sim::detail {

namespace {
std::size_t line_of(const YAML::Node& n) {
  const int line = n.Mark().line;  // 0-based, -1 when unknown
  return line >= 0 ? static_cast<std::size_t>(line) + 1 : 0;
}
}  // namespace

void YamlReader::fail(const YAML::Node& n, const std::string& key, const std::string& what) const {
  throw InputError(where(file_, line_of(n), key + ": " + what));
}

void YamlReader::record(const std::string& key, const YAML::Node& n) const { lines_[key] = line_of(n); }

void YamlReader::expect_map(const YAML::Node& node, const std::string& key) const {
  if (node && !node.IsMap()) fail(node, key, "expected a mapping of keys");
}

void YamlReader::check_keys(const YAML::Node& map, const std::string& prefix,
                            std::initializer_list<const char*> allowed) const {
  for (const auto& kv : map) {
    // A key that is itself a sequence or mapping has no name: as<std::string>() would throw yaml-cpp's
    // BadConversion past the InputError contract (found by fuzzing).
    if (!kv.first.IsScalar()) fail(kv.first, prefix + "?", "a key must be a plain name");
    const std::string name = kv.first.Scalar();
    bool known = false;
    for (const char* a : allowed) known = known || name == a;
    if (known) continue;
    std::string list;
    for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
    fail(kv.first, prefix + name, "unknown key (known here: " + list + ")");
  }
}

double YamlReader::number(const YAML::Node& n, const std::string& key) const {
  if (!n.IsScalar()) fail(n, key, "expected a number");
  const std::string& s = n.Scalar();
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || end != s.c_str() + s.size() || errno == ERANGE) fail(n, key, "expected a number, got '" + s + "'");
  if (!std::isfinite(v)) fail(n, key, "must be finite");
  return v;
}

long long YamlReader::integer(const YAML::Node& n, const std::string& key) const {
  if (!n.IsScalar()) fail(n, key, "expected an integer");
  const std::string& s = n.Scalar();
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(s.c_str(), &end, 10);
  if (s.empty() || end != s.c_str() + s.size() || errno == ERANGE) fail(n, key, "expected an integer, got '" + s + "'");
  return v;
}

void YamlReader::read(const YAML::Node& map, const std::string& prefix, const char* name, double& out) const {
  if (const YAML::Node n = map[name]) {
    record(prefix + name, n);
    out = number(n, prefix + name);
  }
}

void YamlReader::read(const YAML::Node& map, const std::string& prefix, const char* name, int& out) const {
  if (const YAML::Node n = map[name]) {
    record(prefix + name, n);
    const long long v = integer(n, prefix + name);
    if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max()) fail(n, prefix + name, "too large");
    out = static_cast<int>(v);
  }
}

void YamlReader::read(const YAML::Node& map, const std::string& prefix, const char* name, std::uint64_t& out) const {
  if (const YAML::Node n = map[name]) {
    record(prefix + name, n);
    const long long v = integer(n, prefix + name);
    if (v < 0) fail(n, prefix + name, "must be >= 0");
    out = static_cast<std::uint64_t>(v);
  }
}

void YamlReader::read(const YAML::Node& map, const std::string& prefix, const char* name, std::string& out) const {
  if (const YAML::Node n = map[name]) {
    record(prefix + name, n);
    if (!n.IsScalar()) fail(n, prefix + name, "expected a text value");
    out = n.Scalar();
  }
}

}  // namespace twinslam::sim::detail

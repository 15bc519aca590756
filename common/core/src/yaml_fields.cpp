#include "twinslam/core/yaml_fields.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "twinslam/core/error.hpp"

namespace twinslam::yaml {

// Where a value is read: the file, and the key's full name for messages ("keyframe.min_tracked_ratio").
struct Place {
  const std::string& file;
  const std::string& section;
  std::string key;
};

struct Fields::Entry {
  std::string key;
  std::function<void(const YAML::Node&, const Place&)> read;
  std::function<std::string()> show;  // the field's value as a YAML scalar
  std::unique_ptr<Fields> nested;     // set for section()
};

namespace {

std::size_t line_of(const YAML::Node& node) { return static_cast<std::size_t>(node.Mark().line + 1); }

[[noreturn]] void bad(const Place& at, std::size_t line, const std::string& what) {
  throw InputError(where(at.file, line, at.section + " key '" + at.key + "': " + what));
}

template <class T>
T read_as(const YAML::Node& node, const Place& at, const std::string& expected) {
  if (!node.IsScalar()) bad(at, line_of(node), "expected " + expected);
  try {
    return node.as<T>();
  } catch (const YAML::Exception&) {
    bad(at, line_of(node), "expected " + expected);
  }
}

std::string show_number(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

std::string join(const std::vector<std::string>& names, const char* separator) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : separator) + n;
  return out;
}

}  // namespace

// Walks a mapping against a table (a friend, so the table's entries stay private).
struct FieldsWalker {
  static void walk(const Fields& fields, const YAML::Node& map, const std::string& file, const std::string& prefix) {
    for (const auto& item : map) {
      const std::string key = item.first.Scalar();
      const Place at{file, fields.section_, prefix + key};
      const Fields::Entry* entry = nullptr;
      for (const auto& e : fields.entries_) {
        if (e.key == key) entry = &e;
      }
      if (entry == nullptr) bad(at, line_of(item.first), "unknown key (known: " + known(fields) + ")");
      if (entry->nested) {
        if (!item.second.IsMap()) bad(at, line_of(item.second), "expected a mapping of " + at.key + " keys");
        walk(*entry->nested, item.second, file, at.key + ".");
      } else {
        entry->read(item.second, at);
      }
    }
  }

  static std::string known(const Fields& fields) {
    std::vector<std::string> names;
    for (const auto& e : fields.entries_) names.push_back(e.key);
    return join(names, ", ");
  }
};

Fields::Fields(std::string section) : section_(std::move(section)) {}
Fields::~Fields() = default;
Fields::Fields(Fields&&) noexcept = default;
Fields& Fields::operator=(Fields&&) noexcept = default;

Fields& Fields::add(Entry entry) {
  entries_.push_back(std::move(entry));
  return *this;
}

Fields& Fields::number(const std::string& key, double& field, const std::string& unit) {
  const std::string expected = unit.empty() ? "a number" : "a number [" + unit + "]";
  return add({key, [&field, expected](const YAML::Node& node, const Place& at) {
                const double v = read_as<double>(node, at, expected);
                if (!std::isfinite(v)) bad(at, line_of(node), "expected a finite number, got " + node.Scalar());
                field = v;
              }, [&field] { return show_number(field); }, nullptr});
}

Fields& Fields::integer(const std::string& key, int& field) {
  return add({key, [&field](const YAML::Node& node, const Place& at) { field = read_as<int>(node, at, "an integer"); },
              [&field] { return std::to_string(field); }, nullptr});
}

Fields& Fields::count(const std::string& key, unsigned& field) {
  return add({key, [&field](const YAML::Node& node, const Place& at) {
                const long long v = read_as<long long>(node, at, "a non-negative integer");
                if (v < 0 || v > static_cast<long long>(~0u)) bad(at, line_of(node), "expected a non-negative integer");
                field = static_cast<unsigned>(v);
              }, [&field] { return std::to_string(field); }, nullptr});
}

Fields& Fields::flag(const std::string& key, bool& field) {
  return add({key, [&field](const YAML::Node& node, const Place& at) {
                field = read_as<bool>(node, at, "true or false");
              }, [&field] { return std::string(field ? "true" : "false"); }, nullptr});
}

Fields& Fields::text(const std::string& key, std::string& field, const std::string& what) {
  return add({key, [&field, what](const YAML::Node& node, const Place& at) {
                field = read_as<std::string>(node, at, what);
              }, [&field] { return field; }, nullptr});
}

Fields& Fields::milliseconds(const std::string& key, std::chrono::milliseconds& field) {
  return add({key, [&field](const YAML::Node& node, const Place& at) {
                field = std::chrono::milliseconds(read_as<long long>(node, at, "an integer [ms]"));
              }, [&field] { return std::to_string(field.count()); }, nullptr});
}

Fields& Fields::choice_index(const std::string& key, std::vector<std::string> names,
                             std::function<void(std::size_t)> set, std::function<std::size_t()> get) {
  auto show = [names, get = std::move(get)] {
    const std::size_t i = get();
    return i < names.size() ? names[i] : std::string("?");
  };
  return add({key, [names = std::move(names), set = std::move(set)](const YAML::Node& node, const Place& at) {
                const std::string expected = "one of " + join(names, " | ");
                const auto value = read_as<std::string>(node, at, expected);
                for (std::size_t i = 0; i < names.size(); ++i) {
                  if (names[i] == value) return set(i);
                }
                bad(at, line_of(node), "expected " + expected + ", got " + value);
              }, std::move(show), nullptr});
}

Fields& Fields::section(const std::string& key) {
  add({key, {}, {}, std::make_unique<Fields>(section_)});
  return *entries_.back().nested;
}

void Fields::parse(const std::string& text, const std::string& file) const {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(where(file, static_cast<std::size_t>(e.mark.line + 1), "malformed YAML: " + e.msg));
  }
  if (root.IsNull()) return;
  if (!root.IsMap()) throw InputError(where(file, 0, "expected a YAML mapping of " + section_ + " keys"));
  FieldsWalker::walk(*this, root, file, "");
}

void Fields::load(const std::string& path) const { parse(read_text_file(path), path); }

std::vector<std::pair<std::string, std::string>> Fields::values() const {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& e : entries_) {
    if (!e.nested) {
      out.emplace_back(e.key, e.show());
      continue;
    }
    for (auto& [key, value] : e.nested->values()) out.emplace_back(e.key + "." + key, std::move(value));
  }
  return out;
}

std::string changed_values(const std::vector<std::pair<std::string, std::string>>& now,
                           const std::vector<std::pair<std::string, std::string>>& base) {
  std::vector<std::string> changed;
  for (std::size_t i = 0; i < now.size(); ++i) {
    if (i >= base.size() || now[i] != base[i]) changed.push_back(now[i].first + "=" + now[i].second);
  }
  return changed.empty() ? "all defaults" : join(changed, ", ");
}

std::string read_text_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(where(path, 0, "cannot open file"));
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace twinslam::yaml

#pragma once
// Reading a config struct from a YAML mapping, one line per key. A Fields table binds each key to a member of the
// struct (with its type, and its unit for the messages); parse() assigns the keys a document has and leaves the others
// at their values (the defaults). Malformed YAML, a key the table does not know, a value of the wrong type, NaN or
// infinity throw twinslam::InputError, one line naming the file, the line and the key:
//   "estimator.yaml:7: estimator key 'keyframe.min_tracked_ratio': expected a number"
//   "tiles.yaml:1: tiles key 'window': unknown key (known: window_m, cache_tiles, twin_dir, max_tiles_on_wire)"
// Range checks stay in each struct's validate(). A table holds references to the members it binds: build it next to
// the struct, use it, drop it. No yaml-cpp and no service knowledge in this header.
#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace twinslam::yaml {

class Fields {
 public:
  // `section` names the keys in messages ("tiles" -> "tiles key 'window_m'").
  explicit Fields(std::string section);
  ~Fields();
  Fields(Fields&&) noexcept;
  Fields& operator=(Fields&&) noexcept;

  // A finite number; `unit` (e.g. "m") shows in the message "expected a number [m]".
  Fields& number(const std::string& key, double& field, const std::string& unit = "");
  Fields& integer(const std::string& key, int& field);
  Fields& count(const std::string& key, unsigned& field);  // a non-negative integer
  Fields& flag(const std::string& key, bool& field);       // true / false
  // A string; `what` names it in the message ("expected a path").
  Fields& text(const std::string& key, std::string& field, const std::string& what = "a string");
  // An integer number of milliseconds (keys end in _ms).
  Fields& milliseconds(const std::string& key, std::chrono::milliseconds& field);
  // One of the given names, e.g. ransac_model: essential | known_rotation.
  template <class E>
  Fields& choice(const std::string& key, E& field, const std::vector<std::pair<std::string, E>>& names) {
    std::vector<std::string> keys;
    for (const auto& [name, value] : names) keys.push_back(name);
    return choice_index(
        key, keys, [&field, names](std::size_t i) { field = names[i].second; },
        [&field, names] {
          for (std::size_t i = 0; i < names.size(); ++i) {
            if (names[i].second == field) return i;
          }
          return names.size();
        });
  }
  // A nested mapping `key: {...}`; the returned table (owned by this one) binds its keys.
  Fields& section(const std::string& key);

  // Assigns the keys of the YAML document `text` (`file` only names it in messages). An empty document changes
  // nothing; anything but a mapping at the top is an error.
  void parse(const std::string& text, const std::string& file) const;
  // Reads the file at `path` and parses it ("PATH: cannot open file" if it cannot be read).
  void load(const std::string& path) const;

  // Every bound key (nested ones as "section.key") with the current value of its field as a YAML scalar, in binding
  // order: to log the effective config, or to compare two configs key by key.
  std::vector<std::pair<std::string, std::string>> values() const;

  struct Entry;  // one key: how to read its value (a YAML::Node, so defined in the .cpp)

 private:
  friend struct FieldsWalker;
  Fields& choice_index(const std::string& key, std::vector<std::string> names, std::function<void(std::size_t)> set,
                       std::function<std::size_t()> get);
  Fields& add(Entry entry);

  std::string section_;
  std::vector<Entry> entries_;
};

// "key=value, ..." for each key whose value in `now` differs from `base` (both values() of tables bound alike), or
// "all defaults": what a service logs about its config.
std::string changed_values(const std::vector<std::pair<std::string, std::string>>& now,
                           const std::vector<std::pair<std::string, std::string>>& base);

// The whole file as a string; InputError "PATH: cannot open file".
std::string read_text_file(const std::string& path);

}  // namespace twinslam::yaml

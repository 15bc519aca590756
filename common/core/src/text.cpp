#include "twinslam/core/text.hpp"

#include <cstdlib>

namespace twinslam {

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r\n");
  return s.substr(first, last - first + 1);
}

std::vector<std::string_view> split(std::string_view s, char sep) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  while (true) {
    const auto pos = s.find(sep, start);
    out.push_back(s.substr(start, pos == std::string_view::npos ? std::string_view::npos : pos - start));
    if (pos == std::string_view::npos) break;
    start = pos + 1;
  }
  return out;
}

std::string expand_env(std::string_view s) {
  std::string out;
  std::size_t i = 0;
  while (i < s.size()) {
    if (s[i] == '$' && i + 1 < s.size() && s[i + 1] == '{') {
      const auto close = s.find('}', i + 2);
      if (close != std::string_view::npos) {
        std::string_view body = s.substr(i + 2, close - i - 2);
        std::string_view fallback;
        bool has_fallback = false;
        if (const auto dash = body.find(":-"); dash != std::string_view::npos) {
          fallback = body.substr(dash + 2);
          body = body.substr(0, dash);
          has_fallback = true;
        }
        const char* value = std::getenv(std::string(body).c_str());
        if (value != nullptr && *value != '\0') {
          out += value;
        } else if (has_fallback) {
          out += fallback;
        }
        i = close + 1;
        continue;
      }
    }
    out += s[i++];
  }
  return out;
}

}  // namespace twinslam

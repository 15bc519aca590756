#pragma once
// Small string helpers used by parsers and printers.
#include <string>
#include <string_view>
#include <vector>

namespace twinslam {

std::string_view trim(std::string_view s);
std::vector<std::string_view> split(std::string_view s, char sep);
// Replaces ${NAME} and ${NAME:-default} with environment values (launch files, deploy configs).
std::string expand_env(std::string_view s);

}  // namespace twinslam

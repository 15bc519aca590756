#pragma once
// Source-tree checks of the architecture's walls (docs/ARCHITECTURE.md). Scans C++ sources and CMakeLists.txt files.
#include <filesystem>
#include <string>
#include <vector>

namespace twinslam::testing {

// One line per violation: "<file>:<line>: <rule>: <text>". Services are the folders of root/services.
std::vector<std::string> wall_violations(const std::filesystem::path& root);

}  // namespace twinslam::testing

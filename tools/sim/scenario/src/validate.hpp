#pragma once
// Private: validation that can name the line a key came from (the parser records them).
#include <map>
#include <string>

#include "twinslam/sim/scenario.hpp"

namespace twinslam::sim::detail {

void validate_scenario_at(const Scenario& s, const std::string& file, const std::map<std::string, std::size_t>& lines);

}  // namespace twinslam::sim::detail

#pragma once
// The fusion modes of `twinslam run` / `bench` (docs/CONTRACTS.md) and which of them are implemented today. A mode
// that is not implemented is refused (exit 2, one line naming it) instead of silently running plain VIO.
#include <string>
#include <vector>

namespace twinslam::cli {

// Every mode name the contract defines, in table order.
const std::vector<std::string>& all_modes();
bool mode_implemented(const std::string& mode);
// Throws UsageError "mode 'M' is not implemented yet (...); implemented: ..." for a known but unimplemented mode.
void require_implemented_mode(const std::string& mode);
// "vio" today: the comma-separated implemented modes, for messages.
std::string implemented_modes_text();

}  // namespace twinslam::cli

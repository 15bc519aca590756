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

// What a mode asks of the pipeline.
bool uses_twin(const std::string& mode);  // vio-twin*: tiles, registration, the estimator fuses registrations
// Modes whose estimator fuses GNSS fixes as window terms (tightly coupled).
bool fuses_gnss(const std::string& mode);
// The loosely coupled mode: a pose graph apart from the VIO (loose_gnss_fusion.hpp).
bool fuses_gnss_loose(const std::string& mode);
bool needs_gnss(const std::string& mode);  // either of the two above

}  // namespace twinslam::cli

#pragma once
#include <string>
namespace twinslam {
// All log lines go to stderr ("HH:MM:SS.mmm level message"), so stdout carries only a command's real output
// (JSON, tables) and can be piped. Throws UsageError for an unknown level name.
void init_logging(const std::string& level = "info");
}  // namespace twinslam

#pragma once
// Entry point wrapper shared by every executable: turns exceptions into the exit codes of CONTRACTS.md and a single
// line on stderr ("<program>: <reason>"), so no bad input ever ends in a crash or a stack of messages.
#include <functional>
#include <string>

namespace twinslam {

constexpr int kExitOk = 0;
constexpr int kExitInternal = 1;
constexpr int kExitBadInput = 2;

int guarded_main(const std::string& program, const std::function<int()>& body);

}  // namespace twinslam

#pragma once
// Process-wide stop request: SIGINT/SIGTERM set a flag that every loop polls, so services leave their loops, delete
// their DDS entities in order and remove their shared-memory files instead of dying mid-write.
#include <chrono>

namespace twinslam {

// Installs the SIGINT/SIGTERM handlers (idempotent). A second signal while stopping terminates at once.
void install_shutdown_handlers();
// True once a stop was requested by a signal or by request_shutdown().
bool shutdown_requested();
void request_shutdown();
// Sleeps up to `timeout`, returning early (true) when a stop is requested.
bool wait_for_shutdown(std::chrono::milliseconds timeout);

}  // namespace twinslam

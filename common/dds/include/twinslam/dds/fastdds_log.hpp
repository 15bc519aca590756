#pragma once
namespace twinslam::dds {
// Sends Fast DDS's own log (errors and warnings) through spdlog as single lines tagged "fastdds", instead of its
// multi-line console format, so a service's stderr stays one line per event. Errors always; warnings at
// debug level. Call after init_logging(). Idempotent.
void route_fastdds_log();
}  // namespace twinslam::dds

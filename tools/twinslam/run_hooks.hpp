#pragma once
// What `twinslam run` records from the pipeline's topics: hooks on the run's TopicMonitor turn one vehicle's camera
// frames, odometry, local maps and registrations into RunRecord entries (run_record.hpp).
#include <atomic>
#include <cstddef>
#include <functional>
#include <string>

#include "monitor.hpp"
#include "run_record.hpp"

namespace twinslam::cli {

// Hooks that record the messages of `vehicle` into `record`; `since_ms` is the run's clock [ms], `poses` counts the
// estimator's finished frames (the progress bar). With `features` the feature frames are the camera frames coming in.
// Only this vehicle: an edge shared by a fleet (--shared-edge) answers every vehicle in partitions this run also
// reads, and keyframe stamps of different vehicles can coincide.
MonitorHooks record_hooks(RunRecord& record, const std::string& vehicle, bool features,
                          std::function<double()> since_ms, std::atomic<std::size_t>& poses);

OdometryRecord to_record(const msg::Odometry& m);
// The correction as the keyframe's position change dp [m] and its roll, pitch, yaw [deg].
RegistrationRecord to_record(const msg::Registration& m);

}  // namespace twinslam::cli

#pragma once
// Reading back a run folder written by `twinslam run` (CONTRACTS.md "Run outputs") for the commands that work on
// one: export, twin changes.
#include <filesystem>

#include <nlohmann/json.hpp>

#include "twinslam/trajectory/trajectory.hpp"
#include "twinslam/twin/geo.hpp"

namespace twinslam::cli {

// RUN/run.json; InputError naming it when missing or malformed.
nlohmann::json read_run_json(const std::filesystem::path& run);

// W's origin: run.json's, else the run's dataset's dataset.yaml; InputError when neither has one.
twin::GeoOrigin run_origin(const std::filesystem::path& run, const nlohmann::json& run_json);

// RUN/trajectory.tum from where it entered W (run.json aligned_from_stamp_ns); InputError when it never did.
Trajectory estimate_in_W(const std::filesystem::path& run, const nlohmann::json& run_json);

}  // namespace twinslam::cli

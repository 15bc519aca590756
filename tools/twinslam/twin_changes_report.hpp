#pragma once
// `twinslam twin changes RUN` (CONTRACTS.md): where a run's landmarks disagree with its dataset's twin
// (twin/changes.hpp), written as RUN/twin_changes.geojson (footprints in WGS84 with their evidence) and a top-down
// RUN/twin_changes.png (the twin's roofs, the flight, the evidence, the footprints).
#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

#include "twinslam/trajectory/trajectory.hpp"
#include "twinslam/twin/changes.hpp"
#include "twinslam/twin/geo.hpp"

namespace twinslam::cli {

// RUN/landmarks.csv (times in seconds after epoch_ns), without the landmarks last estimated before
// `aligned_from_ns`: their position in W went through the alignment of that time, not yet the declared one.
// InputError naming the file when it is missing or malformed.
std::vector<twin::LandmarkSighting> read_sightings(const std::filesystem::path& run, std::int64_t epoch_ns,
                                                   std::int64_t aligned_from_ns);

// A FeatureCollection: one Polygon Feature per change (closed ring, [lon, lat]) with properties kind, landmarks,
// sight_lines, mean_distance_m, mean_depth_m, first_s, last_s and footprint_W ([[e, n], ...] in W).
nlohmann::json changes_geojson(const std::vector<twin::TwinChange>& changes, const twin::EnuFrame& W);

// The whole report of a run folder: its dataset's twin, its landmarks in W, the changes found, written to
// OUT/twin_changes.geojson and OUT/twin_changes.png, one summary line on stdout if `print` (cmd_twin_changes.cpp).
// InputError naming the file for a run that cannot be compared (no dataset or twin, never in W, no landmarks).
twin::TwinChanges write_twin_change_report(const std::filesystem::path& run, const std::filesystem::path& out,
                                           const twin::TwinChangeConfig& config = {}, bool print = true);

// Top-down PNG: twin triangles in grey (lighter = higher), the flight in blue, the footprints in red.
void write_changes_png(const std::filesystem::path& png, const twin::Mesh& twin_W, const Trajectory& trajectory_W,
                       const std::vector<twin::TwinChange>& changes, int max_side_px = 1200);

}  // namespace twinslam::cli

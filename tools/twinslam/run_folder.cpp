#include "run_folder.hpp"

#include <fstream>

#include "dataset_twin.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/trajectory/io.hpp"

namespace twinslam::cli {
namespace fs = std::filesystem;

nlohmann::json read_run_json(const fs::path& run) {
  const fs::path file = run / "run.json";
  std::ifstream in(file);
  if (!in) throw InputError(file.string() + ": missing (not a run folder written by `twinslam run`)");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file.string() + ": malformed JSON: " + e.what());
  }
}

// W's origin: run.json's (runs since exports exist), else the run's dataset's dataset.yaml.
twin::GeoOrigin run_origin(const fs::path& run, const nlohmann::json& j) {
  const fs::path file = run / "run.json";
  try {
    if (j.contains("origin") && j["origin"].is_object()) {
      return {j["origin"].at("lat_deg").get<double>(), j["origin"].at("lon_deg").get<double>(),
              j["origin"].at("alt_m").get<double>()};
    }
    const std::string dataset = j.value("dataset", "");
    if (!dataset.empty() && fs::exists(fs::path(dataset) / "dataset.yaml")) return read_dataset_geo(dataset).origin;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file.string() + ": malformed origin: " + e.what());
  }
  throw InputError(file.string() + ": no origin of W (its dataset has no dataset.yaml origin): the run has no place "
                   "on Earth to export");
}

// The estimate from where it entered W; InputError when it never did (mode vio: a local frame only).
Trajectory estimate_in_W(const fs::path& run, const nlohmann::json& j) {
  const auto from = j.find("aligned_from_stamp_ns");
  if (from == j.end() || !from->is_number_integer()) {
    throw InputError((run / "run.json").string() + ": the run never aligned to W (mode " + j.value("mode", "?") +
                     "): its trajectory has no geographic position");
  }
  Trajectory est = read_run_trajectory(run);
  const std::int64_t first = from->get<std::int64_t>();
  std::erase_if(est.poses, [first](const StampedPose& p) { return p.stamp_ns < first; });
  return est;
}

}  // namespace twinslam::cli

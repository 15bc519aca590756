// `twinslam export RUN [--geojson] [--kml] [--ply] [--out DIR]` (CONTRACTS.md "Exports"): the run's trajectory in W,
// with the dataset's GNSS fixes and ground truth when the dataset is at hand, as GeoJSON / KML in WGS84 through W's
// origin; the landmarks it estimated in W (RUN/landmarks.csv) as a PLY point cloud with the origin in its header.
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "dataset_twin.hpp"
#include "run_folder.hpp"
#include "export_geo.hpp"
#include "twinslam/core/csv.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/core/main_guard.hpp"
#include "twinslam/ingest/dataset.hpp"
#include "twinslam/trajectory/io.hpp"
#include "twinslam/twin/ply.hpp"

namespace twinslam::cli {
namespace fs = std::filesystem;

namespace {

// The dataset's GNSS fixes and ground truth, when the run's dataset is still where run.json says (else a note).
std::vector<GeoTrack> dataset_tracks(const nlohmann::json& j, const twin::EnuFrame& W) {
  std::vector<GeoTrack> tracks;
  const fs::path dataset = j.value("dataset", "");
  try {
    const auto data = ingest::load_dataset(dataset, ingest::CameraInput::kFeatureTracks);  // no image is read
    GeoTrack gnss{"gnss", {}, {}};
    for (const auto& g : data.gnss) {
      gnss.stamps_ns.push_back(g.stamp_ns);
      gnss.lla.emplace_back(g.latitude_deg, g.longitude_deg, g.altitude_m);
    }
    tracks.push_back(std::move(gnss));
    tracks.push_back(track_from_W("ground_truth", read_dataset_groundtruth(dataset), W));
  } catch (const InputError& e) {
    std::cerr << "export: dataset tracks left out: " << e.what() << std::endl;
  }
  return tracks;
}

// RUN/landmarks.csv -> a point set in W.
twin::Mesh read_landmarks(const fs::path& run) {
  const fs::path file = run / "landmarks.csv";
  if (!fs::exists(file)) {
    throw InputError(file.string() + ": missing: only runs aligned to W record their landmarks (twin or GNSS modes)");
  }
  twin::Mesh cloud;
  read_csv(file, 10, [&](const CsvRow& row) {
    cloud.p_W.emplace_back(parse_double(file, row, 3, "x_W"), parse_double(file, row, 4, "y_W"),
                           parse_double(file, row, 5, "z_W"));
  });
  if (cloud.p_W.empty()) throw InputError(file.string() + ": no landmarks");
  return cloud;
}

struct ExportOptions {
  std::string run, out;
  bool geojson = false, kml = false, ply = false;
};

int run_export(const ExportOptions& o) {
  if (!o.geojson && !o.kml && !o.ply) throw UsageError("export: give at least one of --geojson, --kml, --ply");
  const fs::path run(o.run), out = o.out.empty() ? run : fs::path(o.out);
  const nlohmann::json j = read_run_json(run);
  const twin::GeoOrigin origin = run_origin(run, j);
  fs::create_directories(out);
  if (o.geojson || o.kml) {
    const twin::EnuFrame W(origin);
    std::vector<GeoTrack> tracks{track_from_W("estimate", estimate_in_W(run, j), W)};
    for (auto& t : dataset_tracks(j, W)) tracks.push_back(std::move(t));
    if (o.geojson) {
      const fs::path file = out / "trajectory.geojson";
      std::ofstream f(file);
      if (!(f << tracks_geojson(tracks, origin).dump() << '\n')) throw InputError(file.string() + ": cannot write");
      std::printf("export: %s (%zu estimated poses)\n", file.string().c_str(), tracks.front().lla.size());
    }
    if (o.kml) {
      // EGM96 undulation through PROJ's egm96_15.gtx: (lon, lat, H = 0) -> ellipsoidal h = N.
      const twin::CrsTransform egm96("EPSG:4326+5773");
      const fs::path file = out / "trajectory.kml";
      std::ofstream f(file);
      const auto N = [&](double lat, double lon) { return egm96.to_lla({lon, lat, 0.0}).z(); };
      if (!(f << tracks_kml(tracks, N))) throw InputError(file.string() + ": cannot write");
      std::printf("export: %s (%zu estimated poses)\n", file.string().c_str(), tracks.front().lla.size());
    }
  }
  if (o.ply) {
    const twin::Mesh cloud = read_landmarks(run);
    const fs::path file = out / "landmarks_W.ply";
    twin::write_ply(file.string(), cloud, twin::PlyFormat::kBinaryLittleEndian, origin);
    std::printf("export: %s (%zu landmarks in W)\n", file.string().c_str(), cloud.p_W.size());
  }
  return kExitOk;
}

}  // namespace

void add_export_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("export", "Export a run: trajectory as GeoJSON / KML (WGS84), landmarks as PLY");
  auto o = std::make_shared<ExportOptions>();
  cmd->add_option("RUN", o->run, "Run folder written by `twinslam run`")->required();
  cmd->add_flag("--geojson", o->geojson, "Write trajectory.geojson (estimate, GNSS, ground truth; RFC 7946)");
  cmd->add_flag("--kml", o->kml, "Write trajectory.kml (KML 2.2, heights above EGM96 mean sea level)");
  cmd->add_flag("--ply", o->ply, "Write landmarks_W.ply (the run's landmarks in W, binary PLY with the origin)");
  cmd->add_option("--out", o->out, "Folder for the files (default: RUN)");
  cmd->callback([o, &exit_code] { exit_code = run_export(*o); });
}

}  // namespace twinslam::cli

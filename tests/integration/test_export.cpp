// `twinslam export` on a real tiny vio-twin run (issue 16 item 4): the GeoJSON / KML tracks start and end where an
// independent conversion (PROJ) puts the run's first and last pose in W, the landmark PLY opens with the project's
// reader, and runs that cannot be placed on Earth are refused with one line naming the file.
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <proj.h>

#include "proj_enu.hpp"
#include "subprocess.hpp"
#include "text_file.hpp"
#include "twinslam/trajectory/io.hpp"
#include "twinslam/twin/ply.hpp"

namespace fs = std::filesystem;
using namespace twinslam;
using twinslam::test::read_text;

namespace {


// EGM96 undulation N [m] (h = H + N) through PROJ's own WGS84 -> WGS84 + EGM96 height operation.
double egm96_undulation(double lat_deg, double lon_deg) {
  PJ_CONTEXT* ctx = proj_context_create();
  PJ* op = proj_create_crs_to_crs(ctx, "EPSG:4979", "EPSG:4326+5773", nullptr);
  PJ* norm = proj_normalize_for_visualization(ctx, op);  // (lon, lat, h) order
  const PJ_COORD H = proj_trans(norm, PJ_FWD, proj_coord(lon_deg, lat_deg, 0.0, 0.0));
  proj_destroy(norm);
  proj_destroy(op);
  proj_context_destroy(ctx);
  return -H.xyz.z;  // h = 0 on the ellipsoid is H = -N
}

// The folder of this test process: the tiny dataset, the run, the exports.
const fs::path& base() {
  static const fs::path dir = fs::temp_directory_path() / ("twinslam_export_" + std::to_string(::getpid()));
  return dir;
}

test::ProcessOutput export_run(const fs::path& run, const std::vector<std::string>& flags) {
  std::vector<std::string> argv{test::bin("twinslam"), "export", run.string(), "--out", (base() / "out").string()};
  argv.insert(argv.end(), flags.begin(), flags.end());
  return test::run_process(argv);
}

nlohmann::json run_json() { return nlohmann::json::parse(read_text(base() / "run/run.json")); }

// The run's estimate from its alignment to W on: what the exports must hold.
Trajectory estimate_in_W() {
  Trajectory t = read_run_trajectory(base() / "run");
  const std::int64_t from = run_json()["aligned_from_stamp_ns"].get<std::int64_t>();
  std::erase_if(t.poses, [from](const StampedPose& p) { return p.stamp_ns < from; });
  return t;
}

test::ProjEnu proj() {
  const auto o = run_json()["origin"];
  return test::ProjEnu(o["lat_deg"].get<double>(), o["lon_deg"].get<double>(), o["alt_m"].get<double>());
}

// The GeoJSON starts and ends at the run's first and last pose in W.
void check_geojson() {
  const auto r = export_run(base() / "run", {"--geojson"});
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const auto j = nlohmann::json::parse(read_text(base() / "out/trajectory.geojson"));
  const Trajectory est = estimate_in_W();
  ASSERT_GE(est.size(), 2u);
  const test::ProjEnu enu = proj();
  std::map<std::string, nlohmann::json> features;
  for (const auto& f : j["features"]) features[f["properties"]["name"]] = f;
  ASSERT_TRUE(features.count("estimate") && features.count("gnss") && features.count("ground_truth")) << j.dump(1);
  const auto& c = features["estimate"]["geometry"]["coordinates"];
  ASSERT_EQ(c.size(), est.size());
  const auto at = [&](std::size_t i) {
    return Eigen::Vector3d(c[i][1].get<double>(), c[i][0].get<double>(), c[i][2].get<double>());
  };
  EXPECT_LT(test::lla_distance_m(enu.to_lla(est.poses.front().p_X()), at(0)), 0.01);
  EXPECT_LT(test::lla_distance_m(enu.to_lla(est.poses.back().p_X()), at(c.size() - 1)), 0.01);
  // The GNSS fixes are the dataset's, as they were recorded.
  EXPECT_EQ(features["gnss"]["geometry"]["coordinates"].size(), run_json()["messages"]["twinslam/v1/gnss"]);
}

// The KML too, with heights above mean sea level (EGM96).
void check_kml() {
  const auto r = export_run(base() / "run", {"--kml"});
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const std::string kml = read_text(base() / "out/trajectory.kml");
  const auto start = kml.find("<name>estimate</name>");
  ASSERT_NE(start, std::string::npos);
  const std::string block = kml.substr(start, kml.find("</Placemark>", start) - start);
  const std::regex position(R"(([-0-9.]+),([-0-9.]+),([-0-9.]+)\n)");
  std::vector<Eigen::Vector3d> got;  // lat, lon, ellipsoidal h (H + N)
  for (auto it = std::sregex_iterator(block.begin(), block.end(), position); it != std::sregex_iterator(); ++it) {
    const double lat = std::stod((*it)[2]), lon = std::stod((*it)[1]);
    got.emplace_back(lat, lon, std::stod((*it)[3]) + egm96_undulation(lat, lon));
  }
  const Trajectory est = estimate_in_W();
  ASSERT_EQ(got.size(), est.size());
  const test::ProjEnu enu = proj();
  EXPECT_LT(test::lla_distance_m(enu.to_lla(est.poses.front().p_X()), got.front()), 0.01);
  EXPECT_LT(test::lla_distance_m(enu.to_lla(est.poses.back().p_X()), got.back()), 0.01);
}

// The landmark PLY opens with the project's reader and holds landmarks.csv's points in W, with the origin.
void check_ply() {
  const auto r = export_run(base() / "run", {"--ply"});
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const twin::PlyFile ply = twin::read_ply((base() / "out/landmarks_W.ply").string());
  std::vector<Eigen::Vector3d> csv;
  std::istringstream lines(read_text(base() / "run/landmarks.csv"));
  for (std::string line; std::getline(lines, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::stringstream row(line);
    std::string cell;
    std::vector<double> v;
    while (std::getline(row, cell, ',')) v.push_back(std::stod(cell));
    csv.emplace_back(v.at(3), v.at(4), v.at(5));
  }
  ASSERT_GT(csv.size(), 50u);
  ASSERT_EQ(ply.mesh.p_W.size(), csv.size());
  for (std::size_t i = 0; i < csv.size(); ++i) EXPECT_LT((ply.mesh.p_W[i] - csv[i]).norm(), 1e-6) << i;
  ASSERT_TRUE(ply.origin.has_value());
  EXPECT_DOUBLE_EQ(ply.origin->lat_deg, run_json()["origin"]["lat_deg"].get<double>());
}

TEST(Export, TracksAndLandmarksOfATinyTwinRunLandWhereTheRunPutThem) {
  fs::remove_all(base());
  const auto sim = test::run_process({test::bin("twinslam"), "sim", "--scenario", "tiny", "--out",
                                      (base() / "tiny").string(), "--features", "--quiet"},
                                     {}, std::chrono::seconds(180));
  ASSERT_EQ(sim.exit_code, 0) << sim.out << sim.err;
  const auto run = test::run_process({test::bin("twinslam"), "run", (base() / "tiny").string(), "--mode", "vio-twin",
                                      "--features", "--no-progress", "--out", (base() / "run").string(), "--domain",
                                      std::to_string(test::test_domain())},
                                     {}, std::chrono::seconds(180));
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  check_geojson();
  check_kml();
  check_ply();
  fs::remove_all(base());
}

// Refusals need no pipeline: a run folder as a run without a world alignment (mode vio) leaves it, written here.
TEST(Export, RunsThatCannotBePlacedOnEarthAreRefusedWithTheFile) {
  const fs::path local = base() / "local";
  fs::remove_all(base());
  fs::create_directories(local);
  std::ofstream(local / "trajectory.tum") << "1.0 0 0 0 0 0 0 1\n2.0 1 0 0 0 0 0 1\n";
  nlohmann::json j{{"mode", "vio"}, {"aligned_from_stamp_ns", nullptr},
                   {"origin", {{"lat_deg", 47.3769}, {"lon_deg", 8.5417}, {"alt_m", 408.0}}}};
  std::ofstream(local / "run.json") << j.dump();
  auto r = export_run(local, {"--geojson"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("run.json: the run never aligned to W (mode vio)"), std::string::npos) << r.err;
  r = export_run(local, {"--ply"});  // and it recorded no landmarks in W
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("landmarks.csv: missing"), std::string::npos) << r.err;
  j.erase("origin");  // and without an origin (a dataset without dataset.yaml)
  j["aligned_from_stamp_ns"] = 1000000000;
  std::ofstream(local / "run.json") << j.dump();
  r = export_run(local, {"--kml"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("run.json: no origin of W"), std::string::npos) << r.err;
  std::ofstream(local / "run.json") << "{\"mode\": ";
  r = export_run(local, {"--kml"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("run.json: malformed JSON"), std::string::npos) << r.err;
  r = export_run(base() / "nowhere", {"--kml"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("run.json: missing"), std::string::npos) << r.err;
  r = export_run(local, {});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("at least one of --geojson, --kml, --ply"), std::string::npos) << r.err;
  fs::remove_all(base());
}

}  // namespace

// Real city models as the simulated world (issue 13, item 5): the Delft CityJSON excerpt loads into a City with one
// building per Building object at the file's heights, placed at its own centre when the scenario gives no origin; its
// twin loses exactly the missing building; a loops flight around the tallest building keeps clear of the world; a
// waypoint flight through a building and a missing or malformed city.path are refused with one line naming the key
// and the file. Plus OSM (a building per way) and mesh (buildings from connected components) cities, and the example
// scenario file.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "twinslam/core/error.hpp"
#include "twinslam/sim/flight_clearance.hpp"
#include "twinslam/sim/scenario_io.hpp"
#include "twinslam/sim/world/real_city.hpp"
#include "twinslam/sim/world/twin.hpp"

namespace twinslam::sim {
namespace {

const std::string kDelft = std::string(TWINSLAM_SHARED_DIR) + "/data/cityjson/delft.json";

// The Delft scenario the tests fly: loops above the low roofs and the trees around the tallest building.
Scenario delft_scenario() {
  Scenario s;
  s.name = "delft-test";
  s.city.source = "cityjson";
  s.city.path = kDelft;
  s.trajectory.duration_s = 120;
  s.trajectory.speed_mps = 2.0;
  s.trajectory.altitude_m = {20, 24};
  s.trajectory.loops = 1;
  return s;
}

// The Delft world in the W of its own centre (what `twinslam sim` does without `origin:`).
const City& delft() {
  static const City city = [] {
    Scenario s = delft_scenario();
    s.origin = real_city_origin(s);
    s.origin_given = true;
    return build_real_city(s);
  }();
  return city;
}

// Height (top - bottom) [m] of every Building object of the file, straight from its vertices.
std::map<std::string, double> file_building_heights(const std::string& path) {
  std::ifstream in(path);
  const nlohmann::json doc = nlohmann::json::parse(in);
  const auto& vertices = doc["vertices"];
  const double scale = doc["transform"]["scale"][2].get<double>();
  std::map<std::string, double> heights;
  for (const auto& [id, object] : doc["CityObjects"].items()) {
    if (object["type"] != "Building") continue;
    double lo = 1e300, hi = -1e300;
    std::vector<const nlohmann::json*> stack{&object["geometry"]};
    while (!stack.empty()) {  // every integer in the nested boundaries is a vertex index
      const nlohmann::json* j = stack.back();
      stack.pop_back();
      if (j->is_number_integer()) {
        const double z = vertices[j->get<std::size_t>()][2].get<double>() * scale;
        lo = std::min(lo, z), hi = std::max(hi, z);
      } else if (j->is_array()) {
        for (const auto& x : *j) stack.push_back(&x);
      } else if (j->is_object() && j->contains("boundaries")) {
        stack.push_back(&(*j)["boundaries"]);
      }
    }
    heights[id] = hi - lo;
  }
  return heights;
}

TEST(SimRealCity, DelftLoadsOneBuildingPerObjectAtItsHeightAroundItsOwnCentre) {
  Scenario s = delft_scenario();
  const Origin origin = real_city_origin(s);
  EXPECT_NEAR(origin.lat_deg, 52.012, 0.005);  // Delft
  EXPECT_NEAR(origin.lon_deg, 4.366, 0.005);
  EXPECT_NEAR(origin.alt_m, 43.5, 1.0);  // the ground is about NAP 0, 43.3 m above the WGS84 ellipsoid there

  const City& city = delft();
  const std::map<std::string, double> heights = file_building_heights(kDelft);
  ASSERT_EQ(heights.size(), 160u);
  ASSERT_EQ(city.buildings.size(), heights.size());
  for (const Building& b : city.buildings) {
    ASSERT_TRUE(heights.count(b.name)) << b.name;
    EXPECT_NEAR(b.top_m, heights.at(b.name), 0.02) << b.name;  // a few mm of map curvature at most
    EXPECT_EQ(&b - city.buildings.data(), b.id);
  }
  // The origin is the model's horizontal centre at the median building's ground.
  EXPECT_NEAR(city.hints.ground_z_m, 0.0, 0.01);
  EXPECT_NEAR(0.5 * (city.hints.extent_W[0] + city.hints.extent_W[2]), 0.0, 0.5);
  EXPECT_NEAR(0.5 * (city.hints.extent_W[1] + city.hints.extent_W[3]), 0.0, 0.5);
  // The file's geographicalExtent is 524.4 m x 327.6 m along the RD grid, which is turned by about 1 deg from
  // true north there.
  EXPECT_NEAR(city.hints.extent_W[2] - city.hints.extent_W[0], 524.4, 5.0);
  EXPECT_NEAR(city.hints.extent_W[3] - city.hints.extent_W[1], 327.6, 5.0);
  // The tallest building is the hints' loops centre; every building has triangles and details.
  const Building& tall = city.buildings[static_cast<std::size_t>(city.tallest_id)];
  EXPECT_NEAR(tall.top_m, 8.3, 0.2);
  std::set<int> with_facade, with_detail;
  for (std::size_t i = 0; i < city.mesh.num_triangles(); ++i) {
    if (city.mesh.kind[i] == SurfaceKind::kFacade) with_facade.insert(city.mesh.building_id[i]);
    if (city.mesh.kind[i] == SurfaceKind::kDetail) with_detail.insert(city.mesh.building_id[i]);
  }
  EXPECT_EQ(with_facade.count(kNoBuilding) + 160u, with_facade.size());
  int storeys = 0;  // floor bands at 3 m on every building whose walls reach 0.5 m above that line
  for (const Building& b : city.buildings)
    if (b.base_z_m + b.top_m > 3.6) {
      ++storeys;
      EXPECT_TRUE(with_detail.count(b.id)) << b.name;
    }
  EXPECT_GT(storeys, 30);
  EXPECT_GT(city.empty_lots_W.size(), 0u);
}

TEST(SimRealCity, TwinOfDelftLacksExactlyTheMissingBuilding) {
  TwinConfig config;
  config.missing_buildings = 1;
  const Twin twin = derive_twin(delft(), config, 5);
  ASSERT_EQ(twin.missing_building_ids.size(), 1u);
  const int gone = twin.missing_building_ids[0];
  EXPECT_NE(gone, delft().tallest_id);
  const std::set<int> in_world(delft().mesh.building_id.begin(), delft().mesh.building_id.end());
  const std::set<int> in_twin(twin.mesh.building_id.begin(), twin.mesh.building_id.end());
  EXPECT_TRUE(in_world.count(gone));
  std::set<int> expected = in_world;
  expected.erase(gone);
  EXPECT_EQ(in_twin, expected);
  for (SurfaceKind k : twin.mesh.kind) ASSERT_NE(k, SurfaceKind::kDetail);
}

TEST(SimRealCity, LoopsAroundTheTallestDelftBuildingKeepClearOfTheWorld) {
  const Scenario s = delft_scenario();
  const City& city = delft();
  const FlightTrajectory flight = make_flight_trajectory(s, city.hints);
  const FlightClearance c = measure_flight_clearance(city, flight);
  EXPECT_GE(c.min_distance_m, 3.0) << "at t = " << c.t_s << " s near building " << c.building;
  // ... and it does circle that building.
  const LoopsGeometry g = loops_geometry(s, city.hints);
  for (double t = 5; t < flight.duration() - 5; t += 5) {
    const Eigen::Vector3d p = flight.at(t).p_W;
    EXPECT_NEAR((p.head<2>() - city.hints.tall_building_center_W).norm(), g.radius_m, 2.0) << t;
  }
  EXPECT_NO_THROW(require_flight_clearance(s, city, flight));
}

TEST(SimRealCity, WaypointsThroughABuildingAreRefusedNamingTheKey) {
  Scenario s = delft_scenario();
  const City& city = delft();
  const Building& b = city.buildings[static_cast<std::size_t>(city.tallest_id)];
  const Eigen::Vector2d c = city.hints.tall_building_center_W;
  s.trajectory.type = "waypoints";
  s.trajectory.duration_s = 60;
  const double z = b.base_z_m + 0.5 * b.top_m;
  s.trajectory.waypoints_W = {Eigen::Vector3d(c.x() - 40, c.y(), z), Eigen::Vector3d(c.x() + 40, c.y(), z)};
  try {
    require_flight_clearance(s, city, make_flight_trajectory(s, city.hints));
    ADD_FAILURE() << "a flight through building " << b.name << " was accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("delft-test: trajectory.waypoints: the flight passes 0.", 0), 0u) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
  // The same line high above every roof and tree is fine.
  for (Eigen::Vector3d& w : s.trajectory.waypoints_W) w.z() = 25;
  EXPECT_NO_THROW(require_flight_clearance(s, city, make_flight_trajectory(s, city.hints)));
}

// Expects an InputError of one line that contains every one of `parts`.
void expect_refused(const Scenario& s, const std::vector<std::string>& parts) {
  try {
    build_real_city(s);
    ADD_FAILURE() << "accepted " << *s.city.path;
  } catch (const InputError& e) {
    const std::string what = e.what();
    for (const std::string& p : parts) EXPECT_NE(what.find(p), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

TEST(SimRealCity, MissingOrMalformedCityPathIsOneLineNamingTheFile) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "twinslam_real_city_test";
  std::filesystem::create_directories(dir);
  Scenario s = delft_scenario();
  s.city.path = (dir / "nowhere.json").string();
  expect_refused(s, {"delft-test: city.path: ", "nowhere.json", "no such file"});
  s.city.path = (dir / "broken.json").string();
  std::ofstream(*s.city.path) << "{\"type\": \"CityJSON\", \"vertices\": [";
  expect_refused(s, {"city.path: ", "broken.json", "JSON"});
  s.city.path = std::string(TWINSLAM_SHARED_DIR) + "/data/cityjson/denhaag-lod2-solids.city.json";
  expect_refused(s, {"city.path: ", "denhaag-lod2-solids.city.json", "no CRS", "city.crs"});  // the file names none
  s.city.crs = "EPSG:7415";
  EXPECT_EQ(build_real_city(s).buildings.size(), 4u);  // 4 Buildings, their 8 BuildingParts joined to them
  s.city.source = "mesh";
  s.city.path = kDelft;
  expect_refused(s, {"city.path: ", "delft.json", "city.source mesh reads"});
  std::filesystem::remove_all(dir);
}

TEST(SimRealCity, OsmBuildingsAreOneBuildingPerWay) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "twinslam_real_city_osm";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "three.osm").string();
  {
    std::ofstream osm(path);
    osm.precision(10);
    osm << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<osm version=\"0.6\" generator=\"test\">\n";
    const double lat0 = 47.3769, lon0 = 8.5417, dlat = 1 / 111195.0, dlon = dlat / std::cos(lat0 * M_PI / 180);
    int node = 1;
    for (int b = 0; b < 3; ++b)  // three 20 m x 15 m blocks 40 m apart
      for (const auto& [e, n] : std::vector<std::pair<double, double>>{{0, 0}, {20, 0}, {20, 15}, {0, 15}})
        osm << "  <node id=\"" << node++ << "\" version=\"1\" lat=\"" << lat0 + n * dlat << "\" lon=\""
            << lon0 + (e + 40 * b) * dlon << "\"/>\n";
    for (int b = 0; b < 3; ++b) {
      osm << "  <way id=\"" << 100 + b << "\" version=\"1\">\n";
      for (int k : {1, 2, 3, 4, 1}) osm << "    <nd ref=\"" << 4 * b + k << "\"/>\n";
      osm << "    <tag k=\"building\" v=\"yes\"/>\n    <tag k=\"height\" v=\"" << 9 + 6 * b << "\"/>\n  </way>\n";
    }
    osm << "</osm>\n";
  }
  Scenario s;
  s.name = "osm-test";
  s.city.source = "osm";
  s.city.path = path;
  s.trajectory.altitude_m = {2, 12};
  s.origin_given = true;  // the default origin: the blocks are 0-100 m east of it
  const City city = build_real_city(s);
  ASSERT_EQ(city.buildings.size(), 3u);
  for (int b = 0; b < 3; ++b) {
    EXPECT_EQ(city.buildings[b].name, "osm way " + std::to_string(100 + b));
    EXPECT_NEAR(city.buildings[b].top_m, 9 + 6 * b, 1e-6);
    EXPECT_NEAR(city.buildings[b].rects_W[0][0], 40 * b, 0.005 * 40 * b + 0.01);  // the test's spherical degrees
  }
  EXPECT_EQ(city.tallest_id, 2);
  // Around the 21 m block, flying at 2-12 m, the ring is bounded by the neighbour's east wall (plus its 0.15 m floor
  // bands) 30 m west of the centre.
  const Eigen::Vector4d tall = city.buildings[2].rects_W[0], neighbour = city.buildings[1].rects_W[0];
  EXPECT_NEAR(city.hints.tall_building_radius_m, 0.5 * std::hypot(tall[2] - tall[0], tall[3] - tall[1]), 1e-3);
  EXPECT_NEAR(city.hints.clear_radius_m, 0.5 * (tall[0] + tall[2]) - neighbour[2] - 0.15, 1e-3);
  std::filesystem::remove_all(dir);
}

// An OBJ box [lo, hi] as 12 triangles (its own 8 vertices), appended to `obj`; `next` is the next vertex number.
void obj_box(std::ostream& obj, int* next, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  for (int k = 0; k < 8; ++k)
    obj << "v " << (k & 1 ? hi : lo).x() << ' ' << (k & 2 ? hi : lo).y() << ' ' << (k & 4 ? hi : lo).z() << "\n";
  const int faces[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
  for (const auto& f : faces)
    obj << "f " << *next + f[0] << ' ' << *next + f[1] << ' ' << *next + f[2] << "\nf " << *next + f[0] << ' '
        << *next + f[2] << ' ' << *next + f[3] << "\n";
  *next += 8;
}

TEST(SimRealCity, MeshComponentsOverlappingInPlanAreOneBuildingAndFlatOnesOutsideAreGround) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "twinslam_real_city_mesh";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "blocks.obj").string();
  {
    std::ofstream obj(path);
    int next = 1;
    obj_box(obj, &next, {0, 0, 0}, {10, 10, 12});        // building A
    obj_box(obj, &next, {4, 4, 13}, {5, 5, 14.5});       // a mast above A, not touching it: part of A
    obj_box(obj, &next, {2, 2, 12.5}, {8, 8, 12.6});     // a flat canopy over A's roof: part of A
    obj_box(obj, &next, {30, 0, 0}, {40, 8, 6});         // building B
    obj_box(obj, &next, {-20, -20, -0.2}, {60, 30, -0.1});  // a ground slab around both: terrain
  }
  Scenario s;
  s.name = "mesh-test";
  s.city.source = "mesh";
  s.city.path = path;
  s.trajectory.altitude_m = {16, 20};
  s.origin_given = true;  // the OBJ is in W of the (default) origin
  const City city = build_real_city(s);
  ASSERT_EQ(city.buildings.size(), 2u);
  EXPECT_EQ(city.tallest_id, 0);
  EXPECT_NEAR(city.buildings[0].top_m, 14.5, 1e-9);
  EXPECT_NEAR(city.buildings[1].top_m, 6.0, 1e-9);
  EXPECT_NEAR(city.hints.tall_building_center_W.x(), 5.0, 1e-9);
  std::map<int, int> roofs_at_canopy;  // building -> triangles at the canopy's top, 12.6 m
  int ground_slab = 0;
  for (std::size_t i = 0; i < city.mesh.num_triangles(); ++i) {
    const double z = city.mesh.p_W[city.mesh.triangles[i][0]].z();
    if (city.mesh.kind[i] == SurfaceKind::kRoof && std::abs(z - 12.6) < 1e-9)
      ++roofs_at_canopy[city.mesh.building_id[i]];
    if (city.mesh.kind[i] == SurfaceKind::kGround && std::abs(z + 0.1) < 1e-9) ++ground_slab;
  }
  EXPECT_EQ(roofs_at_canopy[0], 2);
  EXPECT_EQ(roofs_at_canopy.size(), 1u);
  EXPECT_GE(ground_slab, 2);  // the slab's top is ground; its sides are only 0.1 m high, also ground
  std::filesystem::remove_all(dir);
}

TEST(SimRealCity, ExampleScenarioFindsItsCityAndLeavesTheOriginToTheModel) {
  const Scenario s = load_scenario(std::string(TWINSLAM_SOURCE_DIR) + "/deploy/scenarios/delft-loops.yaml");
  EXPECT_EQ(s.city.source, "cityjson");
  ASSERT_TRUE(s.city.path.has_value());
  EXPECT_TRUE(std::filesystem::path(*s.city.path).is_absolute()) << *s.city.path;  // relative to the file's folder
  EXPECT_TRUE(std::filesystem::equivalent(*s.city.path, kDelft)) << *s.city.path;
  EXPECT_FALSE(s.origin_given);
  // The echo in dataset.yaml names the origin, so it reads back as given.
  EXPECT_TRUE(parse_scenario_yaml(scenario_to_yaml(s), "echo.yaml").origin_given);
}

}  // namespace
}  // namespace twinslam::sim

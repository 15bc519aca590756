#pragma once
// A procedural city's digital twin as a tiled store, and the scenario's ground-truth flight: what the tiles service
// serves in the acceptance tests and the benchmark. No rendering.
#include <filesystem>
#include <string>

#include "twinslam/sim/flight_trajectory.hpp"
#include "twinslam/sim/scenario_io.hpp"
#include "twinslam/sim/world/city.hpp"
#include "twinslam/sim/world/twin.hpp"
#include "twinslam/twin/store.hpp"

namespace twinslam::tiles::test {

struct CityTwin {
  sim::Scenario scenario;
  sim::FlightTrajectory trajectory;
  twin::TwinIndex index;
  std::string twin_dir;
};

// Built-in scenario `name` with the city's side set to size_m (0: the scenario's own), its twin written as a store to
// `twin_dir` with `point_spacing_m` (coarser than the default keeps tests fast; the tile grid does not depend on it).
inline CityTwin make_city_twin(const std::string& name, double size_m, const std::filesystem::path& twin_dir,
                               double point_spacing_m = 2.0) {
  sim::Scenario scenario = sim::builtin_scenario(name);
  if (size_m > 0) scenario.city.size_m = size_m;
  const sim::City city = sim::build_city(scenario.city, scenario.seed);
  const sim::Twin twin = sim::derive_twin(city, scenario.twin, scenario.seed);
  CityTwin c{scenario, sim::make_flight_trajectory(scenario, city.hints), {}, twin_dir.string()};
  twin::Mesh mesh_W;
  mesh_W.p_W = twin.mesh.p_W;
  mesh_W.triangles = twin.mesh.triangles;
  twin::StoreConfig store;
  store.point_spacing_m = point_spacing_m;
  const auto& o = c.scenario.origin;
  c.index = twin::build_twin_store(mesh_W, {o.lat_deg, o.lon_deg, o.alt_m}, store, c.twin_dir);
  return c;
}

}  // namespace twinslam::tiles::test

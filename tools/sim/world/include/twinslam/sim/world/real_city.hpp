#pragma once
// A real city model as the simulated world (issue 13, item 5): `city.source: cityjson | osm | 3dtiles | mesh` with
// `city.path` (and `city.crs` when the file does not say) read by the twin loaders (common/twin), placed in W = ENU at
// the scenario origin, and turned into the same `City` the procedural generator makes, so the twin derivation,
// renderer, feature tracks, ray-traced GNSS and flight planning work unchanged:
// - per-building identity from the file: CityJSON Building objects (their BuildingParts and installations joined to
//   them), OSM building ways and relations, mesh / 3D Tiles connected components (welded at 1 cm; a flat component is
//   terrain). Other CityJSON objects are terrain (Road, LandUse, PlantCover, WaterBody, TINRelief, ...: kGround) or
//   structures (Bridge, GenericCityObject, CityFurniture, ...: facades and roofs of no building, kept by every twin);
// - kinds by slope: walls (|n_z| < 0.3) kFacade, the rest kRoof; a building's floor (near-horizontal at its base,
//   never seen from outside) is dropped;
// - a ground plane of 20 m patches under the model and `ground_margin_m` around it, just below its lowest terrain (or
//   at its buildings' ground when it has none), so the camera never looks into a void and the twin perturbs the ground
//   patch by patch like the procedural one;
// - the procedural city's details on every building wall whatever its direction (real_city_details.cpp): floor bands
//   at the 3 m storeys the facade texture draws its windows on, balconies, rooftop boxes on flat roofs;
// - SceneHints from the geometry (real_city_hints.cpp) and empty lots for the twin's added buildings.
// Without `origin:` in the scenario (Scenario::origin_given) W is first placed at the model's centre at ground level
// (real_city_origin), so one scenario fits any file.
#include <cstdint>

#include "twinslam/sim/scenario.hpp"
#include "twinslam/sim/world/city.hpp"

namespace twinslam::sim {

struct RealCityConfig {
  double ground_margin_m = 30;   // ground plane beyond the model's extent on every side [m]
  double ground_patch_m = 20;    // side of a ground patch (the twin offsets each by its own noise) [m]
  double floor_height_m = 3;     // storey height of floor bands and balconies (the texture's window grid) [m]
  double weld_m = 0.01;          // mesh / 3D Tiles: vertices closer than this join components [m]
  double lot_size_m = 24;        // side of an empty lot (twin.added_buildings stand in them) [m]
  double lot_clearance_m = 3;    // an empty lot keeps this far from buildings, structures, raised terrain [m]
};

// The world of a real-city scenario (scenario.city.source != "procedural"), in the W of scenario.origin. The loops
// clear radius (SceneHints::clear_radius_m) counts what reaches within 3 m of the flight's lowest altitude
// (ground + trajectory.altitude_m[0]), so a ring above low neighbours is free. Throws InputError "city.path: FILE:
// reason" for a missing, unreadable or malformed file, "city.source" for a file of another kind, "city.path" when it
// holds no buildings.
City build_real_city(const Scenario& scenario, const RealCityConfig& config = {});

// The origin for a real city: scenario.origin when the scenario gives one (origin_given), else the WGS84 point under
// the model's horizontal centre at its ground level (the file's CRS through PROJ). Loads the file.
Origin real_city_origin(const Scenario& scenario, const RealCityConfig& config = {});

// The world of any scenario: build_city for `procedural`, build_real_city otherwise.
City build_world_city(const Scenario& scenario);

}  // namespace twinslam::sim

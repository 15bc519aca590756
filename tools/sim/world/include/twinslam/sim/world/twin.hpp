#pragma once
// The digital twin derived from the world (issue 3, item 2) the way real twins differ from reality:
// - details removed (every kDetail triangle: floor bands, balconies, rooftop boxes, trees, cars);
// - surfaces perturbed: every planar face (a facade wall, a roof part, a 20 m ground patch) moves along its normal by
//   its own N(0, noise_m^2) offset — a modelling/survey error per surface, RMS = noise_m;
// - `missing_buildings`: N buildings (never the tallest) absent from the twin only (demolished since the survey);
// - `added_buildings`: N boxes in empty lots that exist only in the twin (planned or since-built);
// - `offset_m`: the whole twin translated (a georeferencing error);
// - `shifted_buildings`: N buildings (never the tallest, never a missing one) moved horizontally by offset_m in a
//   seeded random direction each (a building mapped in the wrong place); drawn from their own random stream, so twins
//   without shifted buildings are unchanged by them.
// Missing, shifted and added buildings are drawn first among TwinCandidates (what the flight passes), then among
// the others; with no candidates the draw is over all buildings (lots).
#include <cstdint>
#include <vector>

#include "twinslam/sim/scenario.hpp"
#include "twinslam/sim/world/city.hpp"

namespace twinslam::sim {

struct Twin {
  TriMesh mesh;                          // [m, W], translated by offset_m
  std::vector<int> missing_building_ids; // world buildings absent from the twin
  std::vector<int> added_building_ids;   // twin-only buildings (ids continue after the world's)
  std::vector<std::vector<Eigen::Vector2d>> added_outlines_W;  // their footprints [m, E N], counter-clockwise
  std::vector<int> shifted_building_ids; // world buildings misplaced in the twin, increasing
  std::vector<Eigen::Vector3d> shifted_building_offsets_W;  // their shift [m, W] (z = 0), same order
};

// What the flight passes (simulate.cpp): each kind of change is drawn first among these, then among the rest.
struct TwinCandidates {
  std::vector<int> missing_ids;  // building ids, for missing_buildings
  std::vector<int> shifted_ids;  // building ids, for shifted_buildings
  std::vector<int> lot_ids;      // indices into City::empty_lots_W, for added_buildings
};

// Throws InputError naming the twin.* key when a value is out of range (negative or non-finite noise, more missing
// buildings than there are besides the tallest, more added buildings than empty lots, non-finite offset, more
// shifted buildings than remain besides the tallest and the missing ones, a shift outside [0, 20] m).
Twin derive_twin(const City& world, const TwinConfig& config, std::uint64_t seed,
                 const TwinCandidates& candidates = {});

}  // namespace twinslam::sim

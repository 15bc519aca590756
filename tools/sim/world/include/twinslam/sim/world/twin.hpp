#pragma once
// The digital twin derived from the world (issue 3, item 2) the way real twins differ from reality:
// - details removed (every kDetail triangle: floor bands, balconies, rooftop boxes, trees, cars);
// - surfaces perturbed: every planar face (a facade wall, a roof part, a 20 m ground patch) moves along its normal by
//   its own N(0, noise_m^2) offset — a modelling/survey error per surface, RMS = noise_m;
// - `missing_buildings`: N buildings (never the tallest) absent from the twin only (demolished since the survey);
// - `added_buildings`: N boxes in empty lots that exist only in the twin (planned or since-built);
// - `offset_m`: the whole twin translated (a georeferencing error).
#include <cstdint>
#include <vector>

#include "twinslam/sim/scenario.hpp"
#include "twinslam/sim/world/city.hpp"

namespace twinslam::sim {

struct Twin {
  TriMesh mesh;                          // [m, W], translated by offset_m
  std::vector<int> missing_building_ids; // world buildings absent from the twin
  std::vector<int> added_building_ids;   // twin-only buildings (ids continue after the world's)
};

// Throws InputError naming the twin.* key when a value is out of range (negative or non-finite noise, more missing
// buildings than there are besides the tallest, more added buildings than empty lots, non-finite offset).
Twin derive_twin(const City& world, const TwinConfig& config, std::uint64_t seed);

}  // namespace twinslam::sim

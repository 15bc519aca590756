#pragma once
// Synthetic trajectories with known geometry for the evaluation tests.
#include <cstdint>
#include <random>

#include "twinslam/eval/alignment.hpp"
#include "twinslam/trajectory/trajectory.hpp"

namespace twinslam::test {

// A rising helix (radius 20 m, 0.1 m/s climb) with a body that yaws along the path and rolls/pitches a few degrees,
// so every rotation axis and all three position axes are excited. Poses every dt_ns from t0_ns.
Trajectory helix(std::size_t n, std::int64_t dt_ns = 50'000'000, std::int64_t t0_ns = 1'000'000'000'000);

// A straight path along +x at speed v [m/s], identity orientation.
Trajectory straight_line(std::size_t n, double v_mps, std::int64_t dt_ns = 50'000'000, std::int64_t t0_ns = 0);

// Every pose mapped by S (positions scaled, rotations composed): T' = S * T.
Trajectory transformed(const Trajectory& t, const eval::Similarity& S);

// The inverse similarity, so that transformed(transformed(t, inverse(S)), S) == t.
eval::Similarity inverse(const eval::Similarity& S);

// A deterministic rotation from Euler angles (z-y-x) [rad].
Eigen::Matrix3d rotation_zyx(double yaw, double pitch, double roll);

}  // namespace twinslam::test

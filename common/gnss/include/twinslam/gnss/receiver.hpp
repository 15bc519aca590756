#pragma once
// Single-point positioning: the receiver's position and one clock offset per satellite system (inter-system biases)
// by weighted least squares on one epoch's pseudoranges, iterated Gauss-Newton from a given initial guess, with
// fault detection and exclusion (fde.hpp) and the solution's covariance.
//
// Model (receiver position p, clock offset b_s of system s, both in metres):
//   rho_i = | R3(omega_e tau_i) x_i - p | + b_s(i) + e_i,   e_i ~ N(0, sigma_i^2),   tau_i = |x_i - p| / c
// with x_i the satellite at transmission time; R3 turns it into the ECEF frame of the reception time (the Earth
// rotated during the ~70 ms of flight: up to ~30 m of range). The unknown vector is ordered [p_x p_y p_z b_1 .. b_k]
// with the systems in the order of their first observation in the epoch.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "twinslam/gnss/observation.hpp"
#include "twinslam/gnss/receiver_config.hpp"

namespace twinslam::gnss {

struct Fix {
  bool valid = false;
  std::string reason;                                  // why there is no fix, when !valid
  double t_s = 0;
  Eigen::Vector3d p_ecef = Eigen::Vector3d::Zero();    // [m, ECEF]
  Eigen::Matrix3d cov_ecef = Eigen::Matrix3d::Zero();  // position covariance [m^2, ECEF]
  std::vector<SatSystem> clock_systems;                // order of clock_m
  std::vector<double> clock_m;                         // receiver clock offset per system [m]
  int satellites_used = 0;
  std::vector<int> excluded;                           // indices into the epoch's observations, in exclusion order
  bool residual_test_passed = false;                   // the chi-square test passed after the exclusions
  double residual_rms_m = 0;                           // of the used observations [m]
  int iterations = 0;
};

// Least squares on the observations at `use` (indices into epoch.observations) from `initial_ecef`.
Fix solve_least_squares(const Epoch& epoch, const std::vector<int>& use, const Eigen::Vector3d& initial_ecef,
                        const ReceiverConfig& config);

// The receiver's fix for one epoch: observations above the mask, least squares, then exclusion of the worst satellite
// while the residual test fails (at most config.max_exclusions, and only while one redundant observation remains).
// No fix with fewer observations than unknowns (4 with one system) or when the solution does not converge.
Fix solve_fix(const Epoch& epoch, const Eigen::Vector3d& initial_ecef, const ReceiverConfig& config);

// A receiver over a sequence of epochs: the initial guess of each epoch is the last valid fix, or the Earth's centre
// before the first one (never the truth).
std::vector<Fix> solve_epochs(const std::vector<Epoch>& epochs, const ReceiverConfig& config);

}  // namespace twinslam::gnss

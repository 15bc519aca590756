#pragma once
// One residual term of the sliding window's cost (paper eq. 1): a cost function, an optional robust loss, the
// parameter blocks it acts on, and what it is for. Each solve builds ONE list of terms from the window state
// (window_terms.hpp); the Ceres problem and the marginalizer are both fed from that list, so a new factor type is
// added in one place and its information on a keyframe that leaves the window goes into the prior like any other.
//
// Ownership: terms share ownership of their cost and loss (std::shared_ptr); the Ceres problem is built with
// DO_NOT_TAKE_OWNERSHIP and lives no longer than the list. Parameter blocks are owned by the window state.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <ceres/cost_function.h>
#include <ceres/loss_function.h>

namespace ceres {
class Problem;
}  // namespace ceres

namespace twinslam::estimator {

enum class TermKind {
  kImu,                   // preintegrated IMU factor between consecutive frames
  kZeroVelocity,          // v_L = 0 of a frame at rest
  kInitialPrior,          // prior of the first keyframe from the initialization (defines L's gauge)
  kMarginalizationPrior,  // information of the keyframes that left the window
  kReprojection,          // bearing reprojection of a landmark anchored in another keyframe
  kWorldPrior,            // prior on the world alignment T_WL (from an initial alignment)
  kCameraPrior,           // prior of the online camera-rotation calibration (camera_calibration.hpp)
  kProvider,              // added by a WindowFactorProvider (map registration, GNSS, ...)
};
const char* to_string(TermKind kind);

struct ResidualTerm {
  TermKind kind = TermKind::kProvider;
  std::string purpose;                          // what it is for, e.g. "gnss position @ 1403636580838555648 ns"
  std::shared_ptr<ceres::CostFunction> cost;    // required
  std::shared_ptr<ceres::LossFunction> loss;    // null: plain squared error
  std::vector<double*> blocks;                  // in the cost function's parameter order
  // Reprojection terms only: the landmark (feature id) and the observing frame (WindowFrame::id), for the outlier
  // test after the solve.
  std::int64_t landmark = -1;
  std::int64_t frame = -1;
};

// Convenience for providers: a term from a cost (and loss) they just created.
ResidualTerm make_term(TermKind kind, std::string purpose, std::unique_ptr<ceres::CostFunction> cost,
                       std::unique_ptr<ceres::LossFunction> loss, std::vector<double*> blocks);

// Adds every term to `problem` (created with DO_NOT_TAKE_OWNERSHIP of costs and losses). Throws std::logic_error on a
// term without cost or with a block count that does not match its cost function.
void add_to_problem(const std::vector<ResidualTerm>& terms, ceres::Problem& problem);

// True if the term acts on `block`.
bool touches(const ResidualTerm& term, const double* block);

}  // namespace twinslam::estimator

#pragma once
// One evaluation of an estimate against the ground truth: associate -> align -> ATE, RPE, path length.
#include <cstdint>
#include <string>
#include <vector>

#include "twinslam/eval/alignment.hpp"
#include "twinslam/eval/association.hpp"
#include "twinslam/eval/ate.hpp"
#include "twinslam/eval/rpe.hpp"
#include "twinslam/trajectory/trajectory.hpp"

namespace twinslam::eval {

struct EvalConfig {
  AlignMode align = AlignMode::None;        // the contract's default: twinslam estimates live in W
  std::size_t align_first = 0;              // align on the first N associated pairs; 0 = all
  std::int64_t max_dt_ns = kDefaultMaxDtNs;  // association window
  std::vector<double> rpe_lengths_m{10.0, 50.0, 100.0};
  std::vector<double> rpe_fractions{0.1, 0.2, 0.3, 0.4, 0.5};  // of the ground-truth path length

  // Throws UsageError for a non-positive window, length or fraction.
  void validate() const;
};

struct EvalResult {
  AlignMode align = AlignMode::None;
  std::size_t align_pairs = 0;         // pairs the alignment used
  std::size_t n_gt = 0, n_est = 0;     // poses in the inputs
  std::size_t n = 0;                   // associated pairs
  double length_m = 0.0;               // ground-truth path length over the associated poses [m]
  Similarity S_WL;                     // the alignment applied to the estimate
  std::vector<std::int64_t> stamp_ns;  // per pair: the estimate's stamp [ns]
  std::vector<Eigen::Isometry3d> T_WB_gt, T_WB_est;  // per pair; the estimate after alignment
  AteResult ate;
  std::vector<RpeSegment> rpe;
};

// Throws InputError (naming both sources) when an input is empty or no pose associates.
EvalResult evaluate(const Trajectory& gt, const Trajectory& est, const EvalConfig& config = {});

}  // namespace twinslam::eval

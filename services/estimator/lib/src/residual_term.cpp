#include "twinslam/estimator/residual_term.hpp"

#include <algorithm>
#include <stdexcept>

#include <ceres/cost_function.h>
#include <ceres/loss_function.h>
#include <ceres/problem.h>

namespace twinslam::estimator {

const char* to_string(TermKind kind) {
  switch (kind) {
    case TermKind::kImu: return "imu";
    case TermKind::kZeroVelocity: return "zero_velocity";
    case TermKind::kInitialPrior: return "initial_prior";
    case TermKind::kMarginalizationPrior: return "marginalization_prior";
    case TermKind::kReprojection: return "reprojection";
    case TermKind::kWorldPrior: return "world_prior";
    case TermKind::kCameraPrior: return "camera_prior";
    case TermKind::kProvider: return "provider";
  }
  return "unknown";
}

ResidualTerm make_term(TermKind kind, std::string purpose, std::unique_ptr<ceres::CostFunction> cost,
                       std::unique_ptr<ceres::LossFunction> loss, std::vector<double*> blocks) {
  ResidualTerm t;
  t.kind = kind;
  t.purpose = std::move(purpose);
  t.cost = std::move(cost);
  t.loss = std::move(loss);
  t.blocks = std::move(blocks);
  return t;
}

void add_to_problem(const std::vector<ResidualTerm>& terms, ceres::Problem& problem) {
  for (const auto& t : terms) {
    if (!t.cost || t.blocks.size() != t.cost->parameter_block_sizes().size()) {
      throw std::logic_error(std::string("residual term '") + t.purpose + "' (" + to_string(t.kind) +
                             "): no cost function or wrong number of parameter blocks");
    }
    problem.AddResidualBlock(t.cost.get(), t.loss.get(), t.blocks);
  }
}

bool touches(const ResidualTerm& term, const double* block) {
  return std::find(term.blocks.begin(), term.blocks.end(), block) != term.blocks.end();
}

}  // namespace twinslam::estimator

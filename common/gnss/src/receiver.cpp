#include "twinslam/gnss/receiver.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>

#include "twinslam/gnss/constants.hpp"
#include "twinslam/gnss/fde.hpp"
#include "twinslam/gnss/orbit.hpp"

namespace twinslam::gnss {
namespace {

std::vector<SatSystem> systems_of(const Epoch& epoch, const std::vector<int>& use) {
  std::vector<SatSystem> out;
  for (int i : use) {
    const SatSystem s = epoch.observations[static_cast<std::size_t>(i)].system;
    if (std::find(out.begin(), out.end(), s) == out.end()) out.push_back(s);
  }
  return out;
}

struct Linearized {
  Eigen::MatrixXd H;      // d(predicted range)/d(unknowns), n x (3 + systems)
  Eigen::VectorXd v;      // measured - predicted [m]
  Eigen::VectorXd sigma;  // [m]
};

// The model of receiver.hpp at the unknowns x = [p, b_1..b_k].
Linearized linearize(const Epoch& epoch, const std::vector<int>& use, const Eigen::VectorXd& x,
                     const std::vector<SatSystem>& systems, const ReceiverConfig& config) {
  const auto n = static_cast<Eigen::Index>(use.size());
  Linearized L{Eigen::MatrixXd::Zero(n, x.size()), Eigen::VectorXd(n), Eigen::VectorXd(n)};
  const Eigen::Vector3d p = x.head<3>();
  for (Eigen::Index r = 0; r < n; ++r) {
    const Pseudorange& o = epoch.observations[static_cast<std::size_t>(use[static_cast<std::size_t>(r)])];
    Eigen::Vector3d sat = o.satellite_ecef;
    if (config.earth_rotation) sat = rotate_to_reception(sat, (sat - p).norm() / kSpeedOfLight);
    const Eigen::Vector3d d = sat - p;
    const double range = d.norm();
    const auto k = std::find(systems.begin(), systems.end(), o.system) - systems.begin();
    L.H.block<1, 3>(r, 0) = -d.transpose() / range;  // the Sagnac term's dependence on p is below 1e-6 of this
    L.H(r, 3 + k) = 1;
    L.v[r] = o.range_m - (range + x[3 + k]);
    L.sigma[r] = o.sigma_m * std::pow(10.0, std::max(0.0, config.cn0_reference_dbhz - o.cn0_dbhz) / 20);
  }
  return L;
}

// The unknown vector [p, b_1..b_k] of a fix.
Eigen::VectorXd unknowns_of(const Fix& fix) {
  Eigen::VectorXd x(3 + static_cast<Eigen::Index>(fix.clock_m.size()));
  x.head<3>() = fix.p_ecef;
  for (std::size_t k = 0; k < fix.clock_m.size(); ++k) x[static_cast<Eigen::Index>(3 + k)] = fix.clock_m[k];
  return x;
}

}  // namespace

Fix solve_least_squares(const Epoch& epoch, const std::vector<int>& use, const Eigen::Vector3d& initial_ecef,
                        const ReceiverConfig& config) {
  Fix fix;
  fix.t_s = epoch.t_s;
  fix.clock_systems = systems_of(epoch, use);
  const auto m = static_cast<Eigen::Index>(3 + fix.clock_systems.size());
  if (static_cast<Eigen::Index>(use.size()) < m) {
    fix.reason = std::to_string(use.size()) + " satellites for " + std::to_string(m) + " unknowns";
    return fix;
  }
  Eigen::VectorXd x = Eigen::VectorXd::Zero(m);
  x.head<3>() = initial_ecef;
  Linearized L;
  bool converged = false;
  for (fix.iterations = 1; fix.iterations <= config.max_iterations && !converged; ++fix.iterations) {
    L = linearize(epoch, use, x, fix.clock_systems, config);
    const Eigen::VectorXd w = L.sigma.array().square().inverse().matrix();
    const Eigen::MatrixXd N = L.H.transpose() * w.asDiagonal() * L.H;
    const Eigen::VectorXd dx = N.ldlt().solve(L.H.transpose() * w.asDiagonal() * L.v);
    if (!dx.allFinite()) break;
    x += dx;
    converged = dx.norm() < config.convergence_m;
  }
  --fix.iterations;
  if (!converged) {
    fix.reason = "no convergence in " + std::to_string(config.max_iterations) + " iterations";
    return fix;
  }
  L = linearize(epoch, use, x, fix.clock_systems, config);
  const Eigen::VectorXd w = L.sigma.array().square().inverse().matrix();
  const Eigen::MatrixXd N = L.H.transpose() * w.asDiagonal() * L.H;
  const Eigen::MatrixXd cov = N.ldlt().solve(Eigen::MatrixXd::Identity(m, m));
  if (!cov.allFinite() || L.v.cwiseAbs().maxCoeff() > config.max_residual_m) {
    fix.reason = "degenerate geometry or residuals above " + std::to_string(config.max_residual_m) + " m";
    return fix;
  }
  fix.valid = true;
  fix.p_ecef = x.head<3>();
  fix.cov_ecef = cov.topLeftCorner<3, 3>();
  fix.clock_m.assign(x.data() + 3, x.data() + m);
  fix.satellites_used = static_cast<int>(use.size());
  fix.residual_rms_m = std::sqrt(L.v.squaredNorm() / static_cast<double>(L.v.size()));
  const auto dof = static_cast<int>(L.v.size() - m);
  fix.residual_test_passed =
      dof == 0 || L.v.cwiseQuotient(L.sigma).squaredNorm() <= chi_square_quantile(dof, config.false_alarm_probability);
  return fix;
}

Fix solve_fix(const Epoch& epoch, const Eigen::Vector3d& initial_ecef, const ReceiverConfig& config) {
  std::vector<int> use;
  for (std::size_t i = 0; i < epoch.observations.size(); ++i) {
    if (epoch.observations[i].elevation_deg >= config.elevation_mask_deg) use.push_back(static_cast<int>(i));
  }
  Fix fix = solve_least_squares(epoch, use, initial_ecef, config);
  std::vector<int> excluded;
  // Exclude while the test fails and a redundant observation would remain to test the result (dof >= 1 after).
  while (fix.valid && !fix.residual_test_passed && static_cast<int>(excluded.size()) < config.max_exclusions &&
         static_cast<int>(use.size()) - 1 > 3 + static_cast<int>(fix.clock_systems.size())) {
    const Linearized L = linearize(epoch, use, unknowns_of(fix), fix.clock_systems, config);
    Eigen::Index worst = 0;
    standardized_residuals(L.H, L.sigma, L.v).cwiseAbs().maxCoeff(&worst);
    excluded.push_back(use[static_cast<std::size_t>(worst)]);
    use.erase(use.begin() + worst);
    const Fix next = solve_least_squares(epoch, use, fix.p_ecef, config);
    if (!next.valid) break;  // keep the last valid solution rather than none
    fix = next;
    fix.excluded = excluded;
  }
  return fix;
}

std::vector<Fix> solve_epochs(const std::vector<Epoch>& epochs, const ReceiverConfig& config) {
  std::vector<Fix> out;
  Eigen::Vector3d guess = Eigen::Vector3d::Zero();  // the Earth's centre: Gauss-Newton converges from there
  for (const Epoch& e : epochs) {
    out.push_back(solve_fix(e, guess, config));
    if (out.back().valid) guess = out.back().p_ecef;
  }
  return out;
}

}  // namespace twinslam::gnss

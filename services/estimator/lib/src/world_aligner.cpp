#include "twinslam/estimator/world_aligner.hpp"

#include <cmath>
#include <string>

#include <Eigen/Cholesky>

#include "twinslam/core/error.hpp"

namespace twinslam::estimator {
namespace {

constexpr double kRadToDeg = 57.29577951308232;

// Weighted 2-D Procrustes on the horizontal parts (weights 1 / the mean horizontal variance of each fix): the
// rotation that best maps the centred p_L onto the centred p_W, then the translation of the weighted centroids.
Eigen::Vector4d closed_form(const std::vector<AlignmentPair>& pairs) {
  double sw = 0.0;
  Eigen::Vector3d cL = Eigen::Vector3d::Zero(), cW = Eigen::Vector3d::Zero();
  for (const auto& p : pairs) {
    const double w = 2.0 / (p.cov_W(0, 0) + p.cov_W(1, 1));
    sw += w;
    cL += w * p.p_L;
    cW += w * p.p_W;
  }
  cL /= sw;
  cW /= sw;
  double s_cos = 0.0, s_sin = 0.0;
  for (const auto& p : pairs) {
    const double w = 2.0 / (p.cov_W(0, 0) + p.cov_W(1, 1));
    const Eigen::Vector3d a = p.p_L - cL, b = p.p_W - cW;
    s_cos += w * (a.x() * b.x() + a.y() * b.y());
    s_sin += w * (a.x() * b.y() - a.y() * b.x());
  }
  const double yaw = std::atan2(s_sin, s_cos);
  const Eigen::Vector3d t = cW - Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * cL;
  return {t.x(), t.y(), t.z(), yaw};
}

}  // namespace

void WorldAlignerConfig::validate() const {
  if (!(converged_yaw_sigma_deg > 0.0) || !std::isfinite(converged_yaw_sigma_deg)) {
    throw InputError("world aligner: converged_yaw_sigma_deg must be > 0");
  }
  if (min_pairs < 3) throw InputError("world aligner: min_pairs must be >= 3");
  if (!(min_span_m >= 0.0) || !std::isfinite(min_span_m)) throw InputError("world aligner: min_span_m must be >= 0");
  if (max_pairs < 3) throw InputError("world aligner: max_pairs must be >= 3");
}

WorldAligner::WorldAligner(const WorldAlignerConfig& config) : config_(config) { config_.validate(); }

void WorldAligner::add(const AlignmentPair& pair) {
  const Eigen::LLT<Eigen::Matrix3d> llt(pair.cov_W);
  if (!pair.p_L.allFinite() || !pair.p_W.allFinite() || !pair.cov_W.allFinite() || llt.info() != Eigen::Success ||
      (pair.cov_W - pair.cov_W.transpose()).cwiseAbs().maxCoeff() > 1e-9 * pair.cov_W.norm()) {
    throw InputError("world aligner: a position pair is not finite or its covariance is not positive definite");
  }
  pairs_.push_back(pair);
  if (pairs_.size() > config_.max_pairs) pairs_.erase(pairs_.begin());
}

std::optional<WorldAlignment4Dof> WorldAligner::solve() const {
  if (pairs_.size() < 3) return std::nullopt;
  Eigen::Vector4d x = closed_form(pairs_);
  Eigen::Matrix4d N = Eigen::Matrix4d::Zero();
  // Gauss-Newton on r_n = p_W - Rz(yaw) p_L - t with weights C_n^-1 (a few steps from the closed form).
  for (int it = 0; it < 5; ++it) {
    N.setZero();
    Eigen::Vector4d g = Eigen::Vector4d::Zero();
    const Eigen::Matrix3d Rz = Eigen::AngleAxisd(x[3], Eigen::Vector3d::UnitZ()).toRotationMatrix();
    for (const auto& p : pairs_) {
      const Eigen::Matrix3d Winv = p.cov_W.inverse();
      const Eigen::Vector3d Rp = Rz * p.p_L;
      const Eigen::Vector3d r = p.p_W - Rp - x.head<3>();
      Eigen::Matrix<double, 3, 4> J;  // dr/d[t, yaw]
      J.leftCols<3>() = -Eigen::Matrix3d::Identity();
      J.col(3) = -Eigen::Vector3d(-Rp.y(), Rp.x(), 0.0);
      N += J.transpose() * Winv * J;
      g += J.transpose() * Winv * r;
    }
    const Eigen::Vector4d dx = -N.ldlt().solve(g);
    x += dx;
    if (dx.norm() < 1e-9) break;
  }
  WorldAlignment4Dof out;
  out.T_WL.linear() = Eigen::AngleAxisd(x[3], Eigen::Vector3d::UnitZ()).toRotationMatrix();
  out.T_WL.translation() = x.head<3>();
  out.covariance = N.inverse();
  out.yaw_sigma_deg = std::sqrt(std::max(out.covariance(3, 3), 0.0)) * kRadToDeg;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : pairs_) mean += p.p_L.head<2>();
  mean /= static_cast<double>(pairs_.size());
  for (const auto& p : pairs_) out.span_m = std::max(out.span_m, (p.p_L.head<2>() - mean).norm());
  out.pairs = pairs_.size();
  out.converged = static_cast<int>(pairs_.size()) >= config_.min_pairs && out.span_m >= config_.min_span_m &&
                  out.yaw_sigma_deg <= config_.converged_yaw_sigma_deg;
  return out;
}

}  // namespace twinslam::estimator

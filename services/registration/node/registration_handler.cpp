#include "registration_handler.hpp"

#include <Eigen/Cholesky>

#include <cmath>
#include <cstdio>
#include <optional>

#include <spdlog/spdlog.h>

#include "twinslam/core/error.hpp"
#include "twinslam/dds/convert.hpp"
#include "twinslam/geometry/information_order.hpp"

namespace twinslam::registration {

std::optional<twin::TileKey> parse_tile_key(const std::string& wire_key) {
  const auto slash = wire_key.rfind('/');
  const std::string cell = slash == std::string::npos ? wire_key : wire_key.substr(slash + 1);
  twin::TileKey key;
  char tail = 0;
  if (std::sscanf(cell.c_str(), "%d_%d%c", &key.ix, &key.iy, &tail) != 2) return std::nullopt;
  return key;
}

msg::RegistrationStatus to_msg(RegistrationStatus s) {
  switch (s) {
    case RegistrationStatus::kAccepted: return msg::REG_ACCEPTED;
    case RegistrationStatus::kTooFewPoints: return msg::REG_REJECTED_FEW_POINTS;
    case RegistrationStatus::kNotConverged: return msg::REG_REJECTED_NOT_CONVERGED;
    case RegistrationStatus::kTooFewInliers: return msg::REG_REJECTED_FEW_INLIERS;
    case RegistrationStatus::kFitnessTooLow: return msg::REG_REJECTED_FITNESS;
    case RegistrationStatus::kRmseTooLarge: return msg::REG_REJECTED_RMSE;
    case RegistrationStatus::kDegenerate: return msg::REG_REJECTED_DEGENERATE;
    case RegistrationStatus::kCorrectionTooLarge: return msg::REG_REJECTED_CORRECTION;
  }
  return msg::REG_REJECTED_NOT_CONVERGED;
}

RegistrationHandler::RegistrationHandler(dds::Counters& counters, const RegistrationNodeOptions& options)
    : counters_(counters),
      options_(options),
      twin_(options.tile_size_m, options.window_m, options.max_stored_tiles, options.prefetch_m,
            options.prefetch_per_update, options.keep_m) {}

void RegistrationHandler::on_tile(const msg::MapTile& t) {
  const auto key = parse_tile_key(t.tile_key());
  if (!key) {
    counters_.add("tiles_rejected");
    spdlog::warn("map tile '{}': malformed key", t.tile_key());
    return;
  }
  const Eigen::AlignedBox3d bounds(Eigen::Vector3d(t.bounds_W()[0], t.bounds_W()[1], t.bounds_W()[2]),
                                   Eigen::Vector3d(t.bounds_W()[3], t.bounds_W()[4], t.bounds_W()[5]));
  // The bounds place the tile in vehicles' windows and order its eviction: NaN would make it unplaceable.
  if (!bounds.min().allFinite() || !bounds.max().allFinite() || (bounds.min().array() > bounds.max().array()).any() ||
      bounds.min().cwiseAbs().maxCoeff() > kMaxWorldCoordinate_m || bounds.max().cwiseAbs().maxCoeff() > kMaxWorldCoordinate_m) {
    counters_.add("tiles_rejected");
    spdlog::warn("map tile '{}': bounds not finite, inverted or beyond the world's extent", t.tile_key());
    return;
  }
  twin_.add_tile(*key, bounds, std::vector<std::uint8_t>(t.points_draco().begin(), t.points_draco().end()));
}

namespace {

// Finite, symmetric and positive definite: what register_cloud requires of a prior covariance.
bool usable_covariance(const Matrix6d& S) {
  return S.allFinite() && (S - S.transpose()).norm() <= 1e-9 * std::max(1.0, S.norm()) &&
         Eigen::LLT<Matrix6d>(S).info() == Eigen::Success;
}

}  // namespace

void RegistrationHandler::inject_fault(const msg::LocalMap& m, RegistrationResult& r) {
  const CorrectionFault& fault = options_.registration.fault_correction_offset;
  const auto stamp = static_cast<std::int64_t>(m.keyframe_stamp_ns());
  if (r.status != RegistrationStatus::kAccepted || !fault.contains(stamp, first_stamp_ns_.at(m.vehicle_id()))) return;
  r.correction_W.pretranslate(Eigen::Vector3d(fault.east_m, 0.0, 0.0));
  r.reason = "accepted; fault injected: correction moved " + std::to_string(fault.east_m) + " m east";
  counters_.add("fault_correction_offset");
}

msg::Registration RegistrationHandler::on_local_map(const msg::LocalMap& m) {
  first_stamp_ns_.try_emplace(m.vehicle_id(), static_cast<std::int64_t>(m.keyframe_stamp_ns()));
  msg::Registration out;
  out.vehicle_id(m.vehicle_id());
  out.keyframe_stamp_ns(m.keyframe_stamp_ns());
  out.seq(seq_++);
  try {
    register_map(m, out);
  } catch (const InputError& e) {
    out.status(msg::REG_REJECTED_FEW_POINTS);
    out.reason(std::string("bad input: ") + e.what());
  }
  counters_.add(out.status() == msg::REG_ACCEPTED ? "accepted" : "rejected");
  counters_.add("registrations_out");
  return out;
}

void RegistrationHandler::register_map(const msg::LocalMap& m, msg::Registration& out) {
  if (m.landmarks().size() > options_.max_landmarks) {
    throw InputError("LocalMap has " + std::to_string(m.landmarks().size()) + " landmarks > max_landmarks " +
                     std::to_string(options_.max_landmarks));
  }
  SourceInput source;
  source.T_LB = dds::from_msg(m.T_LB());
  source.T_WL = dds::from_msg(m.T_WL());
  source.landmarks.reserve(m.landmarks().size());
  for (const auto& l : m.landmarks()) {
    const auto& c = l.cov_L();  // upper triangle xx xy xz yy yz zz [m^2]
    Eigen::Matrix3d cov;
    cov << c[0], c[1], c[2], c[1], c[3], c[4], c[2], c[4], c[5];
    source.landmarks.push_back({dds::from_msg(l.p_L()), l.quality(), cov});
  }
  const Eigen::Vector3d p_WB = (source.T_WL * source.T_LB).translation();
  // A NaN pose would become this vehicle's position in the twin window (and its tile eviction distances).
  if (!(source.T_WL * source.T_LB).matrix().allFinite()) throw InputError("LocalMap keyframe pose is not finite");
  const WindowedTwinStats w = twin_.update(m.vehicle_id(), p_WB);
  counters_.add("index_tiles_added", w.added);
  if (!twin_.covers(p_WB, 0.5 * options_.window_m)) {
    out.status(msg::REG_REJECTED_NO_MAP);
    out.reason("no twin tiles within " + std::to_string(static_cast<int>(0.5 * options_.window_m)) + " m yet");
    return;
  }
  std::optional<Matrix6d> covariance;  // the estimator's, in the correction's order (LocalMap.T_WB_covariance)
  if (m.T_WB_covariance().size() == 36) {
    covariance.emplace();
    for (int r = 0; r < 6; ++r)
      for (int k = 0; k < 6; ++k) (*covariance)(r, k) = m.T_WB_covariance()[6 * r + k];
    if (!usable_covariance(*covariance)) {
      covariance.reset();  // not a covariance: register without the gate rather than drop the cloud
      counters_.add("covariance_unusable");
    }
  }
  const auto stamp_ns = static_cast<std::int64_t>(m.keyframe_stamp_ns());
  ScaleTracker& scale = scale_.try_emplace(m.vehicle_id(), options_.registration).first->second;
  const std::optional<ScalePrior> scale_prior =
      scale_prior_applies(options_.registration, covariance) ? scale.prior(stamp_ns) : std::nullopt;
  RegistrationResult r = register_cloud(options_.registration, twin_.index(), source, covariance, scale_prior);
  PersistenceGate& gate = persistence_.try_emplace(m.vehicle_id(), options_.registration).first->second;
  std::optional<double> heading_sigma_deg;  // about W's z: the covariance's rotation block comes first
  if (covariance) heading_sigma_deg = std::sqrt((*covariance)(2, 2)) * 180.0 / M_PI;
  if (gate.review(r, stamp_ns, heading_sigma_deg)) {
    counters_.add("readmitted_persistent");
    out.readmitted(true);
  }
  scale.update(stamp_ns, r.accepted(), r.scale);
  inject_fault(m, r);
  out.status(to_msg(r.status));
  out.reason(r.reason);
  out.correction_W(dds::to_msg(r.correction_W));
  out.pivot_W(dds::to_msg(r.pivot_W));
  const auto info = geometry::to_row_major(r.information);
  std::copy(info.begin(), info.end(), out.information().begin());
  for (int i = 0; i < 6; ++i) out.information_eigenvalues()[i] = r.information_eigenvalues[i];
  out.rmse_m(r.rmse_m);
  out.source_points(static_cast<unsigned>(r.source_points));
  out.inliers(static_cast<unsigned>(r.inliers));
  out.fitness(r.fitness);
  out.compute_ms(r.time.total_ms + w.update_ms);
}

}  // namespace twinslam::registration

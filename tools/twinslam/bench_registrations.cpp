#include "bench_registrations.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "twinslam/core/csv.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/eval/association.hpp"
#include "twinslam/eval/stats.hpp"

namespace twinslam::cli {
namespace {

constexpr std::size_t kColumns = 29;  // CONTRACTS.md "Run outputs": registrations.csv
constexpr std::size_t kAccepted = 1, kDx = 12, kDroll = 15, kKeyframe = 21;
constexpr double kDegToRad = M_PI / 180.0;

double angle_deg(const Eigen::Matrix3d& R) { return Eigen::AngleAxisd(R).angle() / kDegToRad; }

}  // namespace

std::optional<RegistrationTruth> evaluate_registrations(const std::filesystem::path& run_dir, const Trajectory& gt,
                                                        double threshold_m) {
  const auto file = run_dir / "registrations.csv";
  Trajectory before, after;  // the keyframe pose sent with the LocalMap, and the one its registration measured
  read_csv(file, kColumns, [&](const CsvRow& row) {
    if (row.line == 1 || row.cells[kAccepted] != "1" || row.cells[kKeyframe].empty()) return;
    const auto num = [&](std::size_t col) { return parse_double(file, row, col, "value"); };
    Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
    T_WB.translation() << num(kKeyframe), num(kKeyframe + 1), num(kKeyframe + 2);
    const Eigen::Quaterniond q(num(kKeyframe + 6), num(kKeyframe + 3), num(kKeyframe + 4), num(kKeyframe + 5));
    if (std::abs(q.norm() - 1.0) > 1e-3) {
      throw InputError(file.string() + ":" + std::to_string(row.line) + ": kf_q is not a unit quaternion");
    }
    T_WB.linear() = q.normalized().toRotationMatrix();
    // The correction: position + (dx, dy, dz); attitude R_WB' = dR R_WB with dR = Rz(yaw) Ry(pitch) Rx(roll).
    const Eigen::Matrix3d dR = (Eigen::AngleAxisd(num(kDroll + 2) * kDegToRad, Eigen::Vector3d::UnitZ()) *
                                Eigen::AngleAxisd(num(kDroll + 1) * kDegToRad, Eigen::Vector3d::UnitY()) *
                                Eigen::AngleAxisd(num(kDroll) * kDegToRad, Eigen::Vector3d::UnitX()))
                                   .toRotationMatrix();
    Eigen::Isometry3d measured = T_WB;
    measured.linear() = dR * T_WB.linear();
    measured.translation() += Eigen::Vector3d(num(kDx), num(kDx + 1), num(kDx + 2));
    const auto stamp = static_cast<std::int64_t>(std::llround(num(0)));
    if (!before.poses.empty() && stamp <= before.poses.back().stamp_ns) return;  // a repeated answer: the first
    before.poses.push_back({stamp, T_WB});
    after.poses.push_back({stamp, measured});
  });
  const auto matches = eval::associate(gt, after);
  if (matches.empty()) return std::nullopt;
  RegistrationTruth out;
  out.threshold_m = threshold_m;
  std::vector<double> err_before, err_after, err_deg;
  std::ofstream rows(run_dir / "registration_errors.csv");
  rows << "stamp_ns,before_m,after_m,after_deg,ex_m,ey_m,ez_m\n";
  for (const auto& m : matches) {
    const StampedPose& g = gt.poses[m.gt];
    const Eigen::Vector3d e = after.poses[m.est].p_X() - g.p_X();
    err_before.push_back((before.poses[m.est].p_X() - g.p_X()).norm());
    err_after.push_back(e.norm());
    err_deg.push_back(angle_deg(after.poses[m.est].T_XB.linear() * g.T_XB.linear().transpose()));
    if (err_after.back() > threshold_m) ++out.off;
    char line[200];
    std::snprintf(line, sizeof line, "%lld,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f\n",
                  static_cast<long long>(after.poses[m.est].stamp_ns), err_before.back(), err_after.back(),
                  err_deg.back(), e.x(), e.y(), e.z());
    rows << line;
  }
  out.accepted = matches.size();
  out.median_before_m = eval::quantile(err_before, 0.5);
  out.median_after_m = eval::quantile(err_after, 0.5);
  out.max_after_m = *std::max_element(err_after.begin(), err_after.end());
  out.median_after_deg = eval::quantile(err_deg, 0.5);
  out.max_after_deg = *std::max_element(err_deg.begin(), err_deg.end());
  return out;
}

}  // namespace twinslam::cli

// `twinslam register --cloud FILE.ply --twin TWIN_DIR --pose "E N U YAW_DEG" [--repeat N] [--json]
//  [--weights paper|adaptive|fixed] [--config FILE.yaml]`: registers a landmark cloud to a twin store offline (paper
// Sec. III-C) with twinslam_registration_core, as the registration service would for one keyframe. The cloud's points
// are in the body frame B at the given pose (the estimate, which registration corrects); the store's tiles within the
// 150 m x 150 m window around the pose are indexed once (timed as `index`), then the cloud is registered N times.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/core/main_guard.hpp"
#include "twinslam/registration/registration.hpp"
#include "twinslam/twin/ply.hpp"
#include "twinslam/twin/store.hpp"

namespace twinslam::cli {
namespace {

using namespace twinslam::registration;

struct RegisterOptions {
  std::string cloud, twin, pose, weights, config;
  int repeat = 1;
  bool json = false;
};

// "E N U YAW_DEG" (spaces or commas) -> T_WB with the body's yaw about W's up axis.
Eigen::Isometry3d parse_pose(const std::string& text) {
  std::string s = text;
  std::replace(s.begin(), s.end(), ',', ' ');
  std::istringstream in(s);
  double v[4];
  for (double& x : v) {
    if (!(in >> x) || !std::isfinite(x)) throw UsageError("--pose: expected \"E N U YAW_DEG\", got \"" + text + "\"");
  }
  std::string rest;
  if (in >> rest) throw UsageError("--pose: expected 4 numbers \"E N U YAW_DEG\", got \"" + text + "\"");
  Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
  T_WB.linear() = Eigen::AngleAxisd(v[3] * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T_WB.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
  return T_WB;
}

RegistrationConfig make_config(const RegisterOptions& o) {
  RegistrationConfig c = o.config.empty() ? RegistrationConfig{} : load_registration_config(o.config);
  if (!o.weights.empty()) c = parse_registration_config("weights: " + o.weights, "--weights", c);
  c.validate(o.config.empty() ? "defaults" : o.config);
  return c;
}

double percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  const auto i = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size()))) - 1;
  return v[std::min(i, v.size() - 1)];
}

// (dx, dy, dz) [m]: the correction of the body position; (roll, pitch, yaw) [deg]: of dR, ZYX Euler angles in W.
std::vector<double> correction_6(const RegistrationResult& r) {
  const Eigen::Matrix3d& R = r.correction_W.linear();
  const double yaw = std::atan2(R(1, 0), R(0, 0)), pitch = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
  const double roll = std::atan2(R(2, 1), R(2, 2));
  const double d = 180.0 / M_PI;
  const Eigen::Vector3d dp = r.correction_xi.tail<3>();
  return {dp.x(), dp.y(), dp.z(), roll * d, pitch * d, yaw * d};
}

void print(const RegisterOptions& o, const RegistrationResult& r, double index_ms, std::size_t tiles,
           const std::vector<std::vector<double>>& t) {
  const auto med = [&](int k) { return percentile(t[static_cast<std::size_t>(k)], 0.5); };
  const std::vector<double> c = correction_6(r);
  const Vector6d& ev = r.information_eigenvalues;
  if (o.json) {
    const nlohmann::json j = {{"status", status_name(r.status)},
                              {"correction", c},
                              {"information_eigenvalues", std::vector<double>(ev.data(), ev.data() + 6)},
                              {"rmse_m", r.rmse_m},
                              {"inliers", r.inliers},
                              {"fitness", r.fitness},
                              {"time_ms",
                               {{"index", index_ms},
                                {"preprocess", med(0)},
                                {"icp", med(1)},
                                {"hessian", med(2)},
                                {"total", med(3)},
                                {"total_p99", percentile(t[3], 0.99)}}}};
    std::cout << j.dump() << std::endl;  // one object, one line
    return;
  }
  std::printf("status %s%s%s\n", status_name(r.status), r.reason.empty() ? "" : ": ", r.reason.c_str());
  std::printf("correction dx %.4f dy %.4f dz %.4f m, droll %.4f dpitch %.4f dyaw %.4f deg\n", c[0], c[1], c[2], c[3],
              c[4], c[5]);
  std::printf("information eigenvalues (per point, normalized) %.4g %.4g %.4g %.4g %.4g %.4g, %d zeroed (%s)\n", ev(0),
              ev(1), ev(2), ev(3), ev(4), ev(5), r.details.zero_directions, weight_mode_name(make_config(o).weights));
  std::printf("rmse %.4f m, inliers %zu of %zu (fitness %.3f), %d iterations\n", r.rmse_m, r.inliers, r.source_points,
              r.fitness, r.iterations);
  std::printf(
      "time: index %.2f ms (%zu tiles); median of %d: preprocess %.2f, icp %.2f, hessian %.3f, total %.2f ms; "
      "total p99 %.2f ms\n",
      index_ms, tiles, o.repeat, med(0), med(1), med(2), med(3), percentile(t[3], 0.99));
}

int run_register(const RegisterOptions& o) {
  if (o.repeat < 1) throw UsageError("--repeat must be >= 1");
  const Eigen::Isometry3d T_WB = parse_pose(o.pose);
  const RegistrationConfig config = make_config(o);
  const twin::Mesh cloud_B = twin::read_ply(o.cloud).mesh;
  const twin::TwinIndex store = twin::read_twin_index(o.twin);
  // L = W here: the pose is already in W, so T_WL = identity and T_LB = T_WB.
  SourceInput in;
  in.T_LB = T_WB;
  for (const Eigen::Vector3d& p_B : cloud_B.p_W) in.landmarks.push_back({T_WB * p_B, 1.0});
  const auto t0 = std::chrono::steady_clock::now();
  TwinTileIndex index(store.tile_size_m);
  const auto keys = tiles_in_window(store, T_WB.translation(), 150.0);
  for (const twin::TileKey& key : keys) add_tile_from_store(index, o.twin, store, key);
  const double index_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  RegistrationResult r;
  std::vector<std::vector<double>> t(4);
  for (int i = 0; i < o.repeat; ++i) {
    r = register_cloud(config, index, in);
    for (auto [k, v] :
         {std::pair{0, r.time.preprocess_ms}, {1, r.time.icp_ms}, {2, r.time.hessian_ms}, {3, r.time.total_ms}}) {
      t[static_cast<std::size_t>(k)].push_back(v);
    }
  }
  print(o, r, index_ms, keys.size(), t);
  return kExitOk;
}

}  // namespace

void add_register_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<RegisterOptions>();
  CLI::App* cmd = app.add_subcommand(
      "register",
      "Register a landmark cloud (body frame, PLY) to a twin store around a pose: correction, information, "
      "timing (exit 0 also when the registration is rejected: see status)");
  cmd->add_option("--cloud", o->cloud, "PLY of the landmarks in the body frame [m]")->required()->type_name("FILE.ply");
  cmd->add_option("--twin", o->twin, "Twin store (`twinslam twin build` output)")->required()->type_name("TWIN_DIR");
  cmd->add_option("--pose", o->pose, "Estimated body pose in W: east, north, up [m], yaw [deg]")
      ->required()
      ->type_name("\"E N U YAW_DEG\"");
  cmd->add_option("--repeat", o->repeat, "Register N times (timing median and p99)")->capture_default_str();
  cmd->add_flag("--json", o->json, "Print one JSON object (status, correction [m, deg], eigenvalues, time_ms, ...)");
  cmd->add_option("--weights", o->weights, "Information weighting (overrides the config)")
      ->check(CLI::IsMember({"paper", "adaptive", "fixed"}));
  cmd->add_option("--config", o->config, "Registration config (deploy/config/registration.yaml format)")
      ->type_name("FILE.yaml");
  cmd->callback([o, &exit_code] { exit_code = run_register(*o); });
}

}  // namespace twinslam::cli

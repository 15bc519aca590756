// `twinslam register`: a store built with `twinslam twin build` from a PLY, a landmark cloud PLY in the body frame at
// a pose that is off by a known amount, and the JSON correction that undoes it; bad input exits 2 with one line.
#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "subprocess.hpp"
#include "synthetic_twin.hpp"
#include "twinslam/twin/ply.hpp"

namespace twinslam::registration {
namespace {

namespace fs = std::filesystem;

twinslam::test::ProcessOutput twinslam_cli(const std::vector<std::string>& args) {
  std::vector<std::string> argv{std::string(TWINSLAM_BIN_DIR) + "/twinslam"};
  argv.insert(argv.end(), args.begin(), args.end());
  return twinslam::test::run_process(argv);
}

twin::Mesh city_mesh() {
  twin::Mesh m;
  for (const test::Rect& r : test::city_surfaces()) {
    const int i = static_cast<int>(m.p_W.size());
    m.p_W.insert(m.p_W.end(), {r.origin, r.origin + r.u, r.origin + r.u + r.v, r.origin + r.v});
    m.triangles.push_back({i, i + 1, i + 2});
    m.triangles.push_back({i, i + 2, i + 3});
  }
  return m;
}

class RegistrationCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("twinslam_register_cli_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    twin::write_ply((dir_ / "city.ply").string(), city_mesh(), twin::PlyFormat::kBinaryLittleEndian);
    const auto b = twinslam_cli({"twin", "build", (dir_ / "city.ply").string(), "--origin", "47.3769,8.5417,408",
                                 "--out", (dir_ / "twin").string(), "--spacing", "0.5"});
    ASSERT_EQ(b.exit_code, 0) << b.out << b.err;
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(RegistrationCli, JsonCorrectionUndoesAKnownPoseError) {
  // True body pose: 15 m above the city centre, yaw 30 deg. The pose given to the CLI is off by (0.5, -0.4, 0.2) m and
  // 2 deg of yaw; the landmarks are true points expressed in the true body frame.
  const Eigen::Vector3d p_true = test::kCentre + Eigen::Vector3d(0, -5, 15), d_p(0.5, -0.4, 0.2);
  Eigen::Isometry3d T_WB_true = Eigen::Isometry3d::Identity();
  T_WB_true.linear() = Eigen::AngleAxisd(30.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T_WB_true.translation() = p_true;
  twin::Mesh cloud;
  for (const auto& p_W : test::sample_noisy(test::city_surfaces(), 3000, 0.05, 7)) {
    cloud.p_W.push_back(T_WB_true.inverse() * p_W);
  }
  twin::write_ply((dir_ / "cloud.ply").string(), cloud, twin::PlyFormat::kAscii);
  const Eigen::Vector3d p_guess = p_true + d_p;
  const std::string pose =
      std::to_string(p_guess.x()) + " " + std::to_string(p_guess.y()) + " " + std::to_string(p_guess.z()) + " 32";
  const auto r = twinslam_cli({"register", "--cloud", (dir_ / "cloud.ply").string(), "--twin", (dir_ / "twin").string(),
                               "--pose", pose, "--repeat", "3", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);  // exactly one object
  EXPECT_EQ(j.at("status"), "accepted");
  const std::vector<double> c = j.at("correction");
  ASSERT_EQ(c.size(), 6u);
  EXPECT_NEAR(c[0], -d_p.x(), 0.02);
  EXPECT_NEAR(c[1], -d_p.y(), 0.02);
  EXPECT_NEAR(c[2], -d_p.z(), 0.02);
  EXPECT_NEAR(c[3], 0.0, 0.05);
  EXPECT_NEAR(c[4], 0.0, 0.05);
  EXPECT_NEAR(c[5], -2.0, 0.05);
  EXPECT_EQ(j.at("information_eigenvalues").size(), 6u);
  EXPECT_GT(j.at("inliers").get<int>(), 1000);
  for (const char* k : {"index", "preprocess", "icp", "hessian", "total", "total_p99"}) {
    EXPECT_GE(j.at("time_ms").at(k).get<double>(), 0.0) << k;
  }
  EXPECT_TRUE(j.contains("rmse_m") && j.contains("fitness"));
}

TEST_F(RegistrationCli, BadInputExitsTwoWithOneLine) {
  const std::string twin = (dir_ / "twin").string();
  twin::Mesh cloud;
  cloud.p_W = {{0, 0, 0}, {1, 0, 0}};
  twin::write_ply((dir_ / "cloud.ply").string(), cloud, twin::PlyFormat::kAscii);
  const std::string ply = (dir_ / "cloud.ply").string();
  for (const auto& [args, mention] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"--cloud", "/nonexistent.ply", "--twin", twin, "--pose", "0 0 0 0"}, "/nonexistent.ply"},
           {{"--cloud", ply, "--twin", "/nonexistent_twin", "--pose", "0 0 0 0"}, "/nonexistent_twin"},
           {{"--cloud", ply, "--twin", twin, "--pose", "1 2 3"}, "--pose"},
           {{"--cloud", ply, "--twin", twin, "--pose", "1 2 3 x"}, "--pose"},
           {{"--cloud", ply, "--twin", twin, "--pose", "0 0 0 0", "--config", "/nonexistent.yaml"},
            "nonexistent.yaml"}}) {
    std::vector<std::string> argv{"register"};
    argv.insert(argv.end(), args.begin(), args.end());
    const auto r = twinslam_cli(argv);
    EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
    EXPECT_NE(r.err.find(mention), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "not one line: " << r.err;
  }
}

}  // namespace
}  // namespace twinslam::registration

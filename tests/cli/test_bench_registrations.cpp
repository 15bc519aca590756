// `twinslam bench`'s check of accepted registrations against the truth (issue 12): the pose a registration measured
// is the LocalMap's keyframe pose moved by the correction, and it is compared with the ground truth at that stamp.
#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "bench_registrations.hpp"
#include "twinslam/core/error.hpp"

namespace fs = std::filesystem;
using namespace twinslam;

namespace {

constexpr const char* kHeader =
    "stamp_ns,accepted,rmse_m,inliers,fitness,time_ms,ev1,ev2,ev3,ev4,ev5,ev6,dx_m,dy_m,dz_m,droll_deg,dpitch_deg,"
    "dyaw_deg,latency_ms,pipeline_latency_ms,reason,kf_x_m,kf_y_m,kf_z_m,kf_qx,kf_qy,kf_qz,kf_qw,sigma_m\n";

// One registrations.csv row: accepted flag, correction (m, deg), keyframe pose (position, quaternion x y z w).
std::string row(long long stamp, int accepted, const Eigen::Vector3d& dp, const Eigen::Vector3d& drpy_deg,
                const std::string& kf) {
  char buf[400];
  std::snprintf(buf, sizeof buf, "%lld,%d,0.2,100,0.8,4.0,1,2,3,4,5,6,%g,%g,%g,%g,%g,%g,3.0,5.0,%s,%s,0.1\n", stamp,
                accepted, dp.x(), dp.y(), dp.z(), drpy_deg.x(), drpy_deg.y(), drpy_deg.z(),
                accepted ? "accepted" : "rmse", kf.c_str());
  return buf;
}

}  // namespace

TEST(BenchRegistrations, MeasuredPoseIsTheKeyframePoseMovedByTheCorrection) {
  const fs::path dir = fs::temp_directory_path() / ("twinslam_benchreg_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  Trajectory gt;  // truth: at (t, 0, 0), heading 0, every 0.1 s
  for (int k = 0; k < 50; ++k) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() << k, 0, 0;
    gt.poses.push_back({k * 100'000'000LL, T});
  }
  {
    std::ofstream f(dir / "registrations.csv");
    f << kHeader;
    // Keyframe 10 estimated 0.4 m north and yawed 2 deg; the correction brings it to 0.1 m south, 0.5 deg.
    const double h = 1.0 * M_PI / 180.0;  // half of 2 deg
    f << row(1'000'000'000LL, 1, {0, -0.5, 0}, {0, 0, -1.5},
             "10,0.4,0,0,0," + std::to_string(std::sin(h)) + "," + std::to_string(std::cos(h)));
    // Keyframe 20: exact estimate, correction 0.6 m east: off by 0.6 m.
    f << row(2'000'000'000LL, 1, {0.6, 0, 0}, {0, 0, 0}, "20,0,0,0,0,0,1");
    // Rejected, and accepted without a pose in W: not evaluated.
    f << row(3'000'000'000LL, 0, {9, 9, 9}, {0, 0, 0}, "30,0,0,0,0,0,1");
    f << row(4'000'000'000LL, 1, {9, 9, 9}, {0, 0, 0}, ",,,,,,");
  }
  const auto truth = cli::evaluate_registrations(dir, gt, 0.5);
  ASSERT_TRUE(truth.has_value());
  EXPECT_EQ(truth->accepted, 2u);
  EXPECT_EQ(truth->off, 1u);
  EXPECT_NEAR(truth->max_after_m, 0.6, 1e-9);
  EXPECT_NEAR(truth->max_after_deg, 0.5, 1e-3);  // the quaternion is written with 6 decimals here
  EXPECT_NEAR(truth->median_before_m, 0.2, 1e-9);  // 0.4 and 0: the midpoint
  EXPECT_TRUE(fs::exists(dir / "registration_errors.csv"));
  fs::remove_all(dir);
}

TEST(BenchRegistrations, MalformedRowNamesTheFileAndLine) {
  const fs::path dir = fs::temp_directory_path() / ("twinslam_benchreg_bad_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "registrations.csv") << kHeader << row(1, 1, {0, 0, 0}, {0, 0, 0}, "1,2,3,0,0,0,0.5");
  Trajectory gt;
  gt.poses.push_back({1, Eigen::Isometry3d::Identity()});
  try {
    cli::evaluate_registrations(dir, gt);
    FAIL() << "a non-unit quaternion was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("registrations.csv:2"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

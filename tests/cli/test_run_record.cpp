// The run outputs of CONTRACTS.md: trajectory.tum / trajectory_local.tum read back to the poses recorded,
// timing.csv has one row per pose with end-to-end time from this process's clock, registrations.csv has the
// contract's columns.
#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "run_record.hpp"
#include "twinslam/core/csv.hpp"
#include "twinslam/trajectory/io.hpp"

namespace fs = std::filesystem;
using namespace twinslam;

TEST(RunRecord, WritesTrajectoriesTimingAndRegistrations) {
  cli::RunRecord rec;
  for (int k = 0; k < 5; ++k) {
    const std::int64_t stamp = 1'000'000'000LL + k * 50'000'000LL;
    rec.frame_in(stamp, 100.0 * k);
    rec.features(stamp, 2.5);
    cli::OdometryRecord o;
    o.stamp_ns = stamp;
    o.T_LB.translation() = Eigen::Vector3d(k, 0, 0);
    o.T_WB = Eigen::Translation3d(10, 20, 0) * Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()) * o.T_LB;
    o.estimator_ms = 4.0;
    rec.odometry(o, 100.0 * k + 7.5);
  }
  cli::OdometryRecord init;  // an initializing placeholder after the estimates: timing only
  init.stamp_ns = 2'000'000'000LL;
  init.estimated = false;
  rec.odometry(init, 1000.0);
  cli::RegistrationRecord r;
  r.stamp_ns = 1'100'000'000LL;
  r.accepted = true;
  r.info_eigenvalues << 1, 2, 3, 4, 5, 6;
  r.sigma_m = 0.25;
  const Eigen::Isometry3d T_WB_kf(Eigen::Translation3d(1, 2, 3) * Eigen::AngleAxisd(0.25, Eigen::Vector3d::UnitZ()));
  rec.local_map(r.stamp_ns, 500.0, 40, T_WB_kf);  // the estimator had a world alignment: the pose is in W
  rec.local_map(r.stamp_ns, 900.0, 40);  // a re-delivery: the first sighting counts
  rec.registration(r, 512.5);
  cli::RegistrationRecord rejected;
  rejected.stamp_ns = 1'200'000'000LL;
  rejected.reason = "rmse 0.41 m > 0.3 m, 12 inliers";  // a comma would split the field: written as ';'
  rec.registration(rejected, 600.0);  // its LocalMap was never seen: no latency
  const fs::path dir = fs::temp_directory_path() / ("twinslam_runrec_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const auto files = rec.write(dir);
  EXPECT_EQ(files.size(), 4u);

  const auto world = read_tum(dir / "trajectory.tum");
  const auto local = read_tum(dir / "trajectory_local.tum");
  ASSERT_EQ(world.size(), 5u);
  ASSERT_EQ(local.size(), 5u);
  EXPECT_EQ(world.poses[3].stamp_ns, 1'150'000'000LL);
  EXPECT_NEAR((local.poses[3].p_X() - Eigen::Vector3d(3, 0, 0)).norm(), 0, 1e-9);
  const Eigen::Vector3d expected_W = Eigen::Vector3d(10, 20, 0) + Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()) *
                                                                       Eigen::Vector3d(3, 0, 0);
  EXPECT_NEAR((world.poses[3].p_X() - expected_W).norm(), 0, 1e-6);

  std::size_t rows = 0;
  read_csv(dir / "timing.csv", 4, [&](const CsvRow& row) {
    if (row.line == 1) return;  // header
    if (rows++ == 5) return;  // the placeholder frame
    EXPECT_DOUBLE_EQ(parse_double(dir / "timing.csv", row, 1, "tracking_ms"), 2.5);
    EXPECT_DOUBLE_EQ(parse_double(dir / "timing.csv", row, 3, "end_to_end_ms"), 7.5);
  });
  EXPECT_EQ(rows, 6u);  // every frame has a timing row, estimated or not
  std::size_t regs = 0;
  read_csv(dir / "registrations.csv", 29, [&](const CsvRow& row) {
    if (row.line == 1) {
      EXPECT_EQ(row.cells[19], "pipeline_latency_ms");
      EXPECT_EQ(row.cells[20], "reason");
      EXPECT_EQ(row.cells[21], "kf_x_m");
      EXPECT_EQ(row.cells[27], "kf_qw");
      EXPECT_EQ(row.cells[28], "sigma_m");
      return;
    }
    if (regs++ == 0) {
      EXPECT_EQ(row.cells[1], "1");
      EXPECT_EQ(row.cells[11], "6");
      EXPECT_EQ(row.cells[19], "12.5");
      // The keyframe pose the LocalMap carried in W, which the correction applies to.
      EXPECT_DOUBLE_EQ(parse_double(dir / "registrations.csv", row, 22, "kf_y_m"), 2.0);
      EXPECT_NEAR(parse_double(dir / "registrations.csv", row, 26, "kf_qz"), std::sin(0.125), 1e-9);
      EXPECT_DOUBLE_EQ(parse_double(dir / "registrations.csv", row, 28, "sigma_m"), 0.25);
    } else {
      EXPECT_EQ(row.cells[1], "0");
      EXPECT_EQ(row.cells[19], "");
      EXPECT_EQ(row.cells[20], "rmse 0.41 m > 0.3 m; 12 inliers");
      EXPECT_EQ(row.cells[21], "");  // no LocalMap seen: no pose
    }
  });
  EXPECT_EQ(regs, 2u);
  const auto latency = rec.pipeline_latency();
  EXPECT_EQ(latency.count, 1u);
  EXPECT_DOUBLE_EQ(latency.median_ms, 12.5);
  EXPECT_EQ(rec.local_map_landmarks(), (std::pair<std::size_t, std::size_t>{40, 40}));
  fs::remove_all(dir);
}

// The recorder reads LocalMaps and Registrations on separate readers: a registration can be recorded before its
// keyframe's LocalMap (seen in a lockstep tiny run). Its row still carries the keyframe's pose.
TEST(RunRecord, ARegistrationRecordedBeforeItsLocalMapStillGetsTheKeyframePose) {
  cli::RunRecord rec;
  cli::RegistrationRecord r;
  r.stamp_ns = 1'100'000'000LL;
  r.accepted = true;
  rec.registration(r, 500.0);
  rec.local_map(r.stamp_ns, 501.0, 40, Eigen::Isometry3d(Eigen::Translation3d(4, 5, 6)));
  const fs::path dir = fs::temp_directory_path() / ("twinslam_runrec_late_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  rec.write(dir);
  std::size_t rows = 0;
  read_csv(dir / "registrations.csv", 29, [&](const CsvRow& row) {
    if (row.line == 1) return;
    ++rows;
    EXPECT_DOUBLE_EQ(parse_double(dir / "registrations.csv", row, 21, "kf_x_m"), 4.0);
    EXPECT_DOUBLE_EQ(parse_double(dir / "registrations.csv", row, 23, "kf_z_m"), 6.0);
  });
  EXPECT_EQ(rows, 1u);
  fs::remove_all(dir);
}

TEST(RunRecord, WithoutOdometryWritesNoTrajectory) {
  cli::RunRecord rec;
  const fs::path dir = fs::temp_directory_path() / ("twinslam_runrec_empty_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  rec.write(dir);
  EXPECT_FALSE(fs::exists(dir / "trajectory.tum"));
  EXPECT_TRUE(fs::exists(dir / "timing.csv"));
  fs::remove_all(dir);
}

// An estimator that restarts mid-flight (issue 14's fault) is back in its own L, then aligns again: the poses of that
// stretch are listed (run.json out_of_world_ns), so evaluation in W leaves them out; the stretch before the first
// alignment is not one (aligned_from_stamp_ns covers it).
TEST(RunRecord, ListsTheStretchesOutOfWAfterTheAlignment) {
  cli::RunRecord rec;
  const auto pose = [&rec](std::int64_t stamp, bool estimated, bool aligned) {
    cli::OdometryRecord o;
    o.stamp_ns = stamp;
    o.estimated = estimated;
    o.aligned = aligned;
    rec.odometry(o, 0.0);
  };
  pose(1, false, false);
  pose(2, true, false);
  EXPECT_TRUE(rec.out_of_world_after_alignment().empty());
  pose(3, true, true);
  pose(4, true, true);
  pose(5, false, false);  // killed and restarted: initializing
  pose(6, true, false);   // tracking in its new L
  pose(7, true, true);
  pose(8, true, false);
  EXPECT_EQ(rec.first_aligned_stamp_ns(), 3);
  const std::vector<std::pair<std::int64_t, std::int64_t>> expected{{5, 6}, {8, 8}};
  EXPECT_EQ(rec.out_of_world_after_alignment(), expected);
}

// Trajectory readers and writer: exact round trip, strict rejection with FILE:LINE, folder conventions.
#include <gtest/gtest.h>

#include <unistd.h>

#include <fstream>

#include "synthetic.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/trajectory/io.hpp"

namespace twinslam {
namespace {
namespace fs = std::filesystem;

class TrajectoryIo : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("twinslam_test_trajectory_io_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
    return p;
  }
  // The InputError message of reading `text` as TUM.
  std::string tum_error(const std::string& text) {
    const fs::path p = write("bad.tum", text);
    try {
      read_tum(p);
    } catch (const InputError& e) {
      return e.what();
    }
    return "(no error)";
  }
  fs::path dir_;
};

TEST_F(TrajectoryIo, TumRoundTripIsExact) {
  Trajectory t = test::helix(50, 50'000'001, 1'403'715'273'262'140'123);  // epoch-sized, odd nanoseconds
  const fs::path p = dir_ / "t.tum";
  write_tum(p, t);
  const Trajectory back = read_tum(p);
  ASSERT_EQ(back.size(), t.size());
  for (std::size_t k = 0; k < t.size(); ++k) {
    EXPECT_EQ(back.poses[k].stamp_ns, t.poses[k].stamp_ns);
    EXPECT_EQ(back.poses[k].p_X(), t.poses[k].p_X());
    EXPECT_LT((back.poses[k].T_XB.linear() - t.poses[k].T_XB.linear()).norm(), 1e-14);
  }
}

TEST_F(TrajectoryIo, TumSecondsBecomeExactNanoseconds) {
  const Trajectory t = read_tum(write("a.tum", "# t x y z qx qy qz qw\n1403715273.26214 1 2 3 0 0 0 1\n"
                                               "1403715273.5\t1 2 3 0 0 0.7071068 0.7071068\n"));
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t.poses[0].stamp_ns, 1'403'715'273'262'140'000);
  EXPECT_EQ(t.poses[1].stamp_ns, 1'403'715'273'500'000'000);
  EXPECT_NEAR(t.poses[1].T_XB.linear()(1, 0), 1.0, 1e-6);  // 90 deg about z, qx..qw order
}

TEST_F(TrajectoryIo, TumRejectsBadRowsNamingFileAndLine) {
  const std::string ok = "# header\n1.0 0 0 0 0 0 0 1\n";
  EXPECT_NE(tum_error(ok + "2.0 0 0 0 0 0 1\n").find("bad.tum:3: expected 8 values"), std::string::npos);
  EXPECT_NE(tum_error(ok + "2.0 nan 0 0 0 0 0 1\n").find("bad.tum:3: tx: not finite"), std::string::npos);
  EXPECT_NE(tum_error(ok + "2.0 0 0 x 0 0 0 1\n").find("bad.tum:3: tz: not a number"), std::string::npos);
  EXPECT_NE(tum_error(ok + "2.0 0 0 0 0 0 0 1.01\n").find("bad.tum:3: quaternion is not normalized"),
            std::string::npos);
  EXPECT_NE(tum_error(ok + "1.0 0 0 0 0 0 0 1\n").find("bad.tum:3: timestamp"), std::string::npos);
  EXPECT_NE(tum_error(ok + "0.5 0 0 0 0 0 0 1\n").find("does not increase"), std::string::npos);
  EXPECT_NE(tum_error("# only a comment\n\n").find("bad.tum: no poses"), std::string::npos);
  EXPECT_NE(tum_error("").find("no poses"), std::string::npos);
  EXPECT_THROW(read_tum(dir_ / "missing.tum"), InputError);
}

TEST_F(TrajectoryIo, EurocCsvUsesWxyzQuaternionOrder) {
  const std::string header =
      "#timestamp,p_RS_R_x [m],p_RS_R_y [m],p_RS_R_z [m],q_RS_w [],q_RS_x [],q_RS_y [],q_RS_z [],v_RS_R_x [m s^-1],"
      "v_RS_R_y [m s^-1],v_RS_R_z [m s^-1],b_w_RS_S_x [rad s^-1],b_w_RS_S_y [rad s^-1],b_w_RS_S_z [rad s^-1],"
      "b_a_RS_S_x [m s^-2],b_a_RS_S_y [m s^-2],b_a_RS_S_z [m s^-2]\n";
  const fs::path p = write("gt.csv", header +
                                         "1403715273262142976,0.8,2.1,0.9,0.7071068,0,0,0.7071068,0,0,0,0,0,0,0,0,0\n"
                                         "1403715273267142912,0.9,2.1,0.9,1,0,0,0,0,0,0,0,0,0,0,0,0\n");
  const Trajectory t = read_euroc_groundtruth(p);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t.poses[0].stamp_ns, 1403715273262142976);
  EXPECT_EQ(t.poses[0].p_X(), Eigen::Vector3d(0.8, 2.1, 0.9));
  EXPECT_NEAR(t.poses[0].T_XB.linear()(1, 0), 1.0, 1e-6);  // w first: 90 deg about z
  // A truncated row and an unnormalized quaternion are rejected with the line.
  try {
    read_euroc_groundtruth(write("bad.csv", header + "1,0,0,0,1,0,0,0,0,0,0,0,0,0,0,0,0\n2,0,0,0,1,0,0\n"));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.csv:3:"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_euroc_groundtruth(write("bad2.csv", header + "1,0,0,0,2,0,0,0,0,0,0,0,0,0,0,0,0\n")), InputError);
}

TEST_F(TrajectoryIo, DatasetFolderPrefersGroundtruthTum) {
  const std::string csv_row = "5000000000,9,9,9,1,0,0,0,0,0,0,0,0,0,0,0,0\n";
  write("ds/mav0/state_groundtruth_estimate0/data.csv", "#timestamp,...\n" + csv_row);
  EXPECT_EQ(read_dataset_groundtruth(dir_ / "ds").poses[0].p_X().x(), 9.0);  // CSV fallback
  write("ds/groundtruth.tum", "1.0 1 0 0 0 0 0 1\n");
  EXPECT_EQ(read_dataset_groundtruth(dir_ / "ds").poses[0].p_X().x(), 1.0);  // TUM preferred
  EXPECT_EQ(read_trajectory_any(dir_ / "ds").poses[0].p_X().x(), 1.0);
  EXPECT_EQ(read_trajectory_any(dir_ / "ds/mav0/state_groundtruth_estimate0/data.csv").poses[0].p_X().x(), 9.0);
  fs::create_directories(dir_ / "empty_ds");
  EXPECT_THROW(read_dataset_groundtruth(dir_ / "empty_ds"), InputError);
  try {
    read_trajectory_any(dir_ / "empty_ds");
    FAIL() << "empty folder accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("neither a run folder"), std::string::npos) << e.what();
  }
}

TEST_F(TrajectoryIo, RunFolderReadsTrajectoryTum) {
  write("run/trajectory.tum", "2.0 3 0 0 0 0 0 1\n");
  EXPECT_EQ(read_trajectory_any(dir_ / "run").poses[0].p_X().x(), 3.0);
  EXPECT_THROW(read_run_trajectory(dir_ / "nope"), InputError);
  EXPECT_THROW(read_trajectory_any(dir_ / "nope"), InputError);
}

}  // namespace
}  // namespace twinslam

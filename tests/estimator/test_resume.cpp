// A restarted estimator resumes from its checkpoint (resume.hpp, issue 14): the file round-trips and a broken one
// is named; the plan carries the state over the gap with sigmas that grow with it; and an estimator resumed in
// steady flight - where neither initialization can start it (test_motion_init.cpp) - follows the flight at the
// right speed and scale.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include "sliding_window_sim.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/estimator/resume.hpp"
#include "twinslam/estimator/sliding_window_estimator.hpp"

namespace twinslam::estimator {
namespace {

namespace fs = std::filesystem;
constexpr double kDeg = M_PI / 180.0;

EstimatorCheckpoint example() {
  EstimatorCheckpoint cp;
  cp.stamp_ns = 1'000'000'045'000'000'000;
  cp.p_W = {10.0, -20.0, 15.0};
  cp.q_WB = Eigen::AngleAxisd(30.0 * kDeg, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitY());
  cp.v_W = {3.0, 0.5, 0.0};
  cp.bias.gyro = {0.001, -0.002, 0.003};
  cp.bias.accel = {0.05, 0.0, -0.04};
  cp.position_sigma_m = 0.2;
  cp.yaw_sigma_deg = 0.4;
  return cp;
}

fs::path temp(const std::string& name) {
  return fs::temp_directory_path() / ("twinslam_resume_" + std::to_string(::getpid()) + "_" + name);
}

void write_text(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

TEST(Resume, CheckpointFileRoundTripsAndABrokenOneIsNamed) {
  const fs::path file = temp("cp.json");
  const EstimatorCheckpoint cp = example();
  write_checkpoint(file, cp);
  const auto back = read_checkpoint(file);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->stamp_ns, cp.stamp_ns);
  EXPECT_TRUE(back->p_W.isApprox(cp.p_W, 1e-12));
  EXPECT_LT(back->q_WB.angularDistance(cp.q_WB), 1e-12);
  EXPECT_TRUE(back->v_W.isApprox(cp.v_W, 1e-12));
  EXPECT_TRUE(back->bias.gyro.isApprox(cp.bias.gyro, 1e-12));
  EXPECT_TRUE(back->bias.accel.isApprox(cp.bias.accel, 1e-12));
  EXPECT_DOUBLE_EQ(back->yaw_sigma_deg, cp.yaw_sigma_deg);
  EXPECT_FALSE(fs::exists(file.string() + ".tmp"));  // written aside and renamed over

  EXPECT_FALSE(read_checkpoint(temp("absent.json")).has_value());  // no checkpoint yet: nothing to resume
  const std::pair<std::string, std::string> broken[] = {
      {"{not json", "not a JSON object"},
      {R"({"p_W":[1,2,3]})", "'stamp_ns'"},
      {R"({"stamp_ns":-5,"p_W":[1,2,3]})", "'stamp_ns'"},
      {R"({"stamp_ns":18446744073709551615,"p_W":[1,2,3]})", "'stamp_ns'"},  // would wrap to -1
      {R"({"stamp_ns":5,"p_W":[1,null,3]})", "'p_W'"},
      {R"({"stamp_ns":5,"p_W":[1,2,3],"q_WB_wxyz":[1,1,0,0]})", "unit quaternion"},
      {R"({"stamp_ns":5,"p_W":[1,2,3],"q_WB_wxyz":[1,0,0,0],"v_W":[1,2]})", "'v_W'"},
  };
  for (const auto& [text, what] : broken) {
    write_text(file, text);
    try {
      read_checkpoint(file);
      ADD_FAILURE() << "accepted " << text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  }
  fs::remove(file);
}

TEST(Resume, PlanCarriesTheStateOverTheGapWithSigmasThatGrowWithIt) {
  const EstimatorCheckpoint cp = example();
  ResumeConfig c;
  const auto plan = plan_resume(cp, cp.stamp_ns + 1'000'000'000, c);
  ASSERT_TRUE(plan.has_value());
  EXPECT_DOUBLE_EQ(plan->age_s, 1.0);
  // The body where constant velocity takes it, with the checkpoint's heading; T_WL = (that heading, that position)
  // times the new L (heading 0, origin at the body) gives back the checkpoint's attitude.
  EXPECT_TRUE(plan->pose_W.p_W.isApprox(cp.p_W + cp.v_W, 1e-12));
  EXPECT_NEAR(plan->pose_W.yaw_deg, 30.0, 1e-9);
  const Eigen::Matrix3d R_WL = Eigen::AngleAxisd(30.0 * kDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_LT(Eigen::Quaterniond(R_WL * plan->state_L.q_LB.toRotationMatrix()).angularDistance(cp.q_WB), 1e-9);
  EXPECT_TRUE((R_WL * plan->state_L.v_L).isApprox(cp.v_W, 1e-9));
  EXPECT_TRUE(plan->state_L.p_L.isZero());
  EXPECT_TRUE(plan->state_L.bias.accel.isApprox(cp.bias.accel));
  EXPECT_NEAR(plan->sigmas.velocity_mps, c.velocity_sigma_mps + c.max_accel_mps2 * 1.0, 1e-12);
  EXPECT_NEAR(plan->pose_W.sigmas->yaw_rad, (cp.yaw_sigma_deg + c.max_rate_degps) * kDeg, 1e-12);
  const auto later = plan_resume(cp, cp.stamp_ns + 3'000'000'000, c);
  ASSERT_TRUE(later.has_value());
  EXPECT_GT(later->sigmas.velocity_mps, plan->sigmas.velocity_mps);
  EXPECT_GT(later->pose_W.sigmas->position_m, plan->pose_W.sigmas->position_m);

  std::string why;
  EXPECT_FALSE(plan_resume(cp, cp.stamp_ns + 6'000'000'000, c, &why));  // older than max_age_s
  EXPECT_NE(why.find("old"), std::string::npos) << why;
  EXPECT_FALSE(plan_resume(cp, cp.stamp_ns - 1'000'000, c, &why));  // from the future: another flight's
  EXPECT_NE(why.find("after the first frame"), std::string::npos) << why;
  ResumeConfig bad;
  bad.max_age_s = -1.0;
  EXPECT_THROW(bad.validate(), InputError);
}

// Steady flight at 3 m/s, where neither the static nor the motion initialization starts a new estimator
// (SlidingWindow.SteadyFlightIsNeitherRestNorAScaledMotion). A first estimator, started from the truth, runs 3 s and
// leaves its checkpoint; a second one gets IMU and frames only from 4 s on (the restart's gap), resumes from it and
// follows: speed within 0.3 m/s, and the distance flown from 5 to 9 s within 10 % of the truth (the scale held). At
// constant velocity the window cannot observe the scale: the resumed one keeps the checkpoint's speed error, which
// itself depends on rounding (the first 3 s amplify it): 0.976 of the truth built with gcc -O3, 0.930 with clang -O1
// (the sanitized tree); a resume that lost the velocity is off by far more.
TEST(Resume, AnEstimatorResumedInSteadyFlightFollowsIt) {
  testing::AnalyticTrajectory steady;
  steady.position = {testing::Sinusoid{0.0, 3.0, 0.0}, testing::Sinusoid{1.0, 0.0, 0.0},
                     testing::Sinusoid{5.0, 0.0, 0.0}};
  steady.yaw = steady.pitch = steady.roll = testing::Sinusoid{};
  const testing::SimRun run = testing::make_sim_run(9.0, 0.5, 41u, 2000, 460.0, steady, {30.0, 50.0, 60.0});
  SlidingWindowConfig c;
  c.T_BC = run.T_BC;
  c.pixel_sigma = 0.5;
  c.max_solver_time_s = 10.0;  // a cap that never binds: the same result on a slow (sanitized) build

  SlidingWindowEstimator first(c);
  std::optional<EstimatorCheckpoint> cp;
  std::size_t imu_next = 0;
  ImuState truth0;
  truth0.q_LB = run.frames.front().truth.q_LB;
  truth0.v_L = run.frames.front().truth.v_L;
  truth0.bias = run.bias;
  first.initialize_next_frame(truth0);
  for (const auto& f : run.frames) {
    if (f.stamp_ns > 3'000'000'000) break;
    while (imu_next < run.imu.size() && run.imu[imu_next].stamp_ns <= f.stamp_ns) first.add_imu(run.imu[imu_next++]);
    const FrameEstimate e = first.add_frame(f.stamp_ns, f.features);
    ASSERT_EQ(e.status, EstimatorStatus::kTracking);
    cp = EstimatorCheckpoint{e.stamp_ns, e.T_LB.translation(), Eigen::Quaterniond(e.T_LB.linear()), e.v_L, e.bias};
  }
  ASSERT_TRUE(cp.has_value());

  SlidingWindowEstimator second(c);
  imu_next = 0;
  while (run.imu[imu_next].stamp_ns < 4'000'000'000) ++imu_next;
  bool resumed = false;
  std::optional<Eigen::Vector3d> p5_est, p5_true;
  double max_speed_error = 0.0;
  for (const auto& f : run.frames) {
    if (f.stamp_ns < 4'000'000'000 + 50'000'000) continue;  // the first frame IMU covers
    while (imu_next < run.imu.size() && run.imu[imu_next].stamp_ns <= f.stamp_ns) second.add_imu(run.imu[imu_next++]);
    if (!resumed) {
      const auto plan = plan_resume(*cp, f.stamp_ns, ResumeConfig{});
      ASSERT_TRUE(plan.has_value());
      second.initialize_next_frame(plan->state_L, plan->sigmas);
      resumed = true;
    }
    const FrameEstimate e = second.add_frame(f.stamp_ns, f.features);
    ASSERT_EQ(e.status, EstimatorStatus::kTracking) << "at " << 1e-9 * static_cast<double>(f.stamp_ns) << " s";
    max_speed_error = std::max(max_speed_error, std::abs(e.v_L.norm() - f.truth.v_L.norm()));
    if (f.stamp_ns >= 5'000'000'000 && !p5_est) {
      p5_est = e.T_LB.translation();
      p5_true = f.truth.p_L;
    }
    if (f.stamp_ns >= 9'000'000'000 - 50'000'000 && p5_est) {
      const double flown = (e.T_LB.translation() - *p5_est).norm(), truth = (f.truth.p_L - *p5_true).norm();
      std::printf("resumed: speed error up to %.3f m/s; flown %.2f m of %.2f m\n", max_speed_error, flown, truth);
      EXPECT_NEAR(flown / truth, 1.0, 0.10);
      break;
    }
  }
  EXPECT_LT(max_speed_error, 0.3);
}

}  // namespace
}  // namespace twinslam::estimator

// The estimator's own check of a registration (registration_gate.hpp): a correction implausible under the covariance
// published with the LocalMap, or too large once the alignment is declared, is refused with its reason; what
// registration's own gate would pass is never refused.
#include <gtest/gtest.h>

#include "twinslam/core/error.hpp"
#include "twinslam/estimator/registration_gate.hpp"

namespace twinslam::estimator {
namespace {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
constexpr double kDeg = M_PI / 180.0;

// A keyframe 120 m from W's origin (so a rotation about the origin would move it far) with sigmas 1 deg / 0.5 m.
RegistrationGateInput keyframe_with(const Eigen::Isometry3d& correction_W) {
  RegistrationGateInput in;
  in.T_WB.translation() = Eigen::Vector3d(100.0, -60.0, 30.0);
  in.correction_W = correction_W;
  Matrix6d cov = Matrix6d::Zero();
  cov.diagonal() << Eigen::Vector3d::Constant(std::pow(1.0 * kDeg, 2)), Eigen::Vector3d::Constant(0.25);
  in.covariance = cov;
  in.declared = true;
  return in;
}

Eigen::Isometry3d shift(double east_m) {
  return Eigen::Isometry3d(Eigen::Translation3d(east_m, 0.0, 0.0));
}

TEST(RegistrationGate, TheCorrectionIsTakenAboutTheKeyframeRotationFirst) {
  // A 2 deg turn about the keyframe's own vertical: no displacement of the keyframe, whatever its distance from W's
  // origin - the order and pivot of registration's correction_xi and of LocalMap.T_WB_covariance.
  const Eigen::Vector3d p_WB(100.0, -60.0, 30.0);
  const Eigen::Isometry3d turn = Eigen::Translation3d(p_WB) * Eigen::AngleAxisd(2.0 * kDeg, Eigen::Vector3d::UnitZ()) *
                                 Eigen::Translation3d(-p_WB);
  const Eigen::Matrix<double, 6, 1> xi = correction_about(Eigen::Translation3d(0.5, 0.0, 0.0) * turn, p_WB);
  EXPECT_NEAR(xi(2), 2.0 * kDeg, 1e-12);
  EXPECT_NEAR(xi.head<2>().norm(), 0.0, 1e-12);
  EXPECT_NEAR((xi.tail<3>() - Eigen::Vector3d(0.5, 0.0, 0.0)).norm(), 0.0, 1e-12);
}

TEST(RegistrationGate, ACorrectionTwentyMetresOffIsRefusedAndASmallOneFused) {
  const RegistrationGateConfig config;
  EXPECT_EQ(registration_refusal(config, keyframe_with(shift(0.6))), "");  // d^2 = 0.36 / (0.25 + 0.01) = 1.4
  EXPECT_EQ(registration_refusal(config, keyframe_with(shift(20.0))),
            "correction moves the keyframe 20.00 m > registration_gate_max_correction_m 15.00");
  RegistrationGateInput provisional = keyframe_with(shift(20.0));
  provisional.declared = false;  // no size bound yet: the covariance decides, d^2 = 400 / 0.26
  EXPECT_EQ(registration_refusal(config, provisional),
            "correction's Mahalanobis distance^2 1538.5 under the estimator's covariance > "
            "registration_gate_max_mahalanobis_sq 100.0");
}

TEST(RegistrationGate, NeverRefusesWhatRegistrationsOwnDefaultGatePasses) {
  // At registration's bound (d^2 = 22.46, same covariance and floors) the estimator's gate is far away.
  const double at_bound_m = std::sqrt(22.46 * 0.26);
  EXPECT_EQ(registration_refusal(RegistrationGateConfig{}, keyframe_with(shift(at_bound_m))), "");
  EXPECT_NE(registration_refusal(RegistrationGateConfig{}, keyframe_with(shift(std::sqrt(101.0 * 0.26)))), "");
}

TEST(RegistrationGate, AReadmittedCorrectionSkipsTheMahalanobisTestButNotTheSizeBound) {
  RegistrationGateInput in = keyframe_with(shift(8.0));
  in.readmitted = true;  // registration's persistence gate: implausible, but found again and again
  EXPECT_EQ(registration_refusal(RegistrationGateConfig{}, in), "");
  in.correction_W = shift(20.0);
  EXPECT_EQ(registration_refusal(RegistrationGateConfig{}, in),
            "correction moves the keyframe 20.00 m > registration_gate_max_correction_m 15.00");
  in.correction_W = Eigen::Translation3d(in.T_WB.translation()) * Eigen::AngleAxisd(20.0 * kDeg, Eigen::Vector3d::UnitZ()) *
                    Eigen::Translation3d(-in.T_WB.translation());
  EXPECT_EQ(registration_refusal(RegistrationGateConfig{}, in),
            "correction turns the keyframe 20.00 deg > registration_gate_max_correction_deg 15.00");
}

TEST(RegistrationGate, BeforeTheDeclarationLargeCorrectionsAreWhatRegistrationIsFor) {
  RegistrationGateInput in = keyframe_with(shift(20.0));
  in.declared = false;
  in.readmitted = true;  // acquisition: confirmed by registration's votes
  EXPECT_EQ(registration_refusal(RegistrationGateConfig{}, in), "");
  in.readmitted = false;  // not confirmed: still implausible under the published covariance
  EXPECT_NE(registration_refusal(RegistrationGateConfig{}, in), "");
}

TEST(RegistrationGate, WithoutAUsableCovarianceOnlyTheSizeBoundApplies) {
  RegistrationGateInput in = keyframe_with(shift(10.0));
  in.covariance.reset();
  EXPECT_EQ(registration_refusal(RegistrationGateConfig{}, in), "");
  in.covariance = -Matrix6d::Identity();  // not a covariance
  EXPECT_EQ(registration_refusal(RegistrationGateConfig{}, in), "");
  in.covariance = Matrix6d::Constant(NAN);
  EXPECT_EQ(registration_refusal(RegistrationGateConfig{}, in), "");
  in.correction_W = shift(16.0);
  EXPECT_NE(registration_refusal(RegistrationGateConfig{}, in), "");
}

TEST(RegistrationGate, ZeroTurnsEachTestOffAndBadValuesAreNamed) {
  RegistrationGateConfig off;
  off.max_mahalanobis_sq = 0.0;
  off.max_correction_m = 0.0;
  off.max_correction_deg = 0.0;
  EXPECT_EQ(registration_refusal(off, keyframe_with(shift(50.0))), "");
  RegistrationGateConfig bad;
  bad.floor_m = -1.0;
  try {
    bad.validate();
    FAIL() << "accepted a negative floor";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "global fusion: registration_gate_floor_m must be >= 0");
  }
  bad.floor_m = 0.1;
  bad.max_mahalanobis_sq = NAN;
  EXPECT_THROW(bad.validate(), InputError);
}

}  // namespace
}  // namespace twinslam::estimator

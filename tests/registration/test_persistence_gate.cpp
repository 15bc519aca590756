// PersistenceGate: a correction the Mahalanobis gate refuses from keyframes a landmark horizon apart is let in; too few
// agreeing refusals, a short span, disagreeing ones or stale ones are not.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include <Eigen/Geometry>

#include "twinslam/registration/persistence_gate.hpp"

namespace twinslam::registration {
namespace {

RegistrationResult refused(double dx_m, double dyaw_deg = 0.0) {
  RegistrationResult r;
  r.status = RegistrationStatus::kCorrectionTooLarge;
  r.reason = "correction's Mahalanobis distance^2 90 > max_mahalanobis_sq 22.46";
  r.correction_xi << 0, 0, dyaw_deg * M_PI / 180.0, dx_m, 0.1, 0;  // about the keyframe at the origin of W
  r.correction_W = Eigen::Translation3d(dx_m, 0.1, 0) * Eigen::AngleAxisd(dyaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ());
  r.details.information = Matrix6d::Identity() * 7.0;
  r.mahalanobis_sq = 90.0;
  return r;
}

std::int64_t at(double t_s) { return static_cast<std::int64_t>(t_s * 1e9); }

RegistrationConfig config(int n, double span_s) {
  RegistrationConfig c;
  c.persistent_corrections = n;
  c.persistent_span_s = span_s;
  return c;
}

TEST(RegistrationPersistenceGate, AgreeingRefusalsOverTheSpanAdmitTheLastWithItsInformation) {
  PersistenceGate gate(config(3, 10.0));
  RegistrationResult a = refused(1.0), b = refused(1.1, 0.3), c = refused(0.95, -0.2), d = refused(1.0);
  EXPECT_FALSE(gate.review(a, at(100)));
  EXPECT_FALSE(gate.review(b, at(105)));
  EXPECT_EQ(b.status, RegistrationStatus::kCorrectionTooLarge);
  EXPECT_TRUE(b.information.isZero());
  EXPECT_FALSE(gate.review(c, at(109.5)));  // three agree, but over 9.5 s: the same landmarks could say it
  EXPECT_TRUE(gate.review(d, at(110)));
  EXPECT_EQ(d.status, RegistrationStatus::kAccepted);
  EXPECT_EQ(d.information, d.details.information);
  EXPECT_NE(d.reason.find("4 of 4 refused keyframes over 10.0 s"), std::string::npos) << d.reason;
  EXPECT_EQ(gate.readmitted(), 1u);
  RegistrationResult e = refused(1.0);  // the run starts over after a re-admission
  EXPECT_FALSE(gate.review(e, at(120)));
}

TEST(RegistrationPersistenceGate, OnlyRefusalsThatAgreeWithTheNewestVote) {
  PersistenceGate gate(config(3, 2.0));
  RegistrationResult a = refused(1.0), b = refused(1.5), c = refused(1.5, 2.0), d = refused(1.5, 2.2),
                     e = refused(1.45, 2.1);
  EXPECT_FALSE(gate.review(a, at(1)));
  EXPECT_FALSE(gate.review(b, at(2)));  // 0.5 m from a
  EXPECT_FALSE(gate.review(c, at(3)));  // 2 deg from b and a
  EXPECT_FALSE(gate.review(d, at(4)));  // c, d: two
  EXPECT_TRUE(gate.review(e, at(5)));   // c, d, e agree
  EXPECT_NE(e.reason.find("3 of 5 refused keyframes over 2.0 s"), std::string::npos) << e.reason;
}

// Measured on city-loops after a wrong heading was declared: ICP from the wrong estimate finds the right correction
// on some keyframes and a wrong one in between, for 100 s. The right one, said often enough over the span, gets in; the
// interleaved wrong one, said less often, does not.
TEST(RegistrationPersistenceGate, ACorrectionInterleavedWithAnotherIsLetInWhenItIsSaidOftenEnough) {
  PersistenceGate gate(config(5, 10.0));
  int admitted_right = 0, admitted_wrong = 0;
  for (int k = 0; k < 14; ++k) {
    const bool right = k % 3 != 1;  // right, wrong, right, right, wrong, right, ...
    RegistrationResult r = right ? refused(3.0, 4.0) : refused(0.8, -1.0);
    if (gate.review(r, at(2.0 * k))) (right ? admitted_right : admitted_wrong)++;
  }
  EXPECT_EQ(admitted_right, 1);
  EXPECT_EQ(admitted_wrong, 0);
}

TEST(RegistrationPersistenceGate, AcceptancesAndOtherRejectionsInBetweenDoNotCount) {
  PersistenceGate gate(config(3, 2.0));
  RegistrationResult a = refused(1.0);
  EXPECT_FALSE(gate.review(a, at(1)));
  RegistrationResult ok;  // e.g. a degenerate cloud accepted with its weak direction zeroed: it could not fix the drift
  ok.status = RegistrationStatus::kAccepted;
  EXPECT_FALSE(gate.review(ok, at(2)));
  EXPECT_EQ(ok.status, RegistrationStatus::kAccepted);
  RegistrationResult degenerate = refused(1.0);
  degenerate.status = RegistrationStatus::kDegenerate;
  EXPECT_FALSE(gate.review(degenerate, at(3)));
  EXPECT_EQ(degenerate.status, RegistrationStatus::kDegenerate);  // never re-admitted: only the gate's refusals
  RegistrationResult b = refused(1.0), c = refused(1.0);
  EXPECT_FALSE(gate.review(b, at(3.5)));
  EXPECT_TRUE(gate.review(c, at(4)));  // a, b, c
}

TEST(RegistrationPersistenceGate, UnconvergedIcpVotesButIsNeverLetIn) {
  PersistenceGate gate(config(3, 2.0));
  RegistrationResult a = refused(1.0), b = refused(1.0), c = refused(1.0), d = refused(1.0);
  b.status = c.status = RegistrationStatus::kNotConverged;
  EXPECT_FALSE(gate.review(a, at(1)));
  EXPECT_FALSE(gate.review(b, at(2)));
  EXPECT_FALSE(gate.review(c, at(3)));  // three agree over 2 s, but this one did not converge
  EXPECT_EQ(c.status, RegistrationStatus::kNotConverged);
  EXPECT_TRUE(gate.review(d, at(3.5)));  // a, b, c, d
  EXPECT_NE(d.reason.find("4 of 4 refused keyframes over 2.5 s"), std::string::npos) << d.reason;
}

TEST(RegistrationPersistenceGate, RefusalsOlderThanTwoSpansAreForgotten) {
  PersistenceGate gate(config(3, 5.0));
  RegistrationResult a = refused(1.0), b = refused(1.0), c = refused(1.0), d = refused(1.0);
  EXPECT_FALSE(gate.review(a, at(0)));
  EXPECT_FALSE(gate.review(b, at(9)));
  EXPECT_FALSE(gate.review(c, at(12)));  // a is 12 s old (> 10 s): b, c span only 3 s
  EXPECT_TRUE(gate.review(d, at(14)));   // b, c, d over 5 s
}

TEST(RegistrationPersistenceGate, LargeCorrectionsAgreeWithinAShareOfThemselves) {
  PersistenceGate gate(config(2, 1.0));  // tolerance: max(0.3 m, 10 % of the newest correction)
  RegistrationResult a = refused(8.0), b = refused(8.7);
  EXPECT_FALSE(gate.review(a, at(1)));
  EXPECT_TRUE(gate.review(b, at(2)));  // 0.7 m apart, within 0.87 m
  RegistrationResult c = refused(2.0), d = refused(2.5);
  EXPECT_FALSE(gate.review(c, at(3)));
  EXPECT_FALSE(gate.review(d, at(4)));  // 0.5 m apart, beyond max(0.3, 0.25) m
}

// An estimate whose heading is 4 deg off about W's origin, seen from keyframes flying around a tower 30 m from it: each
// registration finds the same dT of W, but its correction about the keyframe changes by metres along the circle.
RegistrationResult refused_heading(double yaw_error_deg, double along_circle_rad) {
  RegistrationResult r;
  r.status = RegistrationStatus::kCorrectionTooLarge;
  r.pivot_W = Eigen::Vector3d(30.0 * std::cos(along_circle_rad), 30.0 * std::sin(along_circle_rad), 10.0);
  r.correction_W = Eigen::Isometry3d(Eigen::AngleAxisd(yaw_error_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()));
  // About the pivot c: dR and dp = dT(c) - c (icp.hpp).
  r.correction_xi << 0, 0, yaw_error_deg * M_PI / 180.0, r.correction_W * r.pivot_W - r.pivot_W;
  r.details.information = Matrix6d::Identity();
  return r;
}

TEST(RegistrationPersistenceGate, AWholeFrameHeadingErrorAgreesFromKeyframesAroundTheCircle) {
  PersistenceGate gate(config(5, 10.0));
  for (int k = 0; k < 10; ++k) {  // a keyframe a second, 1.7 m apart on the circle (0.057 rad)
    RegistrationResult r = refused_heading(4.0, 0.057 * k);
    EXPECT_FALSE(gate.review(r, at(k)));
  }
  const RegistrationResult first = refused_heading(4.0, 0.0), last = refused_heading(4.0, 0.057 * 10);
  ASSERT_GT((first.correction_xi.tail<3>() - last.correction_xi.tail<3>()).norm(), 1.0);  // about the keyframes
  RegistrationResult r = refused_heading(4.0, 0.057 * 10);
  EXPECT_TRUE(gate.review(r, at(10)));  // the same dT of W for 10 s
  // A heading error that changes by 2 deg between keyframes is not one correction.
  PersistenceGate other(config(3, 2.0));
  for (int k = 0; k < 6; ++k) {
    RegistrationResult s = refused_heading(4.0 + 2.0 * k, 0.057 * k);
    EXPECT_FALSE(other.review(s, at(k)));
  }
}

RegistrationResult accepted(double dx_m, double dyaw_deg = 0.0) {
  RegistrationResult r = refused(dx_m, dyaw_deg);
  r.status = RegistrationStatus::kAccepted;
  r.reason.clear();
  r.information = r.details.information;
  return r;
}

// While the estimator's heading is uncertain (a GNSS start in a canyon), one search can end in a wrong basin that no
// other keyframe confirms: a large accepted correction waits for the votes; a small one, or any once the heading is
// known, goes through at once.
TEST(RegistrationPersistenceGate, WhileAcquiringALargeCorrectionWaitsForConfirmation) {
  PersistenceGate gate(config(3, 4.0));
  RegistrationResult wrong = accepted(4.5, -3.8);
  EXPECT_FALSE(gate.review(wrong, at(25), 15.0));
  EXPECT_EQ(wrong.status, RegistrationStatus::kCorrectionTooLarge);
  EXPECT_TRUE(wrong.information.isZero());
  EXPECT_NE(wrong.reason.find("unconfirmed"), std::string::npos) << wrong.reason;
  // The right correction, found again and again as the cloud changes, with a heading-ambiguous result voting for it.
  RegistrationResult a = accepted(8.0, 3.0), b = refused(8.1, 3.1), c = accepted(7.9, 3.05);
  b.status = RegistrationStatus::kDegenerate;
  b.heading_ambiguous = true;
  EXPECT_FALSE(gate.review(a, at(26), 15.0));
  EXPECT_FALSE(gate.review(b, at(28), 12.0));
  EXPECT_EQ(b.status, RegistrationStatus::kDegenerate);  // votes, never admitted itself
  EXPECT_TRUE(gate.review(c, at(30), 12.0));              // a, b, c over 4 s
  EXPECT_EQ(c.status, RegistrationStatus::kAccepted);
  EXPECT_EQ(c.information, c.details.information);
  // Small corrections, and large ones once the heading sigma is below acquisition_heading_sigma_deg (3 deg), pass.
  RegistrationResult small = accepted(0.4, 0.3), sure = accepted(4.5, -3.8), unknown = accepted(4.5, -3.8);
  EXPECT_FALSE(gate.review(small, at(31), 15.0));
  EXPECT_FALSE(gate.review(sure, at(32), 2.0));
  EXPECT_FALSE(gate.review(unknown, at(33)));  // no covariance sent: nothing to judge by
  EXPECT_EQ(small.status, RegistrationStatus::kAccepted);
  EXPECT_EQ(sure.status, RegistrationStatus::kAccepted);
  EXPECT_EQ(unknown.status, RegistrationStatus::kAccepted);
  RegistrationConfig off = config(3, 4.0);
  off.acquisition_heading_sigma_deg = 0.0;
  PersistenceGate no_acquisition(off);
  RegistrationResult d = accepted(4.5, -3.8);
  EXPECT_FALSE(no_acquisition.review(d, at(1), 15.0));
  EXPECT_EQ(d.status, RegistrationStatus::kAccepted);
}

TEST(RegistrationPersistenceGate, ZeroTurnsItOff) {
  PersistenceGate gate(config(0, 0.0));
  for (int i = 0; i < 10; ++i) {
    RegistrationResult r = refused(1.0);
    EXPECT_FALSE(gate.review(r, at(10.0 * i)));
    EXPECT_EQ(r.status, RegistrationStatus::kCorrectionTooLarge);
  }
}

}  // namespace
}  // namespace twinslam::registration

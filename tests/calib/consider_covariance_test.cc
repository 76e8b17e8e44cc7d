#include "splinecal/calib/consider_covariance.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "calib/consider_test_helpers.h"
#include "splinecal/calib/calibrate.h"
#include "splinecal/error.h"

namespace splinecal {
namespace {

// A linear Gaussian problem y = A_t theta + A_c c + A_n n + e, e ~ N(0, I): theta the estimated
// parameters, c the considered ones, n nuisance. Every covariance below is exact (linear maps of
// e), so the consider formula is checked to rounding (1e-9 relative: the matrices are O(1) and
// well conditioned, their condition numbers below 1e3).
struct LinearProblem {
  static constexpr int kRows = 30, kTheta = 3, kC = 2, kN = 2, kCornerRows = 12;
  Eigen::MatrixXd A_t, A_c, A_n;
  explicit LinearProblem(unsigned seed) {
    std::mt19937 engine(seed);
    std::normal_distribution<double> normal;
    auto random = [&](int rows, int cols) {
      return Eigen::MatrixXd(
          Eigen::MatrixXd::NullaryExpr(rows, cols, [&]() { return normal(engine); }));
    };
    A_t = random(kRows, kTheta);
    A_c = random(kRows, kC);
    A_n = random(kRows, kN);
  }
  // The estimate of theta with c held: theta_hat = K (y - A_c c_0), K the theta rows of
  // [A_t A_n]'s least-squares solution.
  Eigen::MatrixXd K() const {
    Eigen::MatrixXd B(kRows, kTheta + kN);
    B << A_t, A_n;
    return (B.transpose() * B).ldlt().solve(B.transpose()).topRows(kTheta);
  }
  // The joint covariance of [theta; c] with c free and no prior (n marginalised).
  Eigen::MatrixXd Joint() const {
    Eigen::MatrixXd M(kRows, kTheta + kC + kN);
    M << A_t, A_c, A_n;
    const Eigen::MatrixXd P = (M.transpose() * M).inverse();
    return P.topLeftCorner(kTheta + kC, kTheta + kC);
  }
};

double RelativeDifference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).norm() / b.norm();
}

// S from the joint covariance is d theta_hat / d c of the held estimate (theta_hat(c) =
// K (y - A_c c): S = -K A_c, the exact finite difference of a linear map), and Sigma_theta|c +
// S Sigma_c S^T is the exact covariance of the held estimate when c_0 is off the truth by an
// independent error of covariance Sigma_c.
TEST(ConsiderCovariance, SensitivityIsTheHeldEstimatesDerivativeAndTheCovarianceExact) {
  const LinearProblem p(7);
  const Eigen::MatrixXd K = p.K();
  const std::optional<Eigen::MatrixXd> S = ConsiderSensitivity(p.Joint(), LinearProblem::kC);
  ASSERT_TRUE(S.has_value());
  EXPECT_LT(RelativeDifference(*S, -K * p.A_c), 1e-9);
  // The theta block of the joint covariance conditioned on c is the held problem's, K K^T.
  const Eigen::MatrixXd joint = p.Joint();
  const Eigen::MatrixXd conditional =
      joint.topLeftCorner(3, 3) - *S * joint.bottomRightCorner(2, 2) * S->transpose();
  EXPECT_LT(RelativeDifference(conditional, K * K.transpose()), 1e-9);
  Eigen::Matrix2d Sigma_c;
  Sigma_c << 0.8, 0.3, 0.3, 0.5;
  // theta_hat - theta = K e + K A_c (c - c_0).
  const Eigen::MatrixXd exact = K * K.transpose() + (K * p.A_c) * Sigma_c * (K * p.A_c).transpose();
  EXPECT_LT(RelativeDifference(AddConsidered(K * K.transpose(), *S, Sigma_c), exact), 1e-9);
}

// The own chain: c_0 comes from the SAME data (the first kCornerRows rows, the corners, fitted
// with a free pose z in place of theta and n, as the intrinsics step fits a pose per view). Then
// c_0's error is correlated with e, yet the consider formula stays exact: the joint estimate is
// the best linear unbiased one, uncorrelated with its difference to any other unbiased one
// (Hausman 1978), which makes Cov(theta_hat) = P_tt + S (Sigma_c - P_cc) S^T, the formula's value.
// A prior at c_0 with covariance Sigma_c (ParameterMode::kPrior) counts those rows twice: its
// reported covariance is below the exact one.
TEST(ConsiderCovariance, ExactWhenTheConsideredValuesComeFromTheSameData) {
  const LinearProblem p(11);
  constexpr int kR = LinearProblem::kCornerRows;
  Eigen::MatrixXd M_R(kR, LinearProblem::kC + LinearProblem::kTheta + LinearProblem::kN);
  M_R << p.A_c.topRows(kR), p.A_t.topRows(kR), p.A_n.topRows(kR);
  const Eigen::MatrixXd info_R = M_R.transpose() * M_R;
  const Eigen::MatrixXd L_c = info_R.ldlt().solve(M_R.transpose()).topRows(LinearProblem::kC);
  const Eigen::MatrixXd Sigma_c = info_R.inverse().topLeftCorner(2, 2);  // c_0 - c = L_c e_R
  const Eigen::MatrixXd K = p.K();
  // theta_hat - theta = K e - K A_c L_c e_R.
  Eigen::MatrixXd G = K;
  G.leftCols(kR) -= K * p.A_c * L_c;
  const Eigen::MatrixXd exact = G * G.transpose();
  const std::optional<Eigen::MatrixXd> S = ConsiderSensitivity(p.Joint(), LinearProblem::kC);
  ASSERT_TRUE(S.has_value());
  const Eigen::MatrixXd consider = AddConsidered(K * K.transpose(), *S, Sigma_c);
  EXPECT_LT(RelativeDifference(consider, exact), 1e-9);
  // The prior's posterior: the joint information plus Sigma_c^-1 on c.
  Eigen::MatrixXd M(LinearProblem::kRows, 7);
  M << p.A_t, p.A_c, p.A_n;
  Eigen::MatrixXd H = M.transpose() * M;
  H.block(3, 3, 2, 2) += Sigma_c.inverse();
  const Eigen::MatrixXd prior = H.inverse().topLeftCorner(3, 3);
  for (int i = 0; i < 3; ++i) EXPECT_LT(prior(i, i), exact(i, i)) << "component " << i;
}

TEST(ConsiderCovariance, RefusesConsideredParametersTheDataDoNotDetermine) {
  Eigen::MatrixXd joint = Eigen::MatrixXd::Identity(4, 4);
  joint(3, 3) = 0.0;
  EXPECT_FALSE(ConsiderSensitivity(joint, 1).has_value());
}

// calibrate with --intrinsics consider: the estimate is the held one, every std of T_cam_imu at
// least the held one's, the intrinsics' std the carried one; consider needs a covariance and is
// not a camera-chain mode.
TEST(ConsiderCovariance, CalibrateHoldsTheIntrinsicsAndWidensTheStds) {
  const testing::CalibrationScenario s = testing::ConsiderScenario();
  Eigen::Matrix<double, 8, 1> std;
  std << 1.5, 1.5, 1.5, 1.5, 2e-3, 2e-3, 2e-4, 2e-4;
  const CameraCovariance given = testing::DiagonalRadtanCovariance(std);
  CalibrateOptions options = testing::FastOptions();
  const testing::ConsideredAndHeld runs = testing::CalibrateConsideredAndHeld(s, given, options);
  const CalibrationResult& consider = runs.consider;
  const CalibrationResult& held = runs.held;
  ASSERT_TRUE(consider.covariance_ok);
  ASSERT_TRUE(held.covariance_ok);
  const CameraEstimate& c = consider.cameras[0];
  const CameraEstimate& h = held.cameras[0];
  EXPECT_EQ(c.intrinsics_mode, ParameterMode::kConsider);
  EXPECT_FALSE(c.intrinsics_estimated);
  EXPECT_TRUE(c.calibration.camera.intrinsics() == h.calibration.camera.intrinsics());
  // The same problem solved (the considered block is constant): the same estimate to far below
  // its std (1e-3 of it; the solves differ only by the block's presence in Ceres' ordering).
  const testing::Errors d = testing::ErrorsOf(c.calibration, h.calibration);
  for (int a = 0; a < 3; ++a) {
    EXPECT_LT(std::abs(d.rotation_deg(a)), 1e-3 * h.rotation_std_deg(a)) << "axis " << a;
    EXPECT_LT(std::abs(d.translation_m(a)), 1e-3 * h.translation_std_m(a)) << "axis " << a;
    EXPECT_GE(c.rotation_std_deg(a), h.rotation_std_deg(a)) << "axis " << a;
    EXPECT_GE(c.translation_std_m(a), h.translation_std_m(a)) << "axis " << a;
  }
  // 1.5 px on the focal lengths and principal point of a 458 px camera is 0.19 deg of rotation
  // and 0.3% of the target's distance: far above the held stds (~0.01 deg, ~1 mm).
  EXPECT_GT(c.rotation_std_deg.maxCoeff(), 3.0 * h.rotation_std_deg.maxCoeff());
  for (int j = 0; j < 8; ++j) {
    EXPECT_DOUBLE_EQ(c.intrinsics_std(given.intrinsics[j]), std(j));
    EXPECT_DOUBLE_EQ(c.intrinsics_prior_std(given.intrinsics[j]), std(j));
  }
  std::printf(
      "rotation std held %.4f %.4f %.4f, consider %.4f %.4f %.4f deg; translation std "
      "held %.2f %.2f %.2f, consider %.2f %.2f %.2f mm\n",
      h.rotation_std_deg(0),
      h.rotation_std_deg(1),
      h.rotation_std_deg(2),
      c.rotation_std_deg(0),
      c.rotation_std_deg(1),
      c.rotation_std_deg(2),
      1e3 * h.translation_std_m(0),
      1e3 * h.translation_std_m(1),
      1e3 * h.translation_std_m(2),
      1e3 * c.translation_std_m(0),
      1e3 * c.translation_std_m(1),
      1e3 * c.translation_std_m(2));
  options.camchain_covariances = {given};
  options.intrinsics = ParameterMode::kConsider;
  options.camera_chain = ParameterMode::kConsider;
  EXPECT_THROW(Calibrate(s.imu, s.observations, s.start, &s.target, options), Error);
  options.camera_chain.reset();
  options.camchain_covariances.clear();
  EXPECT_THROW(Calibrate(s.imu, s.observations, s.start, &s.target, options), Error);
}

}  // namespace
}  // namespace splinecal

#include "splinecal/imu/imu_intrinsic_model.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <random>
#include <vector>

#include "spline/spline_test_util.h"
#include "splinecal/imu/imu_model.h"
#include "splinecal/imu/matrix_parameters.h"
#include "splinecal/imu/spline_body_motion.h"
#include "splinecal/lie/so3.h"
#include "splinecal/spline/se3_spline.h"
#include "testing/numeric_diff.h"

namespace splinecal {
namespace {

using testing::RelativelyNear;

// Automatic differentiation is exact up to rounding; the analytic Jacobians evaluate other
// formulas for the same derivatives of O(1..100) outputs: 1e-9 relative to max(1, |J|).
constexpr double kAutoDiffTolerance = 1e-9;
constexpr double kRoundingTolerance = 1e-12;

// The flat input vector the autodiff oracle differentiates: every input of the models.
enum Input {
  kW = 0,         // w_b (3)
  kDw = 3,        // dw_b (3)
  kF = 6,         // f_b (3)
  kPhiIB = 9,     // right perturbation of C_i_b (3)
  kRb = 12,       // r_b (3)
  kMa = 15,       // M_a (6)
  kMg = 21,       // M_g (6)
  kA = 27,        // A (9)
  kPhiGyro = 36,  // right perturbation of C_gyro_i (3)
  kRy = 39,       // ry_i (3)
  kRz = 42,       // rz_i (3)
  kBg = 45,       // b_g (3)
  kBa = 48,       // b_a (3)
  kNumInputs = 51,
};

using Jet = ceres::Jet<double, kNumInputs>;

// Generic (far from nominal) parameters: scale errors of a few percent, misalignments of a few
// degrees, lever arms of centimetres, so that no Jacobian block vanishes by accident.
ImuIntrinsicsd RandomIntrinsics(uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto vec = [&](double scale) -> Eigen::Vector3d {
    return Eigen::Vector3d(u(rng), u(rng), u(rng)) * scale;
  };
  ImuIntrinsicsd p;
  p.C_i_b = SO3d::Exp(vec(1.5)).matrix();
  p.r_b = vec(0.2);
  for (Eigen::Matrix3d* M : {&p.M_a, &p.M_g}) {
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c <= r; ++c) (*M)(r, c) = (r == c ? 1.0 : 0.0) + 0.05 * u(rng);
    }
  }
  for (int k = 0; k < 9; ++k) p.A(k / 3, k % 3) = 1e-3 * u(rng);
  p.C_gyro_i = SO3d::Exp(vec(0.05)).matrix();
  p.ry_i = vec(0.02);
  p.rz_i = vec(0.02);
  return p;
}

BodyMotion<double> RandomMotion(uint32_t seed) {
  std::mt19937 rng(seed + 1000);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  BodyMotion<double> m;
  m.w_b = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 3.0;
  m.dw_b = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 20.0;
  m.f_b = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 5.0 + Eigen::Vector3d(0, 0, 9.81);
  return m;
}

const Eigen::Vector3d kGyroBias(0.01, -0.02, 0.005);
const Eigen::Vector3d kAccelBias(-0.1, 0.05, 0.2);

// The models' readings [gyro; accel] as a function of the flat input x (rotations at p0
// perturbed on the right), in Jets: the oracle for every analytic Jacobian.
Eigen::Matrix<double, 6, kNumInputs> AutoDiffJacobian(ImuModelKind kind,
                                                      const ImuIntrinsicsd& p0,
                                                      const BodyMotion<double>& m0) {
  Eigen::Matrix<double, kNumInputs, 1> x0 = Eigen::Matrix<double, kNumInputs, 1>::Zero();
  x0.segment<3>(kW) = m0.w_b;
  x0.segment<3>(kDw) = m0.dw_b;
  x0.segment<3>(kF) = m0.f_b;
  x0.segment<3>(kRb) = p0.r_b;
  LowerTriangularToParameters(p0.M_a, x0.data() + kMa);
  LowerTriangularToParameters(p0.M_g, x0.data() + kMg);
  FullMatrixToParameters(p0.A, x0.data() + kA);
  x0.segment<3>(kRy) = p0.ry_i;
  x0.segment<3>(kRz) = p0.rz_i;
  x0.segment<3>(kBg) = kGyroBias;
  x0.segment<3>(kBa) = kAccelBias;
  Eigen::Matrix<Jet, kNumInputs, 1> x;
  for (int k = 0; k < kNumInputs; ++k) x(k) = Jet(x0(k), k);

  BodyMotion<Jet> m;
  m.w_b = x.segment<3>(kW);
  m.dw_b = x.segment<3>(kDw);
  m.f_b = x.segment<3>(kF);
  ImuIntrinsics<Jet> p = p0.cast<Jet>();
  p.C_i_b = p.C_i_b * SO3<Jet>::Exp(x.segment<3>(kPhiIB)).matrix();
  p.C_gyro_i = p.C_gyro_i * SO3<Jet>::Exp(x.segment<3>(kPhiGyro)).matrix();
  p.r_b = x.segment<3>(kRb);
  p.M_a = LowerTriangularFromParameters(x.data() + kMa);
  p.M_g = LowerTriangularFromParameters(x.data() + kMg);
  p.A = FullMatrixFromParameters(x.data() + kA);
  p.ry_i = x.segment<3>(kRy);
  p.rz_i = x.segment<3>(kRz);
  Vector3<Jet> gyro, accel;
  const Vector3<Jet> b_g = x.segment<3>(kBg);
  const Vector3<Jet> b_a = x.segment<3>(kBa);
  PredictImuReadings(kind, p, m, b_g, b_a, &gyro, &accel);
  Eigen::Matrix<double, 6, kNumInputs> J;
  for (int r = 0; r < 3; ++r) {
    J.row(r) = gyro(r).v.transpose();
    J.row(3 + r) = accel(r).v.transpose();
  }
  return J;
}

// The columns both sensors' Jacobians have, into their three rows of the stacked Jacobian: the
// body motion (w, dw, f), the IMU's rotation phi_i_b and its lever arm r_b.
template <typename SensorJacobians, typename Rows>
void SetBodyMotionBlocks(const SensorJacobians& Js, Rows rows) {
  rows.template middleCols<3>(kW) = Js.w_b;
  rows.template middleCols<3>(kDw) = Js.dw_b;
  rows.template middleCols<3>(kF) = Js.f_b;
  rows.template middleCols<3>(kPhiIB) = Js.phi_i_b;
  rows.template middleCols<3>(kRb) = Js.r_b;
}

Eigen::Matrix<double, 6, kNumInputs> AnalyticJacobian(ImuModelKind kind,
                                                      const ImuIntrinsicsd& p,
                                                      const BodyMotion<double>& m) {
  ImuGyroJacobians Jg;
  ImuAccelJacobians Ja;
  PredictImuReadings(kind, p, m, kGyroBias, kAccelBias, nullptr, nullptr, &Jg, &Ja);
  Eigen::Matrix<double, 6, kNumInputs> J = Eigen::Matrix<double, 6, kNumInputs>::Zero();
  SetBodyMotionBlocks(Jg, J.topRows<3>());
  J.block<3, 6>(0, kMg) = Jg.M_g;
  J.block<3, 9>(0, kA) = Jg.A;
  J.block<3, 3>(0, kPhiGyro) = Jg.phi_gyro_i;
  J.block<3, 3>(0, kBg).setIdentity();
  SetBodyMotionBlocks(Ja, J.bottomRows<3>());
  J.block<3, 6>(3, kMa) = Ja.M_a;
  J.block<3, 3>(3, kRy) = Ja.ry_i;
  J.block<3, 3>(3, kRz) = Ja.rz_i;
  J.block<3, 3>(3, kBa).setIdentity();
  return J;
}

class ImuIntrinsicModelJacobians : public ::testing::TestWithParam<ImuModelKind> {};

TEST_P(ImuIntrinsicModelJacobians, MatchAutoDiffForEveryInput) {
  for (uint32_t seed = 0; seed < 5; ++seed) {
    const ImuIntrinsicsd p = RandomIntrinsics(seed);
    const BodyMotion<double> m = RandomMotion(seed);
    const Eigen::Matrix<double, 6, kNumInputs> J_auto = AutoDiffJacobian(GetParam(), p, m);
    const Eigen::Matrix<double, 6, kNumInputs> J = AnalyticJacobian(GetParam(), p, m);
    EXPECT_TRUE(RelativelyNear(J, J_auto, kAutoDiffTolerance)) << "seed " << seed << "\n"
                                                               << J - J_auto;
  }
}

TEST_P(ImuIntrinsicModelJacobians, ValuesMatchTheTemplatedPrediction) {
  const ImuIntrinsicsd p = RandomIntrinsics(7);
  const BodyMotion<double> m = RandomMotion(7);
  Eigen::Vector3d gyro, accel, gyro_t, accel_t;
  ImuGyroJacobians Jg;
  ImuAccelJacobians Ja;
  PredictImuReadings(GetParam(), p, m, kGyroBias, kAccelBias, &gyro, &accel, &Jg, &Ja);
  PredictImuReadings<double>(GetParam(), p, m, kGyroBias, kAccelBias, &gyro_t, &accel_t);
  EXPECT_TRUE(RelativelyNear(gyro, gyro_t, kRoundingTolerance));
  EXPECT_TRUE(RelativelyNear(accel, accel_t, kRoundingTolerance));
}

INSTANTIATE_TEST_SUITE_P(AllModels,
                         ImuIntrinsicModelJacobians,
                         ::testing::Values(ImuModelKind::kCalibrated,
                                           ImuModelKind::kScaleMisalignment,
                                           ImuModelKind::kScaleMisalignmentSizeEffect));

// Equation (1) of rigid_body_point.h against physics: the second time derivative (central
// differences) of a point fixed on the spline's body, rotated into the body.
TEST(SpecificForceAtPoint, EqualsTheSecondDerivativeOfAPointOnTheBody) {
  const SE3Splined spline(testing::RandomControlPoses(8, 3), 0, testing::kTestDtNs);
  const Eigen::Vector3d r_b(0.05, -0.12, 0.3);
  const Eigen::Vector3d g_w = GravityWorld();
  // Step 1e-4 s on a spline with dt = 0.2 s: truncation ~h^2 |p''''| / 12 ~ 1e-7 m/s^2, rounding
  // ~eps |p| / h^2 ~ 1e-8 m/s^2; the accelerations are O(10..100) m/s^2.
  constexpr double kStep = 1e-4;
  constexpr double kTolerance = 1e-6;
  const auto point_w = [&](double t) { return spline.Pose(spline.SegmentAt(t)) * r_b; };
  for (double t : {0.25, 0.33, 0.61, 0.9}) {
    const Eigen::Vector3d a_point_w =
        (point_w(t + kStep) - 2.0 * point_w(t) + point_w(t - kStep)) / (kStep * kStep);
    const Eigen::Matrix3d R_w_b = spline.Pose(spline.SegmentAt(t)).rotationMatrix();
    const Eigen::Vector3d expected = R_w_b.transpose() * (a_point_w - g_w);
    const BodyMotion<double> m = SplineBodyMotion(spline, spline.SegmentAt(t), g_w);
    EXPECT_TRUE(RelativelyNear(SpecificForceAtPoint(m, r_b), expected, kTolerance)) << t;
  }
}

// At nominal parameters every model is imu_model.h's PredictImu, the one-IMU model.
TEST(ImuIntrinsicModel, NominalParametersReduceToPredictImu) {
  const SE3Splined spline(testing::RandomControlPoses(8, 4), 0, testing::kTestDtNs);
  const Segment<double> seg = spline.SegmentAt(0.47);
  const BodyMotion<double> m = SplineBodyMotion(spline, seg, GravityWorld());
  Eigen::Vector3d gyro_ref, accel_ref;
  PredictImu(spline, seg, GravityWorld(), kGyroBias, kAccelBias, &gyro_ref, &accel_ref);
  for (ImuModelKind kind : {ImuModelKind::kCalibrated,
                            ImuModelKind::kScaleMisalignment,
                            ImuModelKind::kScaleMisalignmentSizeEffect}) {
    Eigen::Vector3d gyro, accel;
    PredictImuReadings(
        kind, ImuIntrinsicsd(), m, kGyroBias, kAccelBias, &gyro, &accel, nullptr, nullptr);
    EXPECT_TRUE(RelativelyNear(gyro, gyro_ref, kRoundingTolerance)) << ImuModelName(kind);
    EXPECT_TRUE(RelativelyNear(accel, accel_ref, kRoundingTolerance)) << ImuModelName(kind);
  }
}

// Each model reads only its own parameters: scale-misalignment ignores the lever arms of the
// axes, calibrated also M_a, M_g, A and C_gyro_i.
TEST(ImuIntrinsicModel, ModelsIgnoreTheParametersTheyDoNotHave) {
  const ImuIntrinsicsd p = RandomIntrinsics(11);
  const BodyMotion<double> m = RandomMotion(11);
  ImuIntrinsicsd calibrated_only;
  calibrated_only.C_i_b = p.C_i_b;
  calibrated_only.r_b = p.r_b;
  ImuIntrinsicsd no_arms = p;
  no_arms.ry_i.setZero();
  no_arms.rz_i.setZero();
  const auto readings = [&](ImuModelKind kind, const ImuIntrinsicsd& q) {
    Eigen::Matrix<double, 6, 1> out;
    Eigen::Vector3d gyro, accel;
    PredictImuReadings(kind, q, m, kGyroBias, kAccelBias, &gyro, &accel, nullptr, nullptr);
    out << gyro, accel;
    return out;
  };
  EXPECT_TRUE(RelativelyNear(readings(ImuModelKind::kCalibrated, p),
                             readings(ImuModelKind::kCalibrated, calibrated_only),
                             kRoundingTolerance));
  EXPECT_TRUE(RelativelyNear(readings(ImuModelKind::kScaleMisalignment, p),
                             readings(ImuModelKind::kScaleMisalignmentSizeEffect, no_arms),
                             kRoundingTolerance));
  // ... and the size effect moves the accelerometer's y and z rows only.
  const Eigen::Matrix<double, 6, 1> diff = readings(ImuModelKind::kScaleMisalignmentSizeEffect, p) -
                                           readings(ImuModelKind::kScaleMisalignment, p);
  EXPECT_LT(diff.head<3>().norm(), kRoundingTolerance);
  EXPECT_GT(diff.tail<3>().norm(), 1e-3);
}

// The size effect against Kalibr's own formulation (IccScaledMisalignedSizeEffectImu): row k is
// row k of C_i_b f_b(r_b + C_i_b^T r_k), each axis at its own point of the body.
TEST(SizeEffect, EachAxisSensesTheSpecificForceAtItsOwnPosition) {
  for (uint32_t seed = 20; seed < 25; ++seed) {
    const ImuIntrinsicsd p = RandomIntrinsics(seed);
    const BodyMotion<double> m = RandomMotion(seed);
    const Eigen::Vector3d r_k_i[3] = {Eigen::Vector3d::Zero(), p.ry_i, p.rz_i};
    Eigen::Vector3d v;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d r_k_b = p.r_b + p.C_i_b.transpose() * r_k_i[k];
      v(k) = (p.C_i_b * SpecificForceAtPoint(m, r_k_b))(k);
    }
    EXPECT_TRUE(RelativelyNear(PredictSizeEffectAccel<double>(p, m, kAccelBias),
                               p.M_a * v + kAccelBias,
                               kRoundingTolerance));
  }
}

TEST(MatrixParameters, LowerTriangularRoundTripsInKalibrsRowMajorOrder) {
  const double m[6] = {1.01, 0.002, 0.99, -0.003, 0.004, 1.02};
  const Eigen::Matrix3d M = LowerTriangularFromParameters(m);
  EXPECT_EQ(M(0, 0), 1.01);
  EXPECT_EQ(M(1, 0), 0.002);
  EXPECT_EQ(M(1, 1), 0.99);
  EXPECT_EQ(M(2, 0), -0.003);
  EXPECT_EQ(M(2, 1), 0.004);
  EXPECT_EQ(M(2, 2), 1.02);
  EXPECT_EQ(M(0, 1), 0.0);
  EXPECT_EQ(M(0, 2), 0.0);
  EXPECT_EQ(M(1, 2), 0.0);
  double back[6];
  LowerTriangularToParameters(M, back);
  for (int k = 0; k < 6; ++k) EXPECT_EQ(back[k], m[k]);
}

}  // namespace
}  // namespace splinecal

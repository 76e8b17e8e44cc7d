// Tests of lie/so3.h: Exp/Log round trips (random and edge angles up to pi - 1e-7), Hat/Vee,
// action and composition, the adjoint identity, the four Jacobians against central differences
// in the RIGHT/LEFT perturbation they document, their relations, continuity across the series
// branch, and ceres::Jet: explicit instantiation plus derivatives of Exp and Log against the
// analytic Jacobians.
#include "splinecal/lie/so3.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <unsupported/Eigen/MatrixFunctions>
#include <vector>

#include "splinecal/units.h"
#include "testing/jet_values.h"
#include "testing/numeric_diff.h"
#include "testing/rotations.h"

// Every member compiled with every scalar (a missing ADL path or a std:: call that blocks Jets
// fails here, not in a user's cost function).
template class splinecal::SO3<double>;
template class splinecal::SO3<ceres::Jet<double, 6>>;

namespace splinecal {
namespace {

using testing::RandomQuaternion;
using testing::Value;
using testing::Values;

using Jet6 = ceres::Jet<double, 6>;
using Jet3 = ceres::Jet<double, 3>;

// Exp and Log are a handful of flops plus sin/cos/atan2, each within an ulp or two: round trips
// hold to a few hundred eps.
constexpr double kExactTolerance = 1e-13;
// Central differences with step kDefaultCentralDifferenceStep = 1e-5 carry ~1e-10 absolute error
// (truncation h^2/6 f''' plus rounding eps/h); 1e-8 leaves a margin of 100.
constexpr double kNumericTolerance = 1e-8;
// Products of Jacobians (J J^-1 = I) at angles up to pi: entries O(1), ~10 flops each.
constexpr double kIdentityTolerance = 1e-13;
// Across a series switch the argument moves by ~2e-15 (relative 1e-12 of 1e-3 rad), so smooth
// functions with O(1) slope move by ~2e-15; a truncated series would show up as a larger jump.
constexpr double kContinuityTolerance = 1e-14;
// Relative offset of the arguments on either side of a series switch.
constexpr double kSwitchOffset = 1e-12;

// Angles [rad] at which every property is checked: zero, tiny, around the series switch, generic,
// large, and just below pi.
const std::vector<double>& EdgeAngles() {
  static const std::vector<double> angles = {0.0,
                                             1e-9,
                                             1e-6,
                                             1e-3 * (1.0 - 1e-9),
                                             1e-3 * (1.0 + 1e-9),
                                             0.3,
                                             1.0,
                                             2.5,
                                             kPi - 1e-6,
                                             kPi - 1e-7};
  return angles;
}

const std::vector<Eigen::Vector3d>& Axes() {
  static const std::vector<Eigen::Vector3d> axes = {Eigen::Vector3d::UnitX(),
                                                    Eigen::Vector3d::UnitZ(),
                                                    Eigen::Vector3d(1.0, -2.0, 0.5).normalized(),
                                                    Eigen::Vector3d(-0.3, 0.1, 0.9).normalized()};
  return axes;
}

std::vector<Eigen::Vector3d> EdgeRotationVectors() {
  std::vector<Eigen::Vector3d> out;
  for (const double angle : EdgeAngles()) {
    for (const Eigen::Vector3d& axis : Axes()) out.push_back(angle * axis);
  }
  return out;
}

// Random rotation vectors with angle uniform in [0, max_angle) and a uniform random axis.
std::vector<Eigen::Vector3d> RandomRotationVectors(int count, double max_angle, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0.0, max_angle);
  std::vector<Eigen::Vector3d> out;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d axis =
        Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
    out.push_back(uniform(rng) * axis);
  }
  return out;
}

// q and -q are the same rotation.
double QuaternionDistance(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return std::min((a.coeffs() - b.coeffs()).norm(), (a.coeffs() + b.coeffs()).norm());
}

TEST(SO3, DefaultIsIdentity) {
  EXPECT_TRUE(SO3d().matrix().isIdentity(0.0));
  EXPECT_EQ(SO3d().Log(), Eigen::Vector3d::Zero());
}

TEST(SO3, LogOfExpIsIdentityOnEdgeAngles) {
  for (const Eigen::Vector3d& phi : EdgeRotationVectors()) {
    EXPECT_LT((SO3d::Exp(phi).Log() - phi).norm(), kExactTolerance) << phi.transpose();
  }
}

TEST(SO3, LogOfExpIsIdentityOnRandomVectors) {
  for (const Eigen::Vector3d& phi : RandomRotationVectors(1000, kPi, 1)) {
    EXPECT_LT((SO3d::Exp(phi).Log() - phi).norm(), kExactTolerance) << phi.transpose();
  }
}

TEST(SO3, ExpOfLogIsIdentityOnRandomQuaternions) {
  std::mt19937 rng(2);
  for (int i = 0; i < 1000; ++i) {
    const SO3d r(RandomQuaternion(&rng));
    const Eigen::Vector3d phi = r.Log();
    EXPECT_LE(phi.norm(), kPi);
    EXPECT_LT(QuaternionDistance(SO3d::Exp(phi).quaternion(), r.quaternion()), kExactTolerance);
  }
}

TEST(SO3, ExpMatchesMatrixExponential) {
  for (const Eigen::Vector3d& phi : EdgeRotationVectors()) {
    const Eigen::Matrix3d expected = Hat(phi).exp();
    EXPECT_LT((SO3d::Exp(phi).matrix() - expected).norm(), kExactTolerance) << phi.transpose();
  }
}

TEST(SO3, ExpWrapsAnglesBeyondPi) {
  const Eigen::Vector3d axis = Eigen::Vector3d(1.0, 2.0, -1.0).normalized();
  const SO3d r = SO3d::Exp((kPi + 0.5) * axis);
  EXPECT_LT((r.Log() - (-(kPi - 0.5) * axis)).norm(), kExactTolerance);
}

TEST(SO3, LogNearPiFromQuaternionWithTinyW) {
  // w = 1e-12: angle 2 acos(1e-12) = pi - 2e-12.
  const double w = 1e-12;
  const Eigen::Vector3d axis = Eigen::Vector3d(0.2, -0.7, 0.4).normalized();
  const Eigen::Vector3d v = std::sqrt(1.0 - w * w) * axis;
  const Eigen::Quaterniond q(w, v.x(), v.y(), v.z());
  const Eigen::Vector3d phi = SO3d(q).Log();
  EXPECT_NEAR(phi.norm(), kPi - 2e-12, kExactTolerance);
  EXPECT_LT((phi.normalized() - axis).norm(), kExactTolerance);
  EXPECT_LT(QuaternionDistance(SO3d::Exp(phi).quaternion(), q), kExactTolerance);

  // -q is the same rotation: same phi (folded onto w >= 0).
  const Eigen::Quaterniond minus_q(-q.coeffs());
  EXPECT_LT((SO3d(minus_q).Log() - phi).norm(), kExactTolerance);
}

TEST(SO3, LogAtExactlyPi) {
  const Eigen::Vector3d axis = Eigen::Vector3d(1.0, 1.0, 0.0).normalized();
  const SO3d r(Eigen::Quaterniond(0.0, axis.x(), axis.y(), axis.z()));
  const Eigen::Vector3d phi = r.Log();
  EXPECT_NEAR(phi.norm(), kPi, kExactTolerance);
  EXPECT_LT((SO3d::Exp(phi).matrix() - r.matrix()).norm(), kExactTolerance);
  EXPECT_LT((SO3d::Exp(-phi).matrix() - r.matrix()).norm(), kExactTolerance);
}

TEST(SO3, LogOfTinyRotationIsExact) {
  // 1e-9 rad about z: q = (cos 5e-10, 0, 0, sin 5e-10).
  const SO3d r(Eigen::Quaterniond(std::cos(5e-10), 0.0, 0.0, std::sin(5e-10)));
  EXPECT_NEAR(r.Log().z(), 1e-9, 1e-24);
}

TEST(SO3, HatVeeRoundTripAndCrossProduct) {
  const Eigen::Vector3d v(0.3, -1.2, 2.0);
  const Eigen::Vector3d p(-0.5, 0.25, 4.0);
  EXPECT_EQ(Vee(Hat(v)), v);
  EXPECT_LT((Hat(v) * p - v.cross(p)).norm(), kExactTolerance);
  EXPECT_TRUE((Hat(v) + Hat(v).transpose()).isZero(0.0));
}

TEST(SO3, ActionCompositionAndInverseMatchMatrices) {
  std::mt19937 rng(3);
  for (int i = 0; i < 100; ++i) {
    const SO3d a(RandomQuaternion(&rng));
    const SO3d b(RandomQuaternion(&rng));
    const Eigen::Vector3d p(1.0, -2.0, 3.0);
    EXPECT_LT((a * p - a.matrix() * p).norm(), kExactTolerance);
    EXPECT_LT(((a * b).matrix() - a.matrix() * b.matrix()).norm(), kExactTolerance);
    EXPECT_LT((a.inverse().matrix() - a.matrix().transpose()).norm(), kExactTolerance);
    EXPECT_LT((a.inverse() * a).Log().norm(), kExactTolerance);
    EXPECT_LT((a.matrix().determinant() - 1.0), kExactTolerance);
  }
}

TEST(SO3, FromMatrixAndFromQuaternionNormalise) {
  std::mt19937 rng(4);
  const SO3d r(RandomQuaternion(&rng));
  EXPECT_LT(QuaternionDistance(SO3d::FromMatrix(r.matrix()).quaternion(), r.quaternion()),
            kExactTolerance);
  const Eigen::Quaterniond scaled(3.0 * r.quaternion().coeffs());
  EXPECT_LT(QuaternionDistance(SO3d::FromQuaternion(scaled).quaternion(), r.quaternion()),
            kExactTolerance);
}

TEST(SO3, AdjointConjugatesExp) {
  // Exp(Adj phi) = R Exp(phi) R^-1.
  std::mt19937 rng(5);
  for (const Eigen::Vector3d& phi : RandomRotationVectors(100, kPi, 6)) {
    const SO3d r(RandomQuaternion(&rng));
    const SO3d lhs = SO3d::Exp(r.Adj() * phi);
    const SO3d rhs = r * SO3d::Exp(phi) * r.inverse();
    EXPECT_LT((lhs.matrix() - rhs.matrix()).norm(), kExactTolerance);
  }
}

TEST(SO3, CastToJetKeepsValue) {
  const SO3d r = SO3d::Exp(Eigen::Vector3d(0.1, 0.2, -0.3));
  const SO3<Jet6> r_jet = r.cast<Jet6>();
  EXPECT_LT((Values(r_jet.matrix()) - r.matrix()).norm(), kExactTolerance);
  EXPECT_TRUE(r_jet.quaternion().w().v.isZero(0.0));
}

std::vector<Eigen::Vector3d> JacobianTestVectors() {
  std::vector<Eigen::Vector3d> out = EdgeRotationVectors();
  for (const Eigen::Vector3d& phi : RandomRotationVectors(50, kPi, 7)) out.push_back(phi);
  return out;
}

TEST(SO3, RightJacobianMatchesCentralDifference) {
  // Jr(phi) d ~ Log(Exp(phi)^-1 Exp(phi + d)).
  for (const Eigen::Vector3d& phi : JacobianTestVectors()) {
    const SO3d r_inv = SO3d::Exp(phi).inverse();
    const Eigen::Matrix3d numeric = testing::CentralDifferenceJacobian(
        [&](const Eigen::Vector3d& p) -> Eigen::Vector3d { return (r_inv * SO3d::Exp(p)).Log(); },
        phi);
    EXPECT_LT((RightJacobianSO3(phi) - numeric).norm(), kNumericTolerance) << phi.transpose();
  }
}

TEST(SO3, LeftJacobianMatchesCentralDifference) {
  // Jl(phi) d ~ Log(Exp(phi + d) Exp(phi)^-1).
  for (const Eigen::Vector3d& phi : JacobianTestVectors()) {
    const SO3d r_inv = SO3d::Exp(phi).inverse();
    const Eigen::Matrix3d numeric = testing::CentralDifferenceJacobian(
        [&](const Eigen::Vector3d& p) -> Eigen::Vector3d { return (SO3d::Exp(p) * r_inv).Log(); },
        phi);
    EXPECT_LT((LeftJacobianSO3(phi) - numeric).norm(), kNumericTolerance) << phi.transpose();
  }
}

TEST(SO3, InverseJacobiansMatchCentralDifference) {
  // Log(Exp(phi) Exp(d)) ~ phi + Jr^-1 d and Log(Exp(d) Exp(phi)) ~ phi + Jl^-1 d. Only for
  // |phi| <= 3 rad: with |phi| closer to pi the perturbed Log would wrap to the other side.
  for (const Eigen::Vector3d& phi : RandomRotationVectors(100, 3.0, 8)) {
    const SO3d r = SO3d::Exp(phi);
    const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
    const Eigen::Matrix3d right = testing::CentralDifferenceJacobian(
        [&](const Eigen::Vector3d& d) -> Eigen::Vector3d { return (r * SO3d::Exp(d)).Log(); },
        zero);
    const Eigen::Matrix3d left = testing::CentralDifferenceJacobian(
        [&](const Eigen::Vector3d& d) -> Eigen::Vector3d { return (SO3d::Exp(d) * r).Log(); },
        zero);
    EXPECT_LT((RightJacobianInverseSO3(phi) - right).norm(), kNumericTolerance);
    EXPECT_LT((LeftJacobianInverseSO3(phi) - left).norm(), kNumericTolerance);
  }
}

TEST(SO3, JacobianRelations) {
  for (const Eigen::Vector3d& phi : JacobianTestVectors()) {
    const Eigen::Matrix3d jr = RightJacobianSO3(phi);
    const Eigen::Matrix3d jl = LeftJacobianSO3(phi);
    EXPECT_LT((jl - jr.transpose()).norm(), kIdentityTolerance);
    EXPECT_LT((jr - LeftJacobianSO3(Eigen::Vector3d(-phi))).norm(), kIdentityTolerance);
    EXPECT_LT((jr * RightJacobianInverseSO3(phi) - Eigen::Matrix3d::Identity()).norm(),
              kIdentityTolerance);
    EXPECT_LT((jl * LeftJacobianInverseSO3(phi) - Eigen::Matrix3d::Identity()).norm(),
              kIdentityTolerance);
    // Jl = R Jr (Jl(phi) = Exp(phi) Jr(phi)).
    EXPECT_LT((jl - SO3d::Exp(phi).matrix() * jr).norm(), kIdentityTolerance);
  }
}

TEST(SO3, SeriesBranchesAreContinuous) {
  // Just below and just above the switch at |phi| = 1e-3 rad.
  const Eigen::Vector3d axis = Eigen::Vector3d(0.6, -0.8, 0.0);
  const Eigen::Vector3d below = 1e-3 * (1.0 - kSwitchOffset) * axis;
  const Eigen::Vector3d above = 1e-3 * (1.0 + kSwitchOffset) * axis;
  EXPECT_LT((SO3d::Exp(below).matrix() - SO3d::Exp(above).matrix()).norm(), kContinuityTolerance);
  EXPECT_LT((RightJacobianSO3(below) - RightJacobianSO3(above)).norm(), kContinuityTolerance);
  EXPECT_LT((RightJacobianInverseSO3(below) - RightJacobianInverseSO3(above)).norm(),
            kContinuityTolerance);
  // Log's switch is at |v| / w = tan(|phi| / 2) = 1e-3.
  const double log_switch = 2.0 * std::atan(1e-3);
  const Eigen::Vector3d log_below = log_switch * (1.0 - kSwitchOffset) * axis;
  const Eigen::Vector3d log_above = log_switch * (1.0 + kSwitchOffset) * axis;
  const SO3d r_below = SO3d::Exp(log_below);
  const SO3d r_above = SO3d::Exp(log_above);
  EXPECT_LT((r_below.Log() - r_above.Log()).norm(), kContinuityTolerance);
  EXPECT_LT((r_below.Log() - log_below).norm(), 1e-18);
  EXPECT_LT((r_above.Log() - log_above).norm(), 1e-18);
}

// --- Typed tests: the same properties with double and ceres::Jet (values of the Jets). ---

template <typename T>
class SO3Typed : public ::testing::Test {};
using Scalars = ::testing::Types<double, Jet6>;
TYPED_TEST_SUITE(SO3Typed, Scalars);

TYPED_TEST(SO3Typed, ExpLogRoundTripOnEdgeAngles) {
  using T = TypeParam;
  for (const Eigen::Vector3d& phi : EdgeRotationVectors()) {
    const Vector3<T> phi_t = phi.cast<T>();
    EXPECT_LT((Values(SO3<T>::Exp(phi_t).Log()) - phi).norm(), kExactTolerance);
  }
}

TYPED_TEST(SO3Typed, JacobiansMatchDouble) {
  using T = TypeParam;
  for (const Eigen::Vector3d& phi : EdgeRotationVectors()) {
    const Vector3<T> phi_t = phi.cast<T>();
    EXPECT_LT((Values(RightJacobianSO3(phi_t)) - RightJacobianSO3(phi)).norm(), 1e-15);
    EXPECT_LT((Values(LeftJacobianInverseSO3(phi_t)) - LeftJacobianInverseSO3(phi)).norm(), 1e-15);
    const Matrix3<T> product = RightJacobianSO3(phi_t) * RightJacobianInverseSO3(phi_t);
    EXPECT_LT((Values(product) - Eigen::Matrix3d::Identity()).norm(), kIdentityTolerance);
  }
}

// --- Jet derivatives against the analytic Jacobians. ---

// phi as a Jet with derivative directions e_0, e_1, e_2.
Vector3<Jet3> JetVector(const Eigen::Vector3d& phi) {
  Vector3<Jet3> out;
  for (int i = 0; i < 3; ++i) out(i) = Jet3(phi(i), i);
  return out;
}

template <int M>
Eigen::Matrix<double, M, 3> JetJacobian(const Eigen::Matrix<Jet3, M, 1>& y) {
  Eigen::Matrix<double, M, 3> j;
  for (int r = 0; r < M; ++r) j.row(r) = y(r).v.transpose();
  return j;
}

// Jets are exact derivatives of the code: agreement to a few eps.
constexpr double kJetTolerance = 1e-14;

TEST(SO3Jet, ExpDerivativeAtZero) {
  // q(phi) = [1 - |phi|^2/8, phi/2]: d vec / d phi = I/2, d w / d phi = 0 (exactly at 0, where
  // the closed form would have sqrt'(0) = inf).
  const SO3<Jet3> r = SO3<Jet3>::Exp(JetVector(Eigen::Vector3d::Zero()));
  EXPECT_LT((JetJacobian<3>(r.quaternion().vec()) - 0.5 * Eigen::Matrix3d::Identity()).norm(),
            kJetTolerance);
  EXPECT_TRUE(r.quaternion().w().v.isZero(0.0));
  // d (Exp(phi) p) / d phi at 0 = -Hat(p).
  const Eigen::Vector3d p(1.0, -2.0, 0.5);
  EXPECT_LT((JetJacobian<3>(r * p.cast<Jet3>()) + Hat(p)).norm(), kJetTolerance);
}

TEST(SO3Jet, ExpDerivativeAtGenericPointsIsRightJacobian) {
  // Exp(phi + d) p ~ Exp(phi) Exp(Jr d) p ~ R p - R Hat(p) Jr d.
  const Eigen::Vector3d p(1.0, -2.0, 0.5);
  const std::vector<Eigen::Vector3d> points = {
      Eigen::Vector3d(0.3, -0.2, 0.5),
      Eigen::Vector3d(1e-9, 0.0, 0.0),
      (kPi - 1e-6) * Eigen::Vector3d(1.0, 2.0, 3.0).normalized()};
  for (const Eigen::Vector3d& phi : points) {
    const SO3<Jet3> r = SO3<Jet3>::Exp(JetVector(phi));
    const Eigen::Matrix3d expected = -SO3d::Exp(phi).matrix() * Hat(p) * RightJacobianSO3(phi);
    EXPECT_LT((JetJacobian<3>(r * p.cast<Jet3>()) - expected).norm(), kJetTolerance)
        << phi.transpose();
  }
}

TEST(SO3Jet, LogDerivativeIsRightJacobianInverse) {
  // d Log(R Exp(d)) / d d at d = 0 = Jr^-1(Log R), including R = identity (series branch of
  // both Exp and Log).
  const std::vector<Eigen::Vector3d> points = {
      Eigen::Vector3d::Zero(),
      Eigen::Vector3d(0.3, -0.2, 0.5),
      (kPi - 1e-3) * Eigen::Vector3d(-1.0, 0.5, 0.2).normalized()};
  for (const Eigen::Vector3d& phi : points) {
    const SO3<Jet3> r = SO3d::Exp(phi).cast<Jet3>();
    const Vector3<Jet3> log = (r * SO3<Jet3>::Exp(JetVector(Eigen::Vector3d::Zero()))).Log();
    EXPECT_LT((JetJacobian<3>(log) - RightJacobianInverseSO3(phi)).norm(), 1e-12)
        << phi.transpose();
  }
}

}  // namespace
}  // namespace splinecal

// Tests of lie/se3.h: Exp/Log round trips (random and edge rotation angles up to pi - 1e-7),
// Exp against the 4x4 matrix exponential, Hat/Vee, action/composition/inverse, the adjoint
// identities, the four SE(3) Jacobians against central differences in the perturbation they
// document, their relations, continuity of the Q-block series, and ceres::Jet: explicit
// instantiation plus Jet derivatives of Exp against the analytic right Jacobian.
#include "splinecal/lie/se3.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <unsupported/Eigen/MatrixFunctions>
#include <vector>

#include "splinecal/units.h"
#include "testing/jet_values.h"
#include "testing/numeric_diff.h"

template class splinecal::SE3<double>;
template class splinecal::SE3<ceres::Jet<double, 6>>;

namespace splinecal {
namespace {

using testing::Value;
using testing::Values;

using Jet6 = ceres::Jet<double, 6>;

// Round trips: a few dozen flops on O(1..10) numbers; translations up to |rho| ~ 10 m.
constexpr double kExactTolerance = 1e-12;
// Central differences with step 1e-5: ~1e-10 absolute error on O(1..10) entries; margin 100.
constexpr double kNumericTolerance = 1e-8;
// Identities between closed-form 6x6 matrices (products of a few 3x3 blocks).
constexpr double kIdentityTolerance = 1e-12;
// Jets are exact derivatives of the code: agreement to a few eps times the entries (~10).
constexpr double kJetTolerance = 1e-13;
// Jet values against the double code path: same formulas, but Eigen vectorises the double
// matrix products and not the Jet ones (different rounding); entries up to ~10.
constexpr double kJetValueTolerance = 1e-13;

const std::vector<double>& EdgeAngles() {
  static const std::vector<double> angles = {0.0,
                                             1e-9,
                                             1e-6,
                                             1e-3,
                                             0.1 * (1.0 - 1e-12),
                                             0.1 * (1.0 + 1e-12),
                                             0.3,
                                             1.0,
                                             2.5,
                                             kPi - 1e-6,
                                             kPi - 1e-7};
  return angles;
}

std::vector<Vector6d> EdgeTwists() {
  const std::vector<Eigen::Vector3d> axes = {Eigen::Vector3d::UnitZ(),
                                             Eigen::Vector3d(1.0, -2.0, 0.5).normalized()};
  const std::vector<Eigen::Vector3d> translations = {
      Eigen::Vector3d::Zero(), Eigen::Vector3d(0.5, -1.0, 2.0), Eigen::Vector3d(-7.0, 3.0, 1.0)};
  std::vector<Vector6d> out;
  for (const double angle : EdgeAngles()) {
    for (const Eigen::Vector3d& axis : axes) {
      for (const Eigen::Vector3d& rho : translations) {
        Vector6d xi;
        xi << rho, angle * axis;
        out.push_back(xi);
      }
    }
  }
  return out;
}

// Random twists: rotation angle uniform in [0, max_angle), rho with N(0, 3^2) entries.
std::vector<Vector6d> RandomTwists(int count, double max_angle, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0.0, max_angle);
  std::vector<Vector6d> out;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d axis =
        Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
    const Eigen::Vector3d rho(3.0 * normal(rng), 3.0 * normal(rng), 3.0 * normal(rng));
    Vector6d xi;
    xi << rho, uniform(rng) * axis;
    out.push_back(xi);
  }
  return out;
}

SE3d RandomPose(std::mt19937* rng) {
  std::normal_distribution<double> normal;
  const Eigen::Quaterniond q =
      Eigen::Quaterniond(normal(*rng), normal(*rng), normal(*rng), normal(*rng)).normalized();
  return SE3d(SO3d(q), Eigen::Vector3d(3.0 * normal(*rng), 3.0 * normal(*rng), 3.0 * normal(*rng)));
}

double PoseDistance(const SE3d& a, const SE3d& b) { return (a.matrix() - b.matrix()).norm(); }

std::vector<Vector6d> JacobianTestTwists() {
  std::vector<Vector6d> out = EdgeTwists();
  for (const Vector6d& xi : RandomTwists(50, kPi, 11)) out.push_back(xi);
  return out;
}

TEST(SE3, DefaultIsIdentity) {
  EXPECT_TRUE(SE3d().matrix().isIdentity(0.0));
  EXPECT_TRUE(SE3d().Log().isZero(0.0));
}

TEST(SE3, LogOfExpIsIdentityOnEdgeTwists) {
  for (const Vector6d& xi : EdgeTwists()) {
    EXPECT_LT((SE3d::Exp(xi).Log() - xi).norm(), kExactTolerance) << xi.transpose();
  }
}

TEST(SE3, LogOfExpIsIdentityOnRandomTwists) {
  for (const Vector6d& xi : RandomTwists(1000, kPi, 12)) {
    EXPECT_LT((SE3d::Exp(xi).Log() - xi).norm(), kExactTolerance) << xi.transpose();
  }
}

TEST(SE3, ExpOfLogIsIdentityOnRandomPoses) {
  std::mt19937 rng(13);
  for (int i = 0; i < 1000; ++i) {
    const SE3d pose = RandomPose(&rng);
    EXPECT_LT(PoseDistance(SE3d::Exp(pose.Log()), pose), kExactTolerance);
  }
}

TEST(SE3, ExpOfLogNearPi) {
  // Rotation quaternion with w = 1e-12 (angle pi - 2e-12) and a generic translation.
  const double w = 1e-12;
  const Eigen::Vector3d axis = Eigen::Vector3d(0.2, -0.7, 0.4).normalized();
  const Eigen::Vector3d v = std::sqrt(1.0 - w * w) * axis;
  const SE3d pose(SO3d(Eigen::Quaterniond(w, v.x(), v.y(), v.z())), Eigen::Vector3d(1.0, 2.0, 3.0));
  const Vector6d xi = pose.Log();
  EXPECT_NEAR(xi.tail<3>().norm(), kPi - 2e-12, kExactTolerance);
  EXPECT_LT(PoseDistance(SE3d::Exp(xi), pose), kExactTolerance);
}

TEST(SE3, ExpMatchesMatrixExponential) {
  for (const Vector6d& xi : EdgeTwists()) {
    const Eigen::Matrix4d expected = Hat(xi).exp();
    EXPECT_LT((SE3d::Exp(xi).matrix() - expected).norm(), kExactTolerance) << xi.transpose();
  }
}

TEST(SE3, HatVeeRoundTrip) {
  Vector6d xi;
  xi << 0.1, -0.2, 0.3, 1.0, 2.0, -3.0;
  EXPECT_EQ(Vee(Hat(xi)), xi);
  EXPECT_EQ(VeeSE3(HatSE3(xi)), xi);
  // Hat(xi) [p; 1] = phi x p + rho.
  const Eigen::Vector3d p(4.0, 5.0, 6.0);
  const Eigen::Vector4d p_h(4.0, 5.0, 6.0, 1.0);
  EXPECT_LT(((Hat(xi) * p_h).head<3>() - (xi.tail<3>().cross(p) + xi.head<3>())).norm(),
            kExactTolerance);
}

TEST(SE3, ActionCompositionAndInverseMatchMatrices) {
  std::mt19937 rng(14);
  for (int i = 0; i < 100; ++i) {
    const SE3d a = RandomPose(&rng);
    const SE3d b = RandomPose(&rng);
    const Eigen::Vector3d p(1.0, -2.0, 3.0);
    EXPECT_LT((a * p - (a.matrix() * p.homogeneous()).head<3>()).norm(), kExactTolerance);
    EXPECT_LT(((a * b).matrix() - a.matrix() * b.matrix()).norm(), kExactTolerance);
    EXPECT_LT((a.inverse().matrix() - a.matrix().inverse()).norm(), kExactTolerance);
    EXPECT_LT((a.inverse() * a).Log().norm(), kExactTolerance);
    EXPECT_LT(PoseDistance(SE3d::FromMatrix(a.matrix()), a), kExactTolerance);
  }
}

TEST(SE3, AdjointConjugatesExp) {
  // Exp(Adj xi) = T Exp(xi) T^-1 and Hat(Adj xi) = T Hat(xi) T^-1.
  std::mt19937 rng(15);
  for (const Vector6d& xi : RandomTwists(100, kPi, 16)) {
    const SE3d pose = RandomPose(&rng);
    const Vector6d adj_xi = pose.Adj() * xi;
    EXPECT_LT(PoseDistance(SE3d::Exp(adj_xi), pose * SE3d::Exp(xi) * pose.inverse()),
              kExactTolerance);
    EXPECT_LT((Hat(adj_xi) - pose.matrix() * Hat(xi) * pose.matrix().inverse()).norm(),
              kExactTolerance);
  }
}

TEST(SE3, AdjointOfProductAndInverse) {
  std::mt19937 rng(17);
  const SE3d a = RandomPose(&rng);
  const SE3d b = RandomPose(&rng);
  EXPECT_LT(((a * b).Adj() - a.Adj() * b.Adj()).norm(), kIdentityTolerance);
  EXPECT_LT((a.inverse().Adj() - a.Adj().inverse()).norm(), kIdentityTolerance);
}

TEST(SE3, RightJacobianMatchesCentralDifference) {
  // Jr(xi) d ~ Log(Exp(xi)^-1 Exp(xi + d)).
  for (const Vector6d& xi : JacobianTestTwists()) {
    const SE3d pose_inv = SE3d::Exp(xi).inverse();
    const Matrix6d numeric = testing::CentralDifferenceJacobian(
        [&](const Vector6d& x) -> Vector6d { return (pose_inv * SE3d::Exp(x)).Log(); }, xi);
    EXPECT_LT((RightJacobianSE3(xi) - numeric).norm(), kNumericTolerance) << xi.transpose();
  }
}

TEST(SE3, LeftJacobianMatchesCentralDifference) {
  // Jl(xi) d ~ Log(Exp(xi + d) Exp(xi)^-1).
  for (const Vector6d& xi : JacobianTestTwists()) {
    const SE3d pose_inv = SE3d::Exp(xi).inverse();
    const Matrix6d numeric = testing::CentralDifferenceJacobian(
        [&](const Vector6d& x) -> Vector6d { return (SE3d::Exp(x) * pose_inv).Log(); }, xi);
    EXPECT_LT((LeftJacobianSE3(xi) - numeric).norm(), kNumericTolerance) << xi.transpose();
  }
}

TEST(SE3, InverseJacobiansMatchCentralDifference) {
  // Log(Exp(xi) Exp(d)) ~ xi + Jr^-1 d, Log(Exp(d) Exp(xi)) ~ xi + Jl^-1 d; |phi| <= 3 rad so
  // that the perturbed Log does not wrap around pi.
  for (const Vector6d& xi : RandomTwists(100, 3.0, 18)) {
    const SE3d pose = SE3d::Exp(xi);
    const Vector6d zero = Vector6d::Zero();
    const Matrix6d right = testing::CentralDifferenceJacobian(
        [&](const Vector6d& d) -> Vector6d { return (pose * SE3d::Exp(d)).Log(); }, zero);
    const Matrix6d left = testing::CentralDifferenceJacobian(
        [&](const Vector6d& d) -> Vector6d { return (SE3d::Exp(d) * pose).Log(); }, zero);
    EXPECT_LT((RightJacobianInverseSE3(xi) - right).norm(), kNumericTolerance);
    EXPECT_LT((LeftJacobianInverseSE3(xi) - left).norm(), kNumericTolerance);
  }
}

TEST(SE3, JacobianRelations) {
  for (const Vector6d& xi : JacobianTestTwists()) {
    const Matrix6d jr = RightJacobianSE3(xi);
    const Matrix6d jl = LeftJacobianSE3(xi);
    const Vector6d minus_xi = -xi;
    EXPECT_LT((jr - LeftJacobianSE3(minus_xi)).norm(), kIdentityTolerance);
    EXPECT_LT((jr * RightJacobianInverseSE3(xi) - Matrix6d::Identity()).norm(), kIdentityTolerance);
    EXPECT_LT((jl * LeftJacobianInverseSE3(xi) - Matrix6d::Identity()).norm(), kIdentityTolerance);
    // Jl(xi) = Adj(Exp(xi)) Jr(xi).
    EXPECT_LT((jl - SE3d::Exp(xi).Adj() * jr).norm(), kIdentityTolerance) << xi.transpose();
  }
}

TEST(SE3, QBlockSeriesIsContinuous) {
  // The two neighbouring doubles around the Q-block series switch (|phi|^2 = 1e-2): the
  // argument moves by ~1e-17, so any jump above rounding means a branch is inaccurate.
  double theta_above = 0.1;
  while (theta_above * theta_above < internal::kSE3QSmallAngleSq) {
    theta_above = std::nextafter(theta_above, 1.0);
  }
  const double theta_below = std::nextafter(theta_above, 0.0);
  ASSERT_LT(theta_below * theta_below, internal::kSE3QSmallAngleSq);
  const Eigen::Vector3d rho(3.0, -1.0, 2.0);
  Vector6d below;
  Vector6d above;
  below << rho, theta_below, 0.0, 0.0;
  above << rho, theta_above, 0.0, 0.0;
  // Entries up to |rho| ~ 4: rounding of a few eps each.
  constexpr double kContinuityTolerance = 1e-14;
  EXPECT_LT((LeftJacobianSE3(below) - LeftJacobianSE3(above)).norm(), kContinuityTolerance);
  EXPECT_LT((RightJacobianInverseSE3(below) - RightJacobianInverseSE3(above)).norm(),
            kContinuityTolerance);
}

TEST(SE3, JacobianCoefficientSeriesMatchHighPrecisionValues) {
  // Below |phi| = 0.1 the coefficients come from series. References: the closed forms evaluated
  // with 50-digit arithmetic (Python mpmath, mp.dps = 50) at t = the double nearest to the
  // listed value, rounded to 20 digits. (Long double is not enough: the closed forms lose
  // eps * 2 / t^4 to cancellation, 6e-13 at t = 0.02.)
  struct Reference {
    double t, a, b, c, c2, c3;
  };
  // clang-format off
  const Reference references[] = {
      {0.02, 0.49998333355555396826, 0.16666333336507918871, 0.083333888894179947091,
       0.041666111115079347443, 0.008333174604497348084},
      {0.05, 0.49989584201350137484, 0.16664583457336964108, 0.083336805762248368045,
       0.041663194599450059329, 0.0083323413215096776607},
      {0.0999, 0.49958430455951569548, 0.16658351967595140654, 0.08334719775282593383,
       0.041652808011645729766, 0.0083293738352228166096},
  };
  // clang-format on
  // A polynomial of degree 4 in t^2 with O(1) coefficients: a few eps.
  constexpr double kSeriesTolerance = 1e-16;
  for (const Reference& r : references) {
    const auto k = internal::ComputeSE3JacobianCoefficients(r.t * r.t);
    EXPECT_NEAR(k.a, r.a, kSeriesTolerance) << r.t;
    EXPECT_NEAR(k.b, r.b, kSeriesTolerance) << r.t;
    EXPECT_NEAR(k.c, r.c, kSeriesTolerance) << r.t;
    EXPECT_NEAR(k.c2, r.c2, kSeriesTolerance) << r.t;
    EXPECT_NEAR(k.c3, r.c3, kSeriesTolerance) << r.t;
  }
}

// --- Typed tests over the scalar. ---

template <typename T>
class SE3Typed : public ::testing::Test {};
using Scalars = ::testing::Types<double, Jet6>;
TYPED_TEST_SUITE(SE3Typed, Scalars);

TYPED_TEST(SE3Typed, ExpLogAndJacobiansMatchDouble) {
  using T = TypeParam;
  for (const Vector6d& xi : EdgeTwists()) {
    const Vector6<T> xi_t = xi.cast<T>();
    EXPECT_LT((Values(SE3<T>::Exp(xi_t).Log()) - xi).norm(), kExactTolerance);
    EXPECT_LT((Values(RightJacobianSE3(xi_t)) - RightJacobianSE3(xi)).norm(), kJetValueTolerance);
    EXPECT_LT((Values(LeftJacobianInverseSE3(xi_t)) - LeftJacobianInverseSE3(xi)).norm(),
              kJetValueTolerance);
    EXPECT_LT((Values(SE3<T>::Exp(xi_t).Adj()) - SE3d::Exp(xi).Adj()).norm(), kJetValueTolerance);
  }
}

// --- Jet derivatives against the analytic right Jacobian. ---

using Jet6Vector = Vector6<Jet6>;

Jet6Vector JetTwist(const Vector6d& xi) {
  Jet6Vector out;
  for (int i = 0; i < 6; ++i) out(i) = Jet6(xi(i), i);
  return out;
}

Eigen::Matrix<double, 3, 6> JetJacobian(const Vector3<Jet6>& y) {
  Eigen::Matrix<double, 3, 6> j;
  for (int r = 0; r < 3; ++r) j.row(r) = y(r).v.transpose();
  return j;
}

TEST(SE3Jet, ExpDerivativeAtZero) {
  // d (Exp(xi) p) / d xi at 0 = [I, -Hat(p)] (translation first).
  const Eigen::Vector3d p(1.0, -2.0, 0.5);
  const SE3<Jet6> pose = SE3<Jet6>::Exp(JetTwist(Vector6d::Zero()));
  Eigen::Matrix<double, 3, 6> expected;
  expected << Eigen::Matrix3d::Identity(), -Hat(p);
  EXPECT_LT((JetJacobian(pose * p.cast<Jet6>()) - expected).norm(), kJetTolerance);
}

TEST(SE3Jet, ExpDerivativeAtGenericPointsIsRightJacobian) {
  // Exp(xi + d) p ~ Exp(xi) Exp(Jr d) p  =>  d/dd = R [I, -Hat(p)] Jr(xi).
  const Eigen::Vector3d p(1.0, -2.0, 0.5);
  std::vector<Vector6d> points;
  Vector6d xi;
  xi << 0.5, -1.0, 2.0, 0.3, -0.2, 0.5;
  points.push_back(xi);
  xi << 3.0, 1.0, -2.0, 1e-9, 0.0, 0.0;
  points.push_back(xi);
  xi << -1.0, 0.5, 0.2, (kPi - 1e-6) * Eigen::Vector3d(1.0, 2.0, 3.0).normalized();
  points.push_back(xi);
  for (const Vector6d& x : points) {
    const SE3<Jet6> pose = SE3<Jet6>::Exp(JetTwist(x));
    Eigen::Matrix<double, 3, 6> point_jacobian;
    point_jacobian << Eigen::Matrix3d::Identity(), -Hat(p);
    const Eigen::Matrix<double, 3, 6> expected =
        SE3d::Exp(x).so3().matrix() * point_jacobian * RightJacobianSE3(x);
    EXPECT_LT((JetJacobian(pose * p.cast<Jet6>()) - expected).norm(), kJetTolerance)
        << x.transpose();
  }
}

}  // namespace
}  // namespace splinecal

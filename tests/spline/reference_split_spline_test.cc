// The benchmark's reference split spline (spline/reference_split_spline.h): its Jacobians against
// its own numeric derivatives (it is a different trajectory model from splinecal's coupled SE(3)
// spline), and its rotation part against splinecal's (the same SO(3) cumulative spline).
#include "spline/reference_split_spline.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cstdint>
#include <random>
#include <vector>

#include "spline/spline_test_util.h"
#include "splinecal/imu/imu_model.h"
#include "splinecal/lie/se3.h"
#include "splinecal/spline/se3_spline.h"
#include "testing/numeric_diff.h"

namespace splinecal {
namespace {

using reference::KnotMode;
using reference::Query;
using reference::ResidualJacobians;
using reference::SplitSpline;
using testing::RelativelyNear;

// Central differences with h = 1e-5 on O(1..100) functions: ~1e-8 relative (numeric_diff.h).
constexpr double kNumericTolerance = 1e-7;
// The same SO(3) formulas evaluated in a different order.
constexpr double kSameModelTolerance = 1e-12;

constexpr int kNumControlPoints = 8;

struct ControlPoints {
  std::vector<Eigen::Matrix3d> R;
  std::vector<Eigen::Vector3d> p;
};

ControlPoints FromPoses(const std::vector<SE3d>& poses) {
  ControlPoints c;
  for (const SE3d& T : poses) {
    c.R.push_back(T.rotationMatrix());
    c.p.push_back(T.translation());
  }
  return c;
}

// Control points k..k+3 perturbed by x = [dp_0, dphi_0, ..., dp_3, dphi_3] (p + dp, R Exp(dphi)).
ControlPoints Perturbed(const ControlPoints& c, int first, const Eigen::VectorXd& x) {
  ControlPoints out = c;
  for (int k = 0; k < 4; ++k) {
    out.p[first + k] += x.segment<3>(6 * k);
    out.R[first + k] = c.R[first + k] * SO3d::Exp(x.segment<3>(6 * k + 3)).matrix();
  }
  return out;
}

Eigen::MatrixXd ControlBlocks(const ResidualJacobians& J) {
  Eigen::MatrixXd m(3, 24);
  for (int k = 0; k < 4; ++k) m.middleCols<6>(6 * k) = J.control[k];
  return m;
}

class ReferenceSplitSplineTest : public ::testing::TestWithParam<KnotMode> {
 protected:
  ReferenceSplitSplineTest()
      : points_(FromPoses(testing::RandomControlPoses(kNumControlPoints, 7))) {}

  SplitSpline Make(const ControlPoints& c) const {
    return SplitSpline(c.R, c.p, testing::kEurocLikeT0Ns, testing::kTestDtNs, GetParam());
  }

  // Times in every segment, both ends included.
  std::vector<int64_t> Times() const {
    std::vector<int64_t> times;
    for (int i = 1; i <= kNumControlPoints - 3; ++i) {
      for (double u : {0.0, 0.37, 0.81}) {
        times.push_back(testing::kEurocLikeT0Ns + i * testing::kTestDtNs +
                        static_cast<int64_t>(u * testing::kTestDtNs));
      }
    }
    times.push_back(testing::kEurocLikeT0Ns + (kNumControlPoints - 2) * testing::kTestDtNs);
    return times;
  }

  ControlPoints points_;
};

TEST_P(ReferenceSplitSplineTest, GyroJacobiansMatchNumericDerivatives) {
  const SplitSpline spline = Make(points_);
  const Eigen::Vector3d measured(0.3, -0.1, 0.2);
  const Eigen::Vector3d b_g(0.01, -0.02, 0.03);
  for (int64_t t_ns : Times()) {
    const Query q = spline.QueryAtNs(t_ns);
    const int first = q.index - 1;
    Eigen::Vector3d r;
    ResidualJacobians J;
    spline.GyroResidual(q, measured, b_g, &r, &J);
    const Eigen::MatrixXd J_num = testing::CentralDifferenceJacobian(
        [&](const Eigen::VectorXd& x) -> Eigen::Vector3d {
          Eigen::Vector3d out;
          Make(Perturbed(points_, first, x)).GyroResidual(q, measured, b_g, &out, nullptr);
          return out;
        },
        Eigen::VectorXd::Zero(24));
    EXPECT_TRUE(RelativelyNear(ControlBlocks(J), J_num, kNumericTolerance)) << t_ns;
    EXPECT_TRUE(RelativelyNear(J.bias, Eigen::Matrix3d::Identity(), 0.0));
  }
}

TEST_P(ReferenceSplitSplineTest, AccelJacobiansMatchNumericDerivatives) {
  const SplitSpline spline = Make(points_);
  const Eigen::Vector3d measured(0.3, -0.1, 9.7);
  const Eigen::Vector3d b_a(0.01, -0.02, 0.03);
  const Eigen::Vector3d g_w(0.1, 0.2, -9.81);
  for (int64_t t_ns : Times()) {
    const Query q = spline.QueryAtNs(t_ns);
    const int first = q.index - 1;
    Eigen::Vector3d r;
    ResidualJacobians J;
    spline.AccelResidual(q, measured, b_a, g_w, &r, &J);
    const Eigen::MatrixXd J_num = testing::CentralDifferenceJacobian(
        [&](const Eigen::VectorXd& x) -> Eigen::Vector3d {
          Eigen::Vector3d out;
          Make(Perturbed(points_, first, x)).AccelResidual(q, measured, b_a, g_w, &out, nullptr);
          return out;
        },
        Eigen::VectorXd::Zero(24));
    EXPECT_TRUE(RelativelyNear(ControlBlocks(J), J_num, kNumericTolerance)) << t_ns;
    const Eigen::MatrixXd J_g_num = testing::CentralDifferenceJacobian(
        [&](const Eigen::Vector3d& g) -> Eigen::Vector3d {
          Eigen::Vector3d out;
          spline.AccelResidual(q, measured, b_a, g, &out, nullptr);
          return out;
        },
        g_w);
    EXPECT_TRUE(RelativelyNear(J.gravity, J_g_num, kNumericTolerance)) << t_ns;
    EXPECT_TRUE(RelativelyNear(J.bias, Eigen::Matrix3d::Identity(), 0.0));
  }
}

// The SO(3) part is splinecal's: same rotation, same body angular velocity, whatever the
// translations (the coupled spline's rotation does not depend on them).
TEST_P(ReferenceSplitSplineTest, RotationAndAngularVelocityEqualSplinecals) {
  const std::vector<SE3d> poses = testing::RandomControlPoses(kNumControlPoints, 7);
  const SE3Splined coupled(poses, testing::kEurocLikeT0Ns, testing::kTestDtNs);
  const SplitSpline split = Make(points_);
  for (int64_t t_ns : Times()) {
    const Query q = split.QueryAtNs(t_ns);
    const Segment<double> seg = coupled.SegmentAtNs(t_ns);
    ASSERT_EQ(q.index, seg.index);
    SE3d T_w_s;
    Eigen::Vector3d w_s;
    coupled.Evaluate(seg, &T_w_s, &w_s);
    Eigen::Matrix3d R;
    Eigen::Vector3d p;
    split.Pose(q, &R, &p);
    Eigen::Vector3d w_ref;
    Eigen::Vector3d a_ref;
    split.Rates(q, &w_ref, &a_ref);
    EXPECT_TRUE(RelativelyNear(R, T_w_s.rotationMatrix(), kSameModelTolerance)) << t_ns;
    EXPECT_TRUE(RelativelyNear(w_ref, w_s, kSameModelTolerance)) << t_ns;
    // And the gyro Jacobians' rotation columns, which depend on the rotations only.
    Eigen::Vector3d gyro;
    ControlPoseJacobian<3> J_coupled;
    PredictGyroWithJacobian(coupled, seg, Eigen::Vector3d::Zero(), &gyro, &J_coupled);
    Eigen::Vector3d r;
    ResidualJacobians J_ref;
    split.GyroResidual(q, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), &r, &J_ref);
    for (int k = 0; k < 4; ++k) {
      EXPECT_TRUE(RelativelyNear(
          J_ref.control[k].rightCols<3>(), J_coupled.blocks[k].rightCols<3>(), 1e-11))
          << t_ns << " block " << k;
    }
  }
}

// The positions are the R^3 cubic B-spline: p and a_w against the non-cumulative form
// sum_m B_m p_m with the uniform cubic B-spline matrix M, and a_w against differences of p.
TEST_P(ReferenceSplitSplineTest, PositionIsTheCubicBSplineOfThePoints) {
  const SplitSpline spline = Make(points_);
  Eigen::Matrix4d M;
  M << 1, 4, 1, 0, -3, 0, 3, 0, 3, -6, 3, 0, -1, 3, -3, 1;
  M /= 6.0;
  for (int64_t t_ns : Times()) {
    const Query q = spline.QueryAtNs(t_ns);
    Eigen::Matrix3d R;
    Eigen::Vector3d p;
    spline.Pose(q, &R, &p);
    const Eigen::Vector4d weights =
        M.transpose() * Eigen::Vector4d(1, q.u, q.u * q.u, q.u * q.u * q.u);
    Eigen::Vector3d expected = Eigen::Vector3d::Zero();
    for (int m = 0; m < 4; ++m) expected += weights(m) * points_.p[q.index - 1 + m];
    EXPECT_TRUE(RelativelyNear(p, expected, 1e-13)) << t_ns;
    Eigen::Vector3d w_s;
    Eigen::Vector3d a_w;
    spline.Rates(q, &w_s, &a_w);
    const double dt = spline.dt_s();
    const Eigen::Vector4d d2 = M.transpose() * Eigen::Vector4d(0, 0, 2, 6 * q.u) / (dt * dt);
    Eigen::Vector3d expected_a = Eigen::Vector3d::Zero();
    for (int m = 0; m < 4; ++m) expected_a += d2(m) * points_.p[q.index - 1 + m];
    EXPECT_TRUE(RelativelyNear(a_w, expected_a, 1e-12)) << t_ns;
  }
}

// The one-pass IMU prediction agrees with the residuals' values.
TEST_P(ReferenceSplitSplineTest, PredictionMatchesResiduals) {
  const SplitSpline spline = Make(points_);
  const Eigen::Vector3d g_w(0.0, 0.0, -9.81);
  const Eigen::Vector3d bias(0.01, -0.02, 0.03);
  for (int64_t t_ns : Times()) {
    const Query q = spline.QueryAtNs(t_ns);
    Eigen::Vector3d gyro;
    Eigen::Vector3d accel;
    spline.PredictImu(q, g_w, bias, bias, &gyro, &accel);
    Eigen::Vector3d r_g;
    Eigen::Vector3d r_a;
    spline.GyroResidual(q, Eigen::Vector3d::Zero(), bias, &r_g, nullptr);
    spline.AccelResidual(q, Eigen::Vector3d::Zero(), bias, g_w, &r_a, nullptr);
    EXPECT_TRUE(RelativelyNear(gyro, r_g, 1e-14));
    EXPECT_TRUE(RelativelyNear(accel, r_a, 1e-13));
  }
}

INSTANTIATE_TEST_SUITE_P(KnotModes,
                         ReferenceSplitSplineTest,
                         ::testing::Values(KnotMode::kPerQuery, KnotMode::kCached));

}  // namespace
}  // namespace splinecal

#include "splinecal/imu/imu_model.h"

#include <ceres/autodiff_cost_function.h>
#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "spline/spline_checks.h"
#include "spline/spline_test_util.h"
#include "splinecal/lie/se3.h"
#include "splinecal/lie/se3_manifold.h"
#include "splinecal/spline/se3_spline.h"
#include "splinecal/spline/segment_jacobians.h"
#include "splinecal/spline/trajectory_model.h"
#include "splinecal/units.h"
#include "testing/numeric_diff.h"
#include "testing/trajectory_models.h"

namespace splinecal {
namespace {

using testing::RelativelyNear;

// Jacobians vs central differences (h = 1e-5) of O(1..100) outputs: errors ~1e-10 absolute.
constexpr double kNumericJacobianTolerance = 1e-6;
// Automatic differentiation is exact up to rounding; the analytic Jacobians evaluate other
// formulas for the same derivatives. The brief's bar: 1e-9 (relative to max(1, |J|)).
constexpr double kAutoDiffTolerance = 1e-9;
constexpr double kRoundingTolerance = 1e-12;

SE3Splined MakeRandomSpline(uint32_t seed, TrajectoryModel model = TrajectoryModel::kSE3) {
  return testing::RandomSpline(seed, model);
}

std::vector<double> InteriorTimes(const SE3Splined& spline) {
  return testing::InteriorTimes(spline, {0.0, 0.3, 0.77});
}

const Eigen::Vector3d kGyroBias(0.01, -0.02, 0.005);
const Eigen::Vector3d kAccelBias(-0.1, 0.05, 0.2);

TEST(PredictImu, LevelImuAtRestReadsPlusGOnZ) {
  const std::vector<SE3d> poses(5, SE3d(SO3d(), Eigen::Vector3d(1, 2, 3)));
  const SE3Splined spline(poses, testing::kEurocLikeT0Ns, testing::kTestDtNs);
  Eigen::Vector3d gyro, accel;
  PredictImu(spline,
             spline.SegmentAtNs(spline.start_time_ns() + 12345),
             GravityWorld(),
             Eigen::Vector3d::Zero().eval(),
             Eigen::Vector3d::Zero().eval(),
             &gyro,
             &accel);
  EXPECT_TRUE(RelativelyNear(accel, Eigen::Vector3d(0, 0, 9.81), 1e-15));
  EXPECT_LT(gyro.norm(), 1e-15);
  EXPECT_EQ(GravityWorld(), Eigen::Vector3d(0, 0, -kDefaultGravity));
}

TEST(PredictImu, UpsideDownImuAtRestReadsMinusG) {
  const SO3d flipped = SO3d::Exp(Eigen::Vector3d(kPi, 0, 0));
  const std::vector<SE3d> poses(5, SE3d(flipped, Eigen::Vector3d::Zero()));
  const SE3Splined spline(poses, 0, testing::kTestDtNs);
  Eigen::Vector3d accel;
  PredictImu(spline,
             spline.SegmentAt(0.3),
             GravityWorld(9.80665),
             Eigen::Vector3d::Zero().eval(),
             kAccelBias,
             static_cast<Eigen::Vector3d*>(nullptr),
             &accel);
  EXPECT_TRUE(RelativelyNear(accel, Eigen::Vector3d(0, 0, -9.80665) + kAccelBias, 1e-14));
}

TEST(PredictImu, MatchesSplineRatesPlusBiases) {
  const SE3Splined spline = MakeRandomSpline(1);
  for (double t : InteriorTimes(spline)) {
    const Segment<double> seg = spline.SegmentAt(t);
    SE3d T_w_s;
    Eigen::Vector3d w_s, a_w, gyro, accel;
    spline.Evaluate(seg, &T_w_s, &w_s, nullptr, nullptr, &a_w);
    PredictImu(spline, seg, GravityWorld(), kGyroBias, kAccelBias, &gyro, &accel);
    EXPECT_TRUE(RelativelyNear(gyro, w_s + kGyroBias, kRoundingTolerance));
    EXPECT_TRUE(
        RelativelyNear(accel,
                       T_w_s.rotationMatrix().transpose() * (a_w - GravityWorld()) + kAccelBias,
                       kRoundingTolerance));
    // The Jacobian variants return the same values.
    Eigen::Vector3d gyro_j, accel_j;
    PredictGyroWithJacobian(spline, seg, kGyroBias, &gyro_j, nullptr);
    PredictAccelWithJacobian(spline, seg, GravityWorld(), kAccelBias, &accel_j, nullptr);
    EXPECT_TRUE(RelativelyNear(gyro_j, gyro, 1e-15));
    EXPECT_TRUE(RelativelyNear(accel_j, accel, kRoundingTolerance));
  }
}

TEST(PredictGyroWithJacobian, MatchesNumericRightPerturbation) {
  for (uint32_t seed : {2u, 3u}) {
    const SE3Splined spline = MakeRandomSpline(seed);
    for (double t : InteriorTimes(spline)) {
      const Segment<double> seg = spline.SegmentAt(t);
      ControlPoseJacobian<3> J;
      Eigen::Vector3d gyro;
      PredictGyroWithJacobian(spline, seg, kGyroBias, &gyro, &J);
      EXPECT_TRUE(testing::ControlJacobianMatchesNumeric(
          J,
          spline,
          seg,
          [&](const SE3Splined& s) {
            Eigen::Vector3d g;
            PredictImu(s, seg, GravityWorld(), kGyroBias, kAccelBias, &g, nullptr);
            return Eigen::VectorXd(g);
          },
          kNumericJacobianTolerance))
          << t;
      for (int k = 0; k < 4; ++k) {
        EXPECT_TRUE((J.blocks[k].leftCols<3>().isZero())) << "gyro ignores control translations";
      }
    }
  }
}

TEST(PredictAccelWithJacobian, MatchesNumericRightPerturbation) {
  for (uint32_t seed : {4u, 5u}) {
    const SE3Splined spline = MakeRandomSpline(seed);
    const Eigen::Vector3d g_w(0.3, -0.2, -9.7);  // not axis-aligned: exercises every column
    for (double t : InteriorTimes(spline)) {
      const Segment<double> seg = spline.SegmentAt(t);
      ControlPoseJacobian<3> J;
      Eigen::Matrix3d J_gw;
      Eigen::Vector3d accel;
      PredictAccelWithJacobian(spline, seg, g_w, kAccelBias, &accel, &J, &J_gw);
      EXPECT_TRUE(testing::ControlJacobianMatchesNumeric(
          J,
          spline,
          seg,
          [&](const SE3Splined& s) {
            Eigen::Vector3d a;
            PredictImu(s, seg, g_w, kGyroBias, kAccelBias, nullptr, &a);
            return Eigen::VectorXd(a);
          },
          kNumericJacobianTolerance))
          << t;
      const Eigen::MatrixXd J_gw_num = testing::CentralDifferenceJacobian(
          [&](const Eigen::VectorXd& g) -> Eigen::VectorXd {
            Eigen::Vector3d a;
            PredictImu(spline, seg, Eigen::Vector3d(g), kGyroBias, kAccelBias, nullptr, &a);
            return a;
          },
          g_w);
      EXPECT_TRUE(RelativelyNear(J_gw, J_gw_num, kNumericJacobianTolerance));
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Automatic differentiation through the same templated spline.

// Residual prediction - measurement of one IMU sample, on the four control poses perturbed as
// P_k Exp(d_k): autodiff at d = 0 gives exactly the right-perturbation Jacobians.
struct ImuResidualOnPerturbations {
  std::array<SE3d, 4> poses;
  int segment_index;
  double u;
  double dt_s;
  bool gyro;  // else accel
  Eigen::Vector3d measurement;
  TrajectoryModel model;

  template <typename T>
  bool operator()(const T* d0, const T* d1, const T* d2, const T* d3, T* residual) const {
    const T* d[4] = {d0, d1, d2, d3};
    std::array<SE3<T>, 4> P;
    for (int k = 0; k < 4; ++k) {
      P[k] = poses[k].cast<T>() * SE3<T>::Exp(Eigen::Map<const Vector6<T>>(d[k]));
    }
    const SegmentKnotData<T> data(P[0], P[1], P[2], P[3], false);
    const Segment<T> segment = MakeSegment(segment_index, T(u), dt_s);
    Vector3<T> prediction;
    const Vector3<T> b_g = kGyroBias.cast<T>();
    const Vector3<T> b_a = kAccelBias.cast<T>();
    if (gyro) {
      PredictImu<T>(
          model, data.knots(), segment, GravityWorld<T>(), b_g, b_a, &prediction, nullptr);
    } else {
      PredictImu<T>(
          model, data.knots(), segment, GravityWorld<T>(), b_g, b_a, nullptr, &prediction);
    }
    Eigen::Map<Vector3<T>> r(residual);
    r = prediction - measurement.cast<T>();
    return true;
  }
};

// The same on four 7-parameter pose blocks {px, py, pz, qx, qy, qz, qw} (what a Ceres problem
// holds); the tangent Jacobian is the ambient one times SE3Manifold's PlusJacobian.
struct ImuResidualOnPoseBlocks {
  int segment_index;
  double u;
  double dt_s;
  bool gyro;
  Eigen::Vector3d measurement;
  TrajectoryModel model;

  template <typename T>
  bool operator()(const T* p0, const T* p1, const T* p2, const T* p3, T* residual) const {
    const SegmentKnotData<T> data(
        PoseFromBlock(p0), PoseFromBlock(p1), PoseFromBlock(p2), PoseFromBlock(p3), false);
    const Segment<T> segment = MakeSegment(segment_index, T(u), dt_s);
    Vector3<T> prediction;
    const Vector3<T> b_g = kGyroBias.cast<T>();
    const Vector3<T> b_a = kAccelBias.cast<T>();
    PredictImu<T>(model,
                  data.knots(),
                  segment,
                  GravityWorld<T>(),
                  b_g,
                  b_a,
                  gyro ? &prediction : nullptr,
                  gyro ? nullptr : &prediction);
    Eigen::Map<Vector3<T>> r(residual);
    r = prediction - measurement.cast<T>();
    return true;
  }
};

// Both trajectory models (spline/trajectory_model.h): the same autodiff oracle for each.
class PredictImuAutoDiff : public ::testing::TestWithParam<TrajectoryModel> {};

TEST_P(PredictImuAutoDiff, ThroughTemplatedSplineMatchesAnalyticJacobians) {
  const TrajectoryModel model = GetParam();
  const SE3Splined spline = MakeRandomSpline(6, model);
  for (double t : InteriorTimes(spline)) {
    const Segment<double> seg = spline.SegmentAt(t);
    const int f = seg.first_index();
    for (bool gyro : {true, false}) {
      auto* functor = new ImuResidualOnPerturbations{{spline.control_pose(f),
                                                      spline.control_pose(f + 1),
                                                      spline.control_pose(f + 2),
                                                      spline.control_pose(f + 3)},
                                                     seg.index,
                                                     seg.u,
                                                     spline.dt(),
                                                     gyro,
                                                     Eigen::Vector3d(0.1, 0.2, 0.3),
                                                     model};
      ceres::AutoDiffCostFunction<ImuResidualOnPerturbations, 3, 6, 6, 6, 6> cost(functor);
      const double zeros[6] = {0, 0, 0, 0, 0, 0};
      const double* parameters[4] = {zeros, zeros, zeros, zeros};
      double residual[3];
      Eigen::Matrix<double, 3, 6, Eigen::RowMajor> J_auto[4];
      double* jacobians[4] = {
          J_auto[0].data(), J_auto[1].data(), J_auto[2].data(), J_auto[3].data()};
      ASSERT_TRUE(cost.Evaluate(parameters, residual, jacobians));

      ControlPoseJacobian<3> J;
      Eigen::Vector3d prediction;
      if (gyro) {
        PredictGyroWithJacobian(spline, seg, kGyroBias, &prediction, &J);
      } else {
        PredictAccelWithJacobian(spline, seg, GravityWorld(), kAccelBias, &prediction, &J);
      }
      EXPECT_TRUE(RelativelyNear(Eigen::Map<Eigen::Vector3d>(residual),
                                 prediction - Eigen::Vector3d(0.1, 0.2, 0.3),
                                 kRoundingTolerance));
      for (int k = 0; k < 4; ++k) {
        EXPECT_TRUE(RelativelyNear(J.blocks[k], J_auto[k], kAutoDiffTolerance))
            << (gyro ? "gyro" : "accel") << " t " << t << " k " << k;
      }
    }
  }
}

TEST_P(PredictImuAutoDiff, OnPoseBlocksTimesPlusJacobianMatchesAnalytic) {
  const TrajectoryModel model = GetParam();
  const SE3Splined spline = MakeRandomSpline(7, model);
  const SE3Manifold manifold;
  for (double t : InteriorTimes(spline)) {
    const Segment<double> seg = spline.SegmentAt(t);
    const int f = seg.first_index();
    double blocks[4][7];
    for (int k = 0; k < 4; ++k) PoseToBlock(spline.control_pose(f + k), blocks[k]);
    for (bool gyro : {true, false}) {
      ceres::AutoDiffCostFunction<ImuResidualOnPoseBlocks, 3, 7, 7, 7, 7> cost(
          new ImuResidualOnPoseBlocks{
              seg.index, seg.u, spline.dt(), gyro, Eigen::Vector3d::Zero(), model});
      const double* parameters[4] = {blocks[0], blocks[1], blocks[2], blocks[3]};
      double residual[3];
      Eigen::Matrix<double, 3, 7, Eigen::RowMajor> J_ambient[4];
      double* jacobians[4] = {
          J_ambient[0].data(), J_ambient[1].data(), J_ambient[2].data(), J_ambient[3].data()};
      ASSERT_TRUE(cost.Evaluate(parameters, residual, jacobians));
      ControlPoseJacobian<3> J;
      if (gyro) {
        PredictGyroWithJacobian(spline, seg, kGyroBias, nullptr, &J);
      } else {
        PredictAccelWithJacobian(spline, seg, GravityWorld(), kAccelBias, nullptr, &J);
      }
      for (int k = 0; k < 4; ++k) {
        Eigen::Matrix<double, 7, 6, Eigen::RowMajor> plus_jacobian;
        ASSERT_TRUE(manifold.PlusJacobian(blocks[k], plus_jacobian.data()));
        const Eigen::Matrix<double, 3, 6> J_tangent = J_ambient[k] * plus_jacobian;
        EXPECT_TRUE(RelativelyNear(J.blocks[k], J_tangent, kAutoDiffTolerance))
            << (gyro ? "gyro" : "accel") << " t " << t << " k " << k;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Models,
                         PredictImuAutoDiff,
                         testing::BothTrajectoryModels(),
                         testing::TrajectoryModelTestName);

}  // namespace
}  // namespace splinecal

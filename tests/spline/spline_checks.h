// What the tests of both trajectory models (se3_spline_test.cc, split_segment_test.cc,
// split_segment_jacobians_test.cc, imu_model_test.cc) check a spline with: seeded random splines,
// the interior times they sample, every output of one Evaluate, the reference split spline on the
// same control poses, and the control-pose Jacobians against central differences of the spline
// under splinecal's right perturbation T_k -> T_k Exp(d).
// Header-only, test-only.
#ifndef SPLINECAL_TESTS_SPLINE_SPLINE_CHECKS_H_
#define SPLINECAL_TESTS_SPLINE_SPLINE_CHECKS_H_

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <utility>
#include <vector>

#include "spline/reference_split_spline.h"
#include "spline/spline_test_util.h"
#include "splinecal/lie/se3.h"
#include "splinecal/spline/se3_spline.h"
#include "splinecal/spline/trajectory_model.h"
#include "testing/numeric_diff.h"

namespace splinecal {
namespace testing {

inline constexpr int kRandomSplinePoses = 8;

// Eight random control poses (RandomControlPoses: rotation steps of min_angle..max_angle rad),
// EuRoC-like t0, 0.2 s between knots.
inline SE3Splined RandomSpline(uint32_t seed,
                               TrajectoryModel model,
                               double min_angle = 0.1,
                               double max_angle = 1.0) {
  return SE3Splined(RandomControlPoses(kRandomSplinePoses, seed, min_angle, max_angle),
                    kEurocLikeT0Ns,
                    kTestDtNs,
                    model);
}

// Fractions u of a segment strictly between its knots: central differences in time at t +- h
// stay inside the valid range.
inline constexpr std::initializer_list<double> kInteriorFractions = {0.013, 0.25, 0.5, 0.81, 0.99};

// Times [s since t0] at the fractions `us` of every segment.
inline std::vector<double> InteriorTimes(const SE3Splined& spline,
                                         std::initializer_list<double> us = kInteriorFractions) {
  std::vector<double> times;
  for (int i = 1; i + 2 < spline.num_control_poses(); ++i) {
    for (double u : us)
      times.push_back(spline.TimeSinceT0(spline.knot_time_ns(i)) + u * spline.dt());
  }
  return times;
}

// Every output of one Evaluate.
struct SplineState {
  SE3d T_w_s;
  Eigen::Vector3d w_s, w_dot_s, v_w, a_w;
};

inline SplineState EvaluateAll(const SE3Splined& spline, const Segment<double>& segment) {
  SplineState s;
  spline.Evaluate(segment, &s.T_w_s, &s.w_s, &s.w_dot_s, &s.v_w, &s.a_w);
  return s;
}

inline SplineState EvaluateAt(const SE3Splined& spline, double t_s) {
  return EvaluateAll(spline, spline.SegmentAt(t_s));
}

// Central differences in time (h = kTimeStep = 1e-5 s against dt = 0.2 s): truncation
// h^2/6 |f'''| ~ 1e-9 relative, rounding eps |f| / h ~ 1e-11 relative; 1e-6 is the brief's bar.
inline constexpr double kTimeStep = 1e-5;
inline constexpr double kTimeDerivativeTolerance = 1e-6;

// Every time derivative of one Evaluate against central differences of the outputs at
// InteriorTimes +- kTimeStep: v_w of the position, a_w of v_w, w_dot_s of w_s, and w_s as
// Log(R(t - h)^T R(t + h)) / 2h (vee(R^T dR/dt) to O(h^2)).
inline void ExpectTimeDerivativesMatchCentralDifferences(const SE3Splined& spline) {
  for (double t : InteriorTimes(spline)) {
    const SplineState s = EvaluateAt(spline, t);
    const SplineState plus = EvaluateAt(spline, t + kTimeStep);
    const SplineState minus = EvaluateAt(spline, t - kTimeStep);
    const Eigen::Vector3d v_numeric =
        (plus.T_w_s.translation() - minus.T_w_s.translation()) / (2 * kTimeStep);
    const Eigen::Vector3d a_numeric = (plus.v_w - minus.v_w) / (2 * kTimeStep);
    const Eigen::Vector3d w_numeric =
        (minus.T_w_s.so3().inverse() * plus.T_w_s.so3()).Log() / (2 * kTimeStep);
    const Eigen::Vector3d w_dot_numeric = (plus.w_s - minus.w_s) / (2 * kTimeStep);
    EXPECT_TRUE(RelativelyNear(s.v_w, v_numeric, kTimeDerivativeTolerance)) << t;
    EXPECT_TRUE(RelativelyNear(s.a_w, a_numeric, kTimeDerivativeTolerance)) << t;
    EXPECT_TRUE(RelativelyNear(s.w_s, w_numeric, kTimeDerivativeTolerance)) << t;
    EXPECT_TRUE(RelativelyNear(s.w_dot_s, w_dot_numeric, kTimeDerivativeTolerance)) << t;
  }
}

// The reference split spline of the benchmark (reference_split_spline.h) on the control poses of
// `spline`, with its knot time and spacing.
inline reference::SplitSpline ReferenceSplitSpline(const SE3Splined& spline,
                                                   reference::KnotMode mode) {
  std::vector<Eigen::Matrix3d> R;
  std::vector<Eigen::Vector3d> p;
  for (const SE3d& T : spline.control_poses()) {
    R.push_back(T.rotationMatrix());
    p.push_back(T.translation());
  }
  return reference::SplitSpline(R, p, spline.t0_ns(), spline.dt_ns(), mode);
}

// The spline with control pose `index` replaced by T_index Exp(d).
inline SE3Splined PerturbedControlPose(const SE3Splined& spline,
                                       int index,
                                       const Eigen::VectorXd& d) {
  SE3Splined perturbed = spline;
  perturbed.SetControlPose(index, spline.control_pose(index) * SE3d::Exp(Vector6d(d)));
  return perturbed;
}

// d output / d d_k by central differences, for the segment's four control poses; `output` maps a
// (perturbed) spline to an Eigen vector.
template <typename F>
std::array<Eigen::MatrixXd, 4> NumericControlJacobians(const SE3Splined& spline,
                                                       const Segment<double>& segment,
                                                       const F& output) {
  std::array<Eigen::MatrixXd, 4> J;
  for (int k = 0; k < 4; ++k) {
    const int index = segment.first_index() + k;
    J[k] = CentralDifferenceJacobian(
        [&](const Eigen::VectorXd& d) -> Eigen::VectorXd {
          return output(PerturbedControlPose(spline, index, d));
        },
        Eigen::VectorXd::Zero(6));
  }
  return J;
}

// Each of the four blocks of an analytic control-pose Jacobian against the central differences
// of `output` (RelativelyNear at `tolerance`); a failure names the block.
template <int kRows, typename F>
::testing::AssertionResult ControlJacobianMatchesNumeric(const ControlPoseJacobian<kRows>& J,
                                                         const SE3Splined& spline,
                                                         const Segment<double>& segment,
                                                         const F& output,
                                                         double tolerance) {
  const std::array<Eigen::MatrixXd, 4> J_num = NumericControlJacobians(spline, segment, output);
  for (int k = 0; k < 4; ++k) {
    ::testing::AssertionResult near = RelativelyNear(J.blocks[k], J_num[k], tolerance);
    if (!near) return near << "\nblock k = " << k;
  }
  return ::testing::AssertionSuccess();
}

// The pose Jacobian (EvaluatePoseJacobian's T_w_s and J) against central differences of the
// right-tangent change Log(T_w_s^-1 T_w_s(perturbed)).
inline ::testing::AssertionResult PoseJacobianMatchesNumeric(const ControlPoseJacobian<6>& J,
                                                             const SE3d& T_w_s,
                                                             const SE3Splined& spline,
                                                             const Segment<double>& segment,
                                                             double tolerance) {
  return ControlJacobianMatchesNumeric(
      J,
      spline,
      segment,
      [&](const SE3Splined& s) {
        return Eigen::VectorXd((T_w_s.inverse() * s.Pose(segment)).Log());
      },
      tolerance);
}

// The pose Jacobian (EvaluatePoseJacobian) against central differences (PoseJacobianMatchesNumeric)
// for `seeds` random splines of the model with rotation steps of min_angle..max_angle rad, at
// `segment_fractions` of every segment: its first control pose is the segment's, and the pose it
// evaluates with the Jacobian agrees with Pose's to `same_value_tolerance` (0: bit for bit).
// `also` checks more of each Jacobian where the model promises more (the split model's zero
// blocks).
inline void ExpectPoseJacobianMatchesNumeric(
    TrajectoryModel model,
    std::pair<double, double> rotation_steps,
    std::initializer_list<uint32_t> seeds,
    double same_value_tolerance,
    double jacobian_tolerance,
    std::initializer_list<double> segment_fractions = kInteriorFractions,
    const std::function<void(const ControlPoseJacobian<6>&)>& also = nullptr) {
  for (uint32_t seed : seeds) {
    const SE3Splined spline =
        RandomSpline(seed, model, rotation_steps.first, rotation_steps.second);
    for (double t : InteriorTimes(spline, segment_fractions)) {
      const Segment<double> seg = spline.SegmentAt(t);
      SE3d T_w_s;
      ControlPoseJacobian<6> J;
      spline.EvaluatePoseJacobian(seg, &T_w_s, &J);
      EXPECT_EQ(J.first_index, seg.first_index());
      EXPECT_TRUE(
          RelativelyNear(T_w_s.matrix(), spline.Pose(seg).matrix(), same_value_tolerance))
          << t;
      EXPECT_TRUE(PoseJacobianMatchesNumeric(J, T_w_s, spline, seg, jacobian_tolerance))
          << "t " << t;
      if (also) also(J);
    }
  }
}

// A rate with a control-pose Jacobian of its own: SE3Spline's evaluation with the Jacobian, and
// its accessor.
struct SplineRate {
  void (SE3Splined::*with_jacobian)(const Segment<double>&,
                                    Eigen::Vector3d*,
                                    ControlPoseJacobian<3>*) const;
  Eigen::Vector3d (SE3Splined::*value)(const Segment<double>&) const;
};

inline constexpr SplineRate kAngularVelocity = {&SE3Splined::EvaluateAngularVelocityJacobian,
                                                &SE3Splined::AngularVelocity};
inline constexpr SplineRate kLinearAcceleration = {&SE3Splined::EvaluateLinearAccelerationJacobian,
                                                   &SE3Splined::LinearAcceleration};

// The rate's Jacobian against central differences of its value, for `seeds` random splines of
// the model with rotation steps of min_angle..max_angle rad, at `segment_fractions` of every
// segment (InteriorTimes); the value evaluated with the Jacobian agrees with the accessor's to
// `same_value_tolerance` (0: bit for bit).
inline void ExpectRateJacobianMatchesNumeric(
    const SplineRate& rate,
    TrajectoryModel model,
    std::pair<double, double> rotation_steps,
    std::initializer_list<uint32_t> seeds,
    double same_value_tolerance,
    double jacobian_tolerance,
    std::initializer_list<double> segment_fractions = kInteriorFractions) {
  for (uint32_t seed : seeds) {
    const SE3Splined spline =
        RandomSpline(seed, model, rotation_steps.first, rotation_steps.second);
    for (double t : InteriorTimes(spline, segment_fractions)) {
      const Segment<double> seg = spline.SegmentAt(t);
      Eigen::Vector3d value;
      ControlPoseJacobian<3> J;
      (spline.*rate.with_jacobian)(seg, &value, &J);
      EXPECT_TRUE(RelativelyNear(value, (spline.*rate.value)(seg), same_value_tolerance)) << t;
      EXPECT_TRUE(ControlJacobianMatchesNumeric(
          J,
          spline,
          seg,
          [&](const SE3Splined& s) { return Eigen::VectorXd((s.*rate.value)(seg)); },
          jacobian_tolerance))
          << "t " << t;
    }
  }
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_SPLINE_SPLINE_CHECKS_H_

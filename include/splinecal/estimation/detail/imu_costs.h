// The IMU residuals of `splinecal fit` and `calibrate`, with analytic Jacobians (their
// automatic-differentiation twins, for the tests and the benchmark, are in
// tests/testing/autodiff_costs.h).
//
// Model (docs/conventions.md "IMU model", imu/imu_model.h, [seed000 eqs. (9)-(10)]): at an IMU time
// t in pose-spline segment i (u = (t - t_i) / dt),
//
//   gyro residual   r_g = (w_s(t) + b_g(t) - gyro_measured) / sigma_g
//   accel residual  r_a = (R_w_s(t)^T (a_w(t) - g_w) + b_a(t) - accel_measured) / sigma_a
//
// with w_s, R_w_s and a_w from the pose spline's trajectory model (ImuResidualSegment::model,
// spline/trajectory_model.h: the gyro residual is the same in both models, the accelerometer's
// differs) and sigma = noise density * sqrt(rate), the per-sample white-noise std ([Kalibr]).
// b(t) is the constant bias (one block) or the bias spline of estimation/bias_costs.h (four
// blocks with weights B_j(u_b)); either way b = sum_j weight_j * bias_block_j.
//
// Parameter blocks, in this order:
//   gyro:   4 control poses {px, py, pz, qx, qy, qz, qw} (T_{i-1} .. T_{i+2}), then
//           kBiasBlocks gyro-bias blocks (3 each)
//   accel:  4 control poses, kBiasBlocks accel-bias blocks, then g_w (3;
//   estimation/gravity_manifold.h)
//
// Jacobians. The spline Jacobians (spline/segment_jacobians.h, imu/imu_model.h) are in the RIGHT
// tangent of each control pose (T Exp(d), d = [rho; phi]); they are lifted to the ambient block
// exactly (estimation/detail/pose_block_jacobian.h), so every cost function here keeps Ceres' contract
// (jacobians == nullptr: residuals only; jacobians[i] == nullptr: skip block i; layout
// jacobians[i][r * size_i + c]) and passes ceres::GradientChecker through SE3Manifold and
// GravityManifold. d r_g / d b_g,j = weight_j I / sigma_g, d r_a / d g_w = -R_w_s^T / sigma_a.
//
// Two layouts of the same residuals, one template each over ImuSensor (the Gyro/Accel names):
//   ImuSampleCostFunction   (GyroCostFunction, AccelCostFunction)  one sample, SizedCostFunction
//   ImuSegmentCostFunction  (GyroSegmentCostFunction, ...)         every sample of one spline
//                                                                  segment, stacked (3 per sample)
// The stacked form is the same objective with ~20x fewer residual blocks at 200 Hz and
// dt = 0.1 s: Ceres' per-block costs (bookkeeping, validity checks, the manifold product per
// block, one product term per pair of blocks in J^T J) dominate otherwise; `splinecal fit` uses
// it (docs/fit.md, "Speed").
//
// Sharing: given a SplineEvaluationCallback, a cost function reads its segment's knot deltas and
// their Jacobians from the spline the callback rebuilt once for this evaluation point, instead
// of recomputing them per residual (estimation/spline_evaluation_callback.h); otherwise, or when
// its parameters differ from the callback's, it computes them from its own pose blocks.
#ifndef SPLINECAL_ESTIMATION_DETAIL_IMU_COSTS_H_
#define SPLINECAL_ESTIMATION_DETAIL_IMU_COSTS_H_

#include <ceres/cost_function.h>
#include <ceres/sized_cost_function.h>

#include <Eigen/Core>
#include <array>
#include <optional>
#include <utility>
#include <vector>

#include "splinecal/estimation/detail/pose_block_jacobian.h"
#include "splinecal/estimation/spline_evaluation_callback.h"
#include "splinecal/imu/imu_model.h"
#include "splinecal/imu/static_recording.h"
#include "splinecal/lie/se3_manifold.h"
#include "splinecal/spline/segment.h"
#include "splinecal/spline/segment_jacobians.h"
#include "splinecal/spline/trajectory_model.h"

namespace splinecal {

// One IMU reading as a residual: where it falls in its pose-spline segment, what was measured
// (gyro [rad/s] or accel [m/s^2]) and the weights of its bias blocks (constant model: {1}; bias
// spline: B_0..B_3 at the sample's bias-spline u).
struct ImuResidualSample {
  double u = 0.0;
  Eigen::Vector3d measured = Eigen::Vector3d::Zero();
  std::array<double, 4> bias_weights = {1.0, 0.0, 0.0, 0.0};
};

// What every IMU residual of one pose-spline segment shares.
struct ImuResidualSegment {
  int segment_index = 1;  // i: control poses i-1 .. i+2
  double dt_s = 0.0;      // pose knot spacing [s]
  double sigma = 1.0;     // per-sample noise std [rad/s or m/s^2]
  // The pose spline's model; the accelerometer residual depends on it (the gyro's does not).
  TrajectoryModel model = TrajectoryModel::kSE3;
  // Optional: the knot caches for this evaluation point (not owned; may be nullptr).
  const SplineEvaluationCallback* shared = nullptr;
};

namespace internal {

// The knots and the pose-block lifts of one evaluation (local holds knots computed from the
// blocks when the shared spline does not match).
struct SegmentEvaluation {
  SegmentKnots<double> knots;
  std::optional<SegmentKnotData<double>> local;
  std::array<PoseBlockLift, kSplineOrder> lifts;
};

inline void PrepareSegmentEvaluation(const ImuResidualSegment& segment,
                                     double const* const* parameters,
                                     bool pose_jacobians,
                                     SegmentEvaluation* evaluation) {
  evaluation->knots = SegmentKnotsFor(
      segment.shared, segment.segment_index - 1, parameters, pose_jacobians, &evaluation->local);
  if (pose_jacobians) {
    for (int k = 0; k < kSplineOrder; ++k) {
      evaluation->lifts[k] = MakePoseBlockLift(parameters[k]);
    }
  }
}

inline bool AnyPoseJacobian(double** jacobians) {
  if (jacobians == nullptr) return false;
  for (int k = 0; k < kSplineOrder; ++k) {
    if (jacobians[k] != nullptr) return true;
  }
  return false;
}

template <int kBiasBlocks>
Eigen::Vector3d WeightedBias(const ImuResidualSample& sample, double const* const* bias_blocks) {
  Eigen::Vector3d bias = sample.bias_weights[0] * Eigen::Map<const Eigen::Vector3d>(bias_blocks[0]);
  for (int j = 1; j < kBiasBlocks; ++j) {
    bias += sample.bias_weights[j] * Eigen::Map<const Eigen::Vector3d>(bias_blocks[j]);
  }
  return bias;
}

// d r / d bias block j = weight_j / sigma I, written as 3 rows of 3 at `row`.
template <int kBiasBlocks>
void WriteBiasJacobians(const ImuResidualSample& sample,
                        double inv_sigma,
                        double** bias_jacobians,
                        int row) {
  for (int j = 0; j < kBiasBlocks; ++j) {
    if (bias_jacobians[j] == nullptr) continue;
    Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> J(bias_jacobians[j] + 3 * row);
    J = (sample.bias_weights[j] * inv_sigma) * Eigen::Matrix3d::Identity();
  }
}

// The residual of one sample into residual[0..2]; Jacobians (when jacobians != nullptr) into
// rows row..row+2 of each requested block. parameters: 4 poses, kBiasBlocks biases, and g_w for
// the accelerometer. The gyro's Jacobian has no translation columns (spline/segment_jacobians.h).
template <ImuSensor kSensor, int kBiasBlocks>
void SampleRows(const SegmentEvaluation& evaluation,
                const ImuResidualSegment& segment,
                const ImuResidualSample& sample,
                double const* const* parameters,
                double* residual,
                double** jacobians,
                int row) {
  constexpr bool kGyro = kSensor == ImuSensor::kGyroscope;
  const Segment<double> seg = MakeSegment(segment.segment_index, sample.u, segment.dt_s);
  const double inv_sigma = 1.0 / segment.sigma;
  const bool pose_jacobians = AnyPoseJacobian(jacobians);
  const Eigen::Vector3d bias = WeightedBias<kBiasBlocks>(sample, parameters + kSplineOrder);
  Eigen::Vector3d prediction;
  ControlPoseJacobian<3> J_ctrl;
  Eigen::Matrix3d J_accel_gw;
  if constexpr (kGyro) {
    EvaluateAngularVelocityJacobian(
        evaluation.knots, seg, &prediction, pose_jacobians ? &J_ctrl : nullptr);
    prediction += bias;
  } else {
    const Eigen::Map<const Eigen::Vector3d> g_w(parameters[kSplineOrder + kBiasBlocks]);
    PredictAccelWithJacobian(segment.model,
                             evaluation.knots,
                             seg,
                             g_w,
                             bias,
                             &prediction,
                             pose_jacobians ? &J_ctrl : nullptr,
                             &J_accel_gw);
  }
  Eigen::Map<Eigen::Vector3d> r(residual);
  r = (prediction - sample.measured) * inv_sigma;
  if (jacobians == nullptr) return;
  if (pose_jacobians) {
    for (int k = 0; k < kSplineOrder; ++k) {
      if (jacobians[k] == nullptr) continue;
      if constexpr (kGyro) {
        const Eigen::Matrix3d J_phi = J_ctrl.blocks[k].rightCols<3>() * inv_sigma;
        LiftRotationOnlyPoseJacobian(J_phi, evaluation.lifts[k], jacobians[k] + 7 * row);
      } else {
        const Eigen::Matrix<double, 3, 6> J = J_ctrl.blocks[k] * inv_sigma;
        LiftPoseJacobian(J, evaluation.lifts[k], jacobians[k] + 7 * row);
      }
    }
  }
  WriteBiasJacobians<kBiasBlocks>(sample, inv_sigma, jacobians + kSplineOrder, row);
  if constexpr (!kGyro) {
    double* J_g = jacobians[kSplineOrder + kBiasBlocks];
    if (J_g != nullptr) {
      Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> J(J_g + 3 * row);
      J = J_accel_gw * inv_sigma;
    }
  }
}

}  // namespace internal

// ---- Evaluate: the residual rows and their Jacobians ----

namespace internal {

// The segment of four pose blocks in scalar T, without Jacobian caches: for costs
// differentiated automatically (detail/further_imu_cost.h and the tests' autodiff twins).
template <typename T>
SegmentKnotData<T> KnotDataFromBlocks(const T* const* poses) {
  return SegmentKnotData<T>(PoseFromBlock(poses[0]),
                            PoseFromBlock(poses[1]),
                            PoseFromBlock(poses[2]),
                            PoseFromBlock(poses[3]),
                            /*with_jacobians=*/false);
}

// The sample's bias: its B-spline weights times the segment's kBiasBlocks bias points.

// The rows of `num_samples` samples of one segment, 3 per sample, stacked: the segment's knot
// data is prepared once and kSampleRows (a SampleRows instance, a compile-time
// constant so that it inlines) writes each sample's residual and Jacobian rows.
template <auto kSampleRows>
void EvaluateSegmentSamples(const ImuResidualSegment& segment,
                            const ImuResidualSample* samples,
                            size_t num_samples,
                            double const* const* parameters,
                            double* residuals,
                            double** jacobians) {
  SegmentEvaluation evaluation;
  PrepareSegmentEvaluation(segment, parameters, AnyPoseJacobian(jacobians), &evaluation);
  for (size_t s = 0; s < num_samples; ++s) {
    kSampleRows(evaluation,
                segment,
                samples[s],
                parameters,
                residuals + 3 * s,
                jacobians,
                3 * static_cast<int>(s));
  }
}

// The 3-vector blocks after the four poses: the biases, then g_w for the accelerometer.
template <ImuSensor kSensor, int kBiasBlocks>
inline constexpr int kImuVectorBlocks = kBiasBlocks +
                                        (kSensor == ImuSensor::kAccelerometer ? 1 : 0);

template <int>
inline constexpr int kVectorBlockSize = 3;

// ceres::SizedCostFunction<3, 7, 7, 7, 7, 3, ..., 3> with kVectorBlocks blocks of 3.
template <int kVectorBlocks, typename = std::make_integer_sequence<int, kVectorBlocks>>
struct OneSampleCostBase;
template <int kVectorBlocks, int... kBlock>
struct OneSampleCostBase<kVectorBlocks, std::integer_sequence<int, kBlock...>> {
  using Type = ceres::SizedCostFunction<3, 7, 7, 7, 7, kVectorBlockSize<kBlock>...>;
};

}  // namespace internal

// The residual of one sample (3 rows). kBiasBlocks: 1 (constant bias) or 4 (bias spline).
template <ImuSensor kSensor, int kBiasBlocks>
class ImuSampleCostFunction
    : public internal::OneSampleCostBase<internal::kImuVectorBlocks<kSensor, kBiasBlocks>>::Type {
 public:
  ImuSampleCostFunction(const ImuResidualSegment& segment, const ImuResidualSample& sample)
      : segment_(segment), sample_(sample) {}

  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override {
    internal::EvaluateSegmentSamples<internal::SampleRows<kSensor, kBiasBlocks>>(
        segment_, &sample_, 1, parameters, residuals, jacobians);
    return true;
  }

 private:
  ImuResidualSegment segment_;
  ImuResidualSample sample_;
};

// Every residual of one segment, stacked: rows 3s..3s+2 are sample s. The parameter blocks of
// ImuSampleCostFunction. `samples` must not be empty.
template <ImuSensor kSensor, int kBiasBlocks>
class ImuSegmentCostFunction : public ceres::CostFunction {
 public:
  ImuSegmentCostFunction(const ImuResidualSegment& segment, std::vector<ImuResidualSample> samples)
      : segment_(segment), samples_(std::move(samples)) {
    CHECK(!samples_.empty());
    set_num_residuals(3 * static_cast<int>(samples_.size()));
    for (int k = 0; k < kSplineOrder; ++k) mutable_parameter_block_sizes()->push_back(7);
    for (int j = 0; j < internal::kImuVectorBlocks<kSensor, kBiasBlocks>; ++j) {
      mutable_parameter_block_sizes()->push_back(3);
    }
  }

  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override {
    internal::EvaluateSegmentSamples<internal::SampleRows<kSensor, kBiasBlocks>>(
        segment_, samples_.data(), samples_.size(), parameters, residuals, jacobians);
    return true;
  }

  const std::vector<ImuResidualSample>& samples() const { return samples_; }

 private:
  ImuResidualSegment segment_;
  std::vector<ImuResidualSample> samples_;
};

template <int kBiasBlocks>
using GyroCostFunction = ImuSampleCostFunction<ImuSensor::kGyroscope, kBiasBlocks>;
template <int kBiasBlocks>
using AccelCostFunction = ImuSampleCostFunction<ImuSensor::kAccelerometer, kBiasBlocks>;
template <int kBiasBlocks>
using GyroSegmentCostFunction = ImuSegmentCostFunction<ImuSensor::kGyroscope, kBiasBlocks>;
template <int kBiasBlocks>
using AccelSegmentCostFunction = ImuSegmentCostFunction<ImuSensor::kAccelerometer, kBiasBlocks>;

// The analytic costs are compiled once, in src/estimation/imu_costs.cc, for both sensors and
// both bias models; other units only declare them (their Evaluate is the costly part to compile).
extern template class ImuSampleCostFunction<ImuSensor::kGyroscope, 1>;
extern template class ImuSampleCostFunction<ImuSensor::kGyroscope, 4>;
extern template class ImuSampleCostFunction<ImuSensor::kAccelerometer, 1>;
extern template class ImuSampleCostFunction<ImuSensor::kAccelerometer, 4>;
extern template class ImuSegmentCostFunction<ImuSensor::kGyroscope, 1>;
extern template class ImuSegmentCostFunction<ImuSensor::kGyroscope, 4>;
extern template class ImuSegmentCostFunction<ImuSensor::kAccelerometer, 1>;
extern template class ImuSegmentCostFunction<ImuSensor::kAccelerometer, 4>;

}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_DETAIL_IMU_COSTS_H_

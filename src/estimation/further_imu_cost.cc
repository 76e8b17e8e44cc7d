#include "splinecal/estimation/detail/further_imu_cost.h"

#include <ceres/dynamic_autodiff_cost_function.h>

#include "splinecal/estimation/detail/imu_costs.h"
#include "splinecal/imu/imu_intrinsic_model.h"
#include "splinecal/lie/se3_manifold.h"
#include "splinecal/spline/trajectory_evaluation.h"

namespace splinecal {
namespace {

// Parameters per DynamicAutoDiffCostFunction pass (as estimation/detail/imu_model_costs.h).
constexpr int kStride = 8;

// Block indices after the four control poses (file comment of the header).
struct BlockIndex {
  explicit BlockIndex(int nb)
      : gyro_bias(4), accel_bias(4 + nb), gravity(4 + 2 * nb), q_i_b(5 + 2 * nb),
        r_b(6 + 2 * nb), time_offset(7 + 2 * nb) {}
  int gyro_bias, accel_bias, gravity, q_i_b, r_b, time_offset;
};

template <typename T>
Vector3<T> Bias(const FurtherImuSample& sample, int nb, T const* const* blocks) {
  Vector3<T> bias = Vector3<T>::Zero();
  for (int j = 0; j < nb; ++j) {
    bias += T(sample.bias_weights[j]) * Eigen::Map<const Vector3<T>>(blocks[j]);
  }
  return bias;
}

// The predicted gyro and accel of one sample (the header's model) in the scalar type T.
template <typename T>
void Predict(const FurtherImuSegment& s,
             const SegmentKnotData<T>& data,
             const FurtherImuSample& sample,
             T const* const* blocks,
             Vector3<T>* gyro,
             Vector3<T>* accel) {
  const BlockIndex b(s.bias_blocks);
  const T u = T(sample.u0) + blocks[b.time_offset][0] * T(1.0 / s.dt_s);
  const Segment<T> seg = MakeSegment(s.segment_index, u, s.dt_s);
  BodyMotion<T> motion;
  Matrix3<T> R_w_b;
  Vector3<T> a_b;
  internal::EvaluateSegmentBody(
      s.model, data.knots(), seg, nullptr, &R_w_b, &motion.w_b, &motion.dw_b, nullptr, &a_b);
  motion.f_b = a_b - R_w_b.transpose() * Eigen::Map<const Vector3<T>>(blocks[b.gravity]);
  ImuIntrinsics<T> p;
  p.C_i_b = RotationFromBlock(blocks[b.q_i_b]).matrix();
  p.r_b = Eigen::Map<const Vector3<T>>(blocks[b.r_b]);
  PredictImuReadings<T>(ImuModelKind::kCalibrated,
                        p,
                        motion,
                        Bias<T>(sample, s.bias_blocks, blocks + b.gyro_bias),
                        Bias<T>(sample, s.bias_blocks, blocks + b.accel_bias),
                        gyro,
                        accel);
}

struct FurtherImuResidual {
  explicit FurtherImuResidual(const FurtherImuSegment& s) : s(s) {}
  template <typename T>
  bool operator()(T const* const* blocks, T* residuals) const {
    const SegmentKnotData<T> data = internal::KnotDataFromBlocks(blocks);
    const T inv_gyro = T(1.0 / s.sigma_gyro);
    const T inv_accel = T(1.0 / s.sigma_accel);
    for (size_t k = 0; k < s.samples.size(); ++k) {
      Vector3<T> gyro;
      Vector3<T> accel;
      Predict(s, data, s.samples[k], blocks, &gyro, &accel);
      for (int r = 0; r < 3; ++r) {
        residuals[6 * k + r] = (gyro[r] - T(s.samples[k].gyro[r])) * inv_gyro;
        residuals[6 * k + 3 + r] = (accel[r] - T(s.samples[k].accel[r])) * inv_accel;
      }
    }
    return true;
  }
  FurtherImuSegment s;
};

}  // namespace

ceres::CostFunction* NewFurtherImuCost(const FurtherImuSegment& segment) {
  auto* cost = new ceres::DynamicAutoDiffCostFunction<FurtherImuResidual, kStride>(
      new FurtherImuResidual(segment));
  for (int j = 0; j < 4; ++j) cost->AddParameterBlock(kPoseBlockSize);
  for (int j = 0; j < 2 * segment.bias_blocks + 1; ++j) cost->AddParameterBlock(3);  // biases, g_w
  cost->AddParameterBlock(kRotationBlockSize);
  cost->AddParameterBlock(3);
  cost->AddParameterBlock(1);
  cost->SetNumResiduals(6 * static_cast<int>(segment.samples.size()));
  return cost;
}

void PredictFurtherImu(const FurtherImuSegment& segment,
                       const FurtherImuSample& sample,
                       double const* const* blocks,
                       Eigen::Vector3d* gyro,
                       Eigen::Vector3d* accel) {
  const SegmentKnotData<double> data = internal::KnotDataFromBlocks(blocks);
  Predict(segment, data, sample, blocks, gyro, accel);
}

}  // namespace splinecal

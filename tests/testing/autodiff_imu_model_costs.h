// The automatic-differentiation twins of Kalibr's IMU-model residuals
// (estimation/detail/imu_model_costs.h): the same residuals on the same parameter blocks, with
// the spline's body motion (w_b, dw_b, f_b) evaluated in the scalar type from the segment's four
// control poses and passed through the templated PredictImuReadings. They are the oracle the
// analytic Jacobians are tested against and the baseline the benchmark compares with. Test code
// only (kept apart from testing/autodiff_costs.h so that its Jets compile only where used).
#ifndef SPLINECAL_TESTS_TESTING_AUTODIFF_IMU_MODEL_COSTS_H_
#define SPLINECAL_TESTS_TESTING_AUTODIFF_IMU_MODEL_COSTS_H_

#include <ceres/cost_function.h>

#include <array>

#include "splinecal/estimation/detail/imu_costs.h"
#include "splinecal/estimation/detail/imu_model_costs.h"
#include "splinecal/estimation/detail/imu_model_intrinsics.h"
#include "splinecal/estimation/imu_model_parameters.h"
#include "splinecal/imu/imu_intrinsic_model.h"
#include "splinecal/spline/trajectory_evaluation.h"
#include "testing/autodiff_costs.h"

namespace splinecal {
namespace testing {

// (predicted - measured) / sigma of every sample of the segment, predicted by
// predict(motion, bias) from the spline's w_b, dw_b, f_b evaluated in scalar T: blocks 0..3 are
// the control poses, then the segment's bias points, then g_w.
template <typename T, typename Predict>
void ImuModelSegmentResiduals(const ImuModelSegment& s,
                              T const* const* blocks,
                              const Predict& predict,
                              T* residuals) {
  const SegmentKnotData<T> data = internal::KnotDataFromBlocks(blocks);
  const Vector3<T> g_w = Eigen::Map<const Vector3<T>>(blocks[4 + s.bias_blocks]);
  const T inv_sigma = T(1.0 / s.segment.sigma);
  for (size_t k = 0; k < s.samples.size(); ++k) {
    const ImuResidualSample& sample = s.samples[k];
    const Segment<T> seg = MakeSegment(s.segment.segment_index, T(sample.u), s.segment.dt_s);
    BodyMotion<T> motion;
    Matrix3<T> R_w_s;
    Vector3<T> a_s;
    internal::EvaluateSegmentBody(s.segment.model,
                                  data.knots(),
                                  seg,
                                  nullptr,
                                  &R_w_s,
                                  &motion.w_b,
                                  &motion.dw_b,
                                  nullptr,
                                  &a_s);
    motion.f_b = a_s - R_w_s.transpose() * g_w;
    const Vector3<T> bias = s.bias_blocks == 1 ? testing::WeightedBiasT<T, 1>(sample, blocks + 4)
                                               : testing::WeightedBiasT<T, 4>(sample, blocks + 4);
    const Vector3<T> predicted = predict(motion, bias);
    for (int r = 0; r < 3; ++r) {
      residuals[3 * k + r] = (predicted[r] - T(sample.measured[r])) * inv_sigma;
    }
  }
}

// Blocks: poses 0..3, gyro bias points, g_w, m_g, a, phi_gyro_i.
struct ImuModelGyroResidual {
  explicit ImuModelGyroResidual(const ImuModelSegment& s_in) : s(s_in) {}
  template <typename T>
  bool operator()(T const* const* blocks, T* residuals) const {
    const int nb = s.bias_blocks;
    const ImuModelParameters nominal;
    const std::array<T, 3> zero = {T(0.0), T(0.0), T(0.0)};
    std::array<T, kLowerTriangularParameters> m_a;
    for (int j = 0; j < kLowerTriangularParameters; ++j) m_a[j] = T(nominal.m_a[j]);
    const ImuIntrinsics<T> p = ImuModelParameters::Intrinsics<T>(
        m_a.data(), blocks[5 + nb], blocks[6 + nb], blocks[7 + nb], zero.data(), zero.data());
    ImuModelSegmentResiduals(
        s,
        blocks,
        [&](const BodyMotion<T>& motion, const Vector3<T>& bias) {
          Vector3<T> gyro;
          PredictImuReadings<T>(s.kind, p, motion, bias, Vector3<T>::Zero(), &gyro, nullptr);
          return gyro;
        },
        residuals);
    return true;
  }
  ImuModelSegment s;
};

// Blocks: poses 0..3, accel bias points, g_w, m_a (, ry_i, rz_i).
struct ImuModelAccelResidual {
  explicit ImuModelAccelResidual(const ImuModelSegment& s_in) : s(s_in) {}
  template <typename T>
  bool operator()(T const* const* blocks, T* residuals) const {
    const int nb = s.bias_blocks;
    const bool size_effect = s.kind == ImuModelKind::kScaleMisalignmentSizeEffect;
    const ImuModelParameters nominal;
    const std::array<T, 3> zero = {T(0.0), T(0.0), T(0.0)};
    std::array<T, kLowerTriangularParameters> m_g;
    std::array<T, kFullMatrixParameters> a;
    for (int j = 0; j < kLowerTriangularParameters; ++j) m_g[j] = T(nominal.m_g[j]);
    for (T& v : a) v = T(0.0);
    const ImuIntrinsics<T> p =
        ImuModelParameters::Intrinsics<T>(blocks[5 + nb],
                                          m_g.data(),
                                          a.data(),
                                          zero.data(),
                                          size_effect ? blocks[6 + nb] : zero.data(),
                                          size_effect ? blocks[7 + nb] : zero.data());
    ImuModelSegmentResiduals(
        s,
        blocks,
        [&](const BodyMotion<T>& motion, const Vector3<T>& bias) {
          Vector3<T> accel;
          PredictImuReadings<T>(s.kind, p, motion, Vector3<T>::Zero(), bias, nullptr, &accel);
          return accel;
        },
        residuals);
    return true;
  }
  ImuModelSegment s;
};

// The autodiff twins of NewImuModelGyroCost / NewImuModelAccelCost: the same blocks, in the same
// order, as the analytic cost of `segment` (caller owns the result). Defined in
// autodiff_imu_model_costs.cc, compiled once for every test and benchmark that uses them
// (testing/autodiff_costs.h says why).
ceres::CostFunction* NewAutoDiffImuModelGyroCost(const ImuModelSegment& segment);
ceres::CostFunction* NewAutoDiffImuModelAccelCost(const ImuModelSegment& segment);

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_TESTING_AUTODIFF_IMU_MODEL_COSTS_H_

#include "splinecal/estimation/detail/imu_model_costs.h"

#include <ceres/dynamic_autodiff_cost_function.h>

#include "splinecal/imu/imu_intrinsic_model.h"
#include "splinecal/imu/matrix_parameters.h"
#include "splinecal/lie/so3.h"
#include "splinecal/spline/trajectory_evaluation.h"

namespace splinecal {

template <typename T>
ImuIntrinsics<T> ImuModelParameters::Intrinsics(const T* m_a,
                                                const T* m_g,
                                                const T* a,
                                                const T* phi_gyro_i,
                                                const T* ry_i,
                                                const T* rz_i) {
  ImuIntrinsics<T> p;
  p.M_a = LowerTriangularFromParameters(m_a);
  p.M_g = LowerTriangularFromParameters(m_g);
  p.A = FullMatrixFromParameters(a);
  p.C_gyro_i = SO3<T>::Exp(Eigen::Map<const Vector3<T>>(phi_gyro_i)).matrix();
  p.ry_i = Eigen::Map<const Vector3<T>>(ry_i);
  p.rz_i = Eigen::Map<const Vector3<T>>(rz_i);
  return p;
}

ImuIntrinsicsd ImuModelParameters::Intrinsics() const {
  return Intrinsics(m_a.data(), m_g.data(), a.data(), phi_gyro_i.data(), ry_i.data(), rz_i.data());
}

namespace {

// (predicted - measured) / sigma of every sample of the segment, predicted by
// predict(motion, bias): blocks 0..3 are the control poses, then the segment's bias points,
// then g_w.
template <typename T, typename Predict>
void SegmentResiduals(const ImuModelSegment& s,
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
    internal::EvaluateSegmentBody(
        s.segment.model, data.knots(), seg, nullptr, &R_w_s, &motion.w_b, &motion.dw_b, nullptr, &a_s);
    motion.f_b = a_s - R_w_s.transpose() * g_w;
    const Vector3<T> bias = s.bias_blocks == 1 ? internal::WeightedBiasT<T, 1>(sample, blocks + 4)
                                               : internal::WeightedBiasT<T, 4>(sample, blocks + 4);
    const Vector3<T> predicted = predict(motion, bias);
    for (int r = 0; r < 3; ++r) {
      residuals[3 * k + r] = (predicted[r] - T(sample.measured[r])) * inv_sigma;
    }
  }
}

// Blocks: poses 0..3, gyro bias points, g_w, m_g, a, phi_gyro_i.
struct GyroModelResidual {
  explicit GyroModelResidual(const ImuModelSegment& s) : s(s) {}
  template <typename T>
  bool operator()(T const* const* blocks, T* residuals) const {
    const int nb = s.bias_blocks;
    const ImuModelParameters nominal;
    const std::array<T, 3> zero = {T(0.0), T(0.0), T(0.0)};
    std::array<T, kLowerTriangularParameters> m_a;
    for (int j = 0; j < kLowerTriangularParameters; ++j) m_a[j] = T(nominal.m_a[j]);
    const ImuIntrinsics<T> p = ImuModelParameters::Intrinsics<T>(
        m_a.data(), blocks[5 + nb], blocks[6 + nb], blocks[7 + nb], zero.data(), zero.data());
    SegmentResiduals(
        s, blocks,
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
struct AccelModelResidual {
  explicit AccelModelResidual(const ImuModelSegment& s) : s(s) {}
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
    const ImuIntrinsics<T> p = ImuModelParameters::Intrinsics<T>(
        blocks[5 + nb], m_g.data(), a.data(), zero.data(),
        size_effect ? blocks[6 + nb] : zero.data(), size_effect ? blocks[7 + nb] : zero.data());
    SegmentResiduals(
        s, blocks,
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

template <typename Functor>
ceres::CostFunction* NewCost(const ImuModelSegment& segment, const std::vector<int>& sizes) {
  auto* cost = new ceres::DynamicAutoDiffCostFunction<Functor, kImuModelStride>(
      new Functor(segment));
  for (int size : sizes) cost->AddParameterBlock(size);
  cost->SetNumResiduals(3 * static_cast<int>(segment.samples.size()));
  return cost;
}

std::vector<int> PoseAndBiasSizes(const ImuModelSegment& segment) {
  std::vector<int> sizes(4, kPoseBlockSize);
  for (int j = 0; j < segment.bias_blocks; ++j) sizes.push_back(3);
  sizes.push_back(3);  // g_w
  return sizes;
}

}  // namespace

ceres::CostFunction* NewImuModelGyroCost(const ImuModelSegment& segment) {
  std::vector<int> sizes = PoseAndBiasSizes(segment);
  sizes.insert(sizes.end(), {kLowerTriangularParameters, kFullMatrixParameters, 3});
  return NewCost<GyroModelResidual>(segment, sizes);
}

ceres::CostFunction* NewImuModelAccelCost(const ImuModelSegment& segment) {
  std::vector<int> sizes = PoseAndBiasSizes(segment);
  sizes.push_back(kLowerTriangularParameters);
  if (segment.kind == ImuModelKind::kScaleMisalignmentSizeEffect) sizes.insert(sizes.end(), {3, 3});
  return NewCost<AccelModelResidual>(segment, sizes);
}

}  // namespace splinecal

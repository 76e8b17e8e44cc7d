#include "splinecal/estimation/detail/imu_model_costs.h"

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <vector>

#include "splinecal/estimation/detail/imu_model_intrinsics.h"
#include "splinecal/estimation/detail/imu_model_motion.h"
#include "splinecal/imu/imu_intrinsic_model.h"
#include "splinecal/imu/imu_model.h"
#include "splinecal/imu/matrix_parameters.h"
#include "splinecal/lie/so3.h"
#include "splinecal/spline/angular_acceleration_jacobian.h"
#include "splinecal/spline/segment_jacobians.h"

namespace splinecal {

ImuIntrinsicsd ImuModelParameters::Intrinsics() const {
  return Intrinsics(m_a.data(), m_g.data(), a.data(), phi_gyro_i.data(), ry_i.data(), rz_i.data());
}

namespace {

template <int kCols>
using RowMajorRows = Eigen::Map<Eigen::Matrix<double, 3, kCols, Eigen::RowMajor>>;

void WriteBias(int bias_blocks,
               const ImuResidualSample& sample,
               double inv_sigma,
               double** bias_jacobians,
               int row) {
  if (bias_blocks == 1) {
    internal::WriteBiasJacobians<1>(sample, inv_sigma, bias_jacobians, row);
  } else {
    internal::WriteBiasJacobians<4>(sample, inv_sigma, bias_jacobians, row);
  }
}

// The gyro (kGyro) or accelerometer residuals of one segment under Kalibr's model, with the
// analytic Jacobians: the spline's motion Jacobians (spline/segment_jacobians.h steps 4 and 5,
// spline/angular_acceleration_jacobian.h) chained through the model's
// (imu/imu_intrinsic_model.h). Blocks as the header lists.
template <bool kGyro>
class ImuModelCostFunction : public ceres::CostFunction {
 public:
  explicit ImuModelCostFunction(const ImuModelSegment& segment) : s_(segment) {
    CHECK(!s_.samples.empty());
    CHECK(s_.bias_blocks == 1 || s_.bias_blocks == 4) << "bias_blocks must be 1 or 4";
    set_num_residuals(3 * static_cast<int>(s_.samples.size()));
    std::vector<int>& sizes = *mutable_parameter_block_sizes();
    sizes.assign(kSplineOrder, kPoseBlockSize);
    for (int j = 0; j < s_.bias_blocks; ++j) sizes.push_back(3);
    sizes.push_back(3);  // g_w
    if (kGyro) {
      sizes.insert(sizes.end(), {kLowerTriangularParameters, kFullMatrixParameters, 3});
    } else {
      sizes.push_back(kLowerTriangularParameters);
      if (SizeEffect()) sizes.insert(sizes.end(), {3, 3});
    }
  }

  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override {
    const int nb = s_.bias_blocks;
    const int model = kSplineOrder + nb + 1;  // first model block
    const bool pose_jacobians = internal::AnyPoseJacobian(jacobians);
    internal::SegmentEvaluation evaluation;
    internal::PrepareSegmentEvaluation(s_.segment, parameters, pose_jacobians, &evaluation);
    const ImuIntrinsicsd p = Intrinsics(parameters + model);
    const Eigen::Map<const Eigen::Vector3d> g_w(parameters[kSplineOrder + nb]);
    // The gyro reads f_b only through A.
    const bool f_pose_jacobian = pose_jacobians && (!kGyro || !p.A.isZero(0.0));
    // d C_gyro_i / d phi: C_gyro_i = Exp(phi) moves as C_gyro_i Exp(Jr(phi) dphi).
    const Eigen::Matrix3d Jr_gyro =
        kGyro ? RightJacobianSO3(Eigen::Map<const Eigen::Vector3d>(parameters[model + 2]))
              : Eigen::Matrix3d::Identity();
    const double inv_sigma = 1.0 / s_.segment.sigma;
    const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
    for (size_t k = 0; k < s_.samples.size(); ++k) {
      const ImuResidualSample& sample = s_.samples[k];
      const int row = 3 * static_cast<int>(k);
      const Segment<double> seg = MakeSegment(s_.segment.segment_index, sample.u, s_.segment.dt_s);
      internal::SampleMotion m;
      internal::EvaluateSampleMotion(
          s_.segment.model, evaluation.knots, seg, g_w, f_pose_jacobian, &m);
      const Eigen::Vector3d bias =
          nb == 1 ? internal::WeightedBias<1>(sample, parameters + kSplineOrder)
                  : internal::WeightedBias<4>(sample, parameters + kSplineOrder);
      Eigen::Vector3d predicted;
      ImuGyroJacobians Jg;
      ImuAccelJacobians Ja;
      if (kGyro) {
        PredictImuReadings(s_.kind,
                           p,
                           m.motion,
                           bias,
                           zero,
                           &predicted,
                           nullptr,
                           jacobians != nullptr ? &Jg : nullptr,
                           nullptr);
      } else {
        PredictImuReadings(s_.kind,
                           p,
                           m.motion,
                           zero,
                           bias,
                           nullptr,
                           &predicted,
                           nullptr,
                           jacobians != nullptr ? &Ja : nullptr);
      }
      Eigen::Map<Eigen::Vector3d>(residuals + row) = (predicted - sample.measured) * inv_sigma;
      if (jacobians == nullptr) continue;
      const Eigen::Matrix3d& J_f = kGyro ? Jg.f_b : Ja.f_b;
      if (pose_jacobians) {
        std::array<Eigen::Matrix<double, 3, 6>, kSplineOrder> J_pose;
        internal::ChainPoseJacobians<3>(evaluation.knots,
                      seg,
                      m,
                      kGyro ? Jg.w_b : Ja.w_b,
                      kGyro ? Jg.dw_b : Ja.dw_b,
                      J_f,
                      &J_pose);
        for (int c = 0; c < kSplineOrder; ++c) {
          if (jacobians[c] == nullptr) continue;
          internal::LiftPoseJacobian(
              J_pose[c] * inv_sigma, evaluation.lifts[c], jacobians[c] + kPoseBlockSize * row);
        }
      }
      WriteBias(nb, sample, inv_sigma, jacobians + kSplineOrder, row);
      if (double* J = jacobians[kSplineOrder + nb]; J != nullptr) {
        RowMajorRows<3>(J + 3 * row) = (J_f * m.J_f_gw) * inv_sigma;
      }
      double* const* J_model = jacobians + model;
      if (kGyro) {
        if (J_model[0] != nullptr) {
          RowMajorRows<kLowerTriangularParameters>(J_model[0] + kLowerTriangularParameters * row) =
              Jg.M_g * inv_sigma;
        }
        if (J_model[1] != nullptr) {
          RowMajorRows<kFullMatrixParameters>(J_model[1] + kFullMatrixParameters * row) =
              Jg.A * inv_sigma;
        }
        if (J_model[2] != nullptr) {
          RowMajorRows<3>(J_model[2] + 3 * row) = (Jg.phi_gyro_i * Jr_gyro) * inv_sigma;
        }
      } else {
        if (J_model[0] != nullptr) {
          RowMajorRows<kLowerTriangularParameters>(J_model[0] + kLowerTriangularParameters * row) =
              Ja.M_a * inv_sigma;
        }
        if (SizeEffect() && J_model[1] != nullptr) {
          RowMajorRows<3>(J_model[1] + 3 * row) = Ja.ry_i * inv_sigma;
        }
        if (SizeEffect() && J_model[2] != nullptr) {
          RowMajorRows<3>(J_model[2] + 3 * row) = Ja.rz_i * inv_sigma;
        }
      }
    }
    return true;
  }

 private:
  bool SizeEffect() const { return s_.kind == ImuModelKind::kScaleMisalignmentSizeEffect; }

  // The model's parameters from its blocks, the others nominal.
  ImuIntrinsicsd Intrinsics(double const* const* blocks) const {
    ImuModelParameters values;
    const auto copy = [](const double* from, auto* to) {
      std::copy(from, from + to->size(), to->begin());
    };
    if (kGyro) {
      copy(blocks[0], &values.m_g);
      copy(blocks[1], &values.a);
      copy(blocks[2], &values.phi_gyro_i);
    } else {
      copy(blocks[0], &values.m_a);
      if (SizeEffect()) {
        copy(blocks[1], &values.ry_i);
        copy(blocks[2], &values.rz_i);
      }
    }
    return values.Intrinsics();
  }

  ImuModelSegment s_;
};

}  // namespace

ceres::CostFunction* NewImuModelGyroCost(const ImuModelSegment& segment) {
  return new ImuModelCostFunction<true>(segment);
}

ceres::CostFunction* NewImuModelAccelCost(const ImuModelSegment& segment) {
  return new ImuModelCostFunction<false>(segment);
}

}  // namespace splinecal

#include "splinecal/estimation/detail/further_imu_cost.h"

#include <ceres/jet.h>
#include <glog/logging.h>

#include <Eigen/Core>
#include <array>
#include <optional>
#include <vector>

#include "splinecal/estimation/detail/imu_costs.h"
#include "splinecal/estimation/detail/imu_model_motion.h"
#include "splinecal/estimation/detail/pose_block_jacobian.h"
#include "splinecal/imu/matrix_parameters.h"
#include "splinecal/lie/so3.h"

namespace splinecal {
namespace {

using Dual = ceres::Jet<double, 1>;

template <int kCols>
using RowMajorRows = Eigen::Map<Eigen::Matrix<double, 6, kCols, Eigen::RowMajor>>;

template <typename T>
Vector3<T> WeightedBias(const FurtherImuSample& sample, int nb, T const* const* blocks) {
  Vector3<T> bias = Vector3<T>::Zero();
  for (int j = 0; j < nb; ++j) {
    bias += T(sample.bias_weights[j]) * Eigen::Map<const Vector3<T>>(blocks[j]);
  }
  return bias;
}

// The time offset's column of one sample, d pred / d time_offset = d pred / du / dt: the
// prediction with u a dual number (every other input constant).
Eigen::Matrix<double, 6, 1> TimeOffsetColumn(const FurtherImuSegment& s,
                                             const SegmentKnotData<Dual>& data,
                                             double u,
                                             const Vector3<Dual>& g_w,
                                             const ImuIntrinsics<Dual>& p,
                                             const Eigen::Vector3d& b_g,
                                             const Eigen::Vector3d& b_a) {
  const Dual u_dual(u, 0);
  Vector3<Dual> gyro;
  Vector3<Dual> accel;
  PredictFurtherImuAt<Dual>(
      s, data, u_dual, g_w, p, b_g.cast<Dual>(), b_a.cast<Dual>(), &gyro, &accel);
  Eigen::Matrix<double, 6, 1> column;
  for (int r = 0; r < 3; ++r) {
    column(r) = gyro[r].v[0] / s.dt_s;
    column(3 + r) = accel[r].v[0] / s.dt_s;
  }
  return column;
}

// The segment's four control poses as constant dual numbers.
SegmentKnotData<Dual> DualKnots(double const* const* poses) {
  std::array<std::array<Dual, kPoseBlockSize>, kSplineOrder> values;
  std::array<const Dual*, kSplineOrder> pointers;
  for (int k = 0; k < kSplineOrder; ++k) {
    for (int j = 0; j < kPoseBlockSize; ++j) values[k][j] = Dual(poses[k][j]);
    pointers[k] = values[k].data();
  }
  return internal::KnotDataFromBlocks(pointers.data());
}

class FurtherImuCostFunction : public ceres::CostFunction {
 public:
  explicit FurtherImuCostFunction(const FurtherImuSegment& segment) : s_(segment) {
    CHECK(!s_.samples.empty());
    CHECK(s_.bias_blocks == 1 || s_.bias_blocks == 4) << "bias_blocks must be 1 or 4";
    set_num_residuals(6 * static_cast<int>(s_.samples.size()));
    std::vector<int>& sizes = *mutable_parameter_block_sizes();
    sizes.assign(kSplineOrder, kPoseBlockSize);
    for (int j = 0; j < 2 * s_.bias_blocks + 1; ++j) sizes.push_back(3);  // biases, g_w
    sizes.insert(sizes.end(), {kRotationBlockSize, 3, 1});
    if (s_.kind != ImuModelKind::kCalibrated) {
      sizes.insert(sizes.end(),
                   {kLowerTriangularParameters, kLowerTriangularParameters,
                    kFullMatrixParameters, 3});
    }
    if (s_.kind == ImuModelKind::kScaleMisalignmentSizeEffect) sizes.insert(sizes.end(), {3, 3});
  }

  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override {
    const int nb = s_.bias_blocks;
    const FurtherImuBlockIndex b(nb);
    const bool pose_jacobians = internal::AnyPoseJacobian(jacobians);
    ImuResidualSegment shared;  // the knots from the blocks (no shared cache)
    shared.segment_index = s_.segment_index;
    shared.dt_s = s_.dt_s;
    shared.model = s_.model;
    internal::SegmentEvaluation evaluation;
    internal::PrepareSegmentEvaluation(shared, parameters, pose_jacobians, &evaluation);
    const ImuIntrinsicsd p = FurtherImuIntrinsics<double>(s_.kind, nb, parameters);
    const Eigen::Map<const Eigen::Vector3d> g_w(parameters[b.gravity]);
    const double tau = parameters[b.time_offset][0];
    if (jacobians != nullptr) {
      const std::vector<int32_t>& sizes = parameter_block_sizes();
      for (size_t j = 0; j < sizes.size(); ++j) {
        if (jacobians[j] == nullptr) continue;
        Eigen::Map<Eigen::MatrixXd>(jacobians[j], num_residuals(), sizes[j]).setZero();
      }
    }
    const bool time_column = jacobians != nullptr && jacobians[b.time_offset] != nullptr;
    std::optional<SegmentKnotData<Dual>> dual_knots;
    ImuIntrinsics<Dual> dual_p;
    if (time_column) {
      dual_knots.emplace(DualKnots(parameters));
      dual_p = p.cast<Dual>();
    }
    // C_i_b Exp(dphi): the ambient quaternion's Jacobian through the manifold's Minus Jacobian.
    const Eigen::Matrix<double, 3, 4> dphi_dq =
        internal::QuaternionRightMinusJacobian(RotationFromBlock(parameters[b.q_i_b]).quaternion());
    const Eigen::Matrix3d Jr_gyro =
        s_.kind != ImuModelKind::kCalibrated
            ? RightJacobianSO3(Eigen::Map<const Eigen::Vector3d>(parameters[b.phi_gyro_i]))
            : Eigen::Matrix3d::Identity();
    Eigen::Matrix<double, 6, 6> inv_sigma = Eigen::Matrix<double, 6, 6>::Zero();
    inv_sigma.diagonal() << Eigen::Vector3d::Constant(1.0 / s_.sigma_gyro),
        Eigen::Vector3d::Constant(1.0 / s_.sigma_accel);
    const Eigen::Matrix<double, 6, 1> w = inv_sigma.diagonal();
    for (size_t k = 0; k < s_.samples.size(); ++k) {
      const FurtherImuSample& sample = s_.samples[k];
      const int row = 6 * static_cast<int>(k);
      const double u = sample.u0 + tau / s_.dt_s;
      const Segment<double> seg = MakeSegment(s_.segment_index, u, s_.dt_s);
      internal::SampleMotion m;
      internal::EvaluateSampleMotion(s_.model, evaluation.knots, seg, g_w, pose_jacobians, &m);
      const Eigen::Vector3d b_g = WeightedBias(sample, nb, parameters + b.gyro_bias);
      const Eigen::Vector3d b_a = WeightedBias(sample, nb, parameters + b.accel_bias);
      Eigen::Vector3d gyro;
      Eigen::Vector3d accel;
      ImuGyroJacobians Jg;
      ImuAccelJacobians Ja;
      const bool want = jacobians != nullptr;
      PredictImuReadings(s_.kind, p, m.motion, b_g, b_a, &gyro, &accel, want ? &Jg : nullptr,
                         want ? &Ja : nullptr);
      Eigen::Map<Eigen::Matrix<double, 6, 1>> r(residuals + row);
      r << gyro - sample.gyro, accel - sample.accel;
      r = r.cwiseProduct(w);
      if (!want) continue;
      // Each input's 6x3 Jacobian: gyro rows over accelerometer rows, weighted.
      const auto stack = [&](const auto& top, const auto& bottom) {
        Eigen::Matrix<double, 6, Eigen::Dynamic> J(6, top.cols());
        J << top, bottom;
        return Eigen::Matrix<double, 6, Eigen::Dynamic>(inv_sigma * J);
      };
      if (pose_jacobians) {
        Eigen::Matrix<double, 6, 3> J_w;
        Eigen::Matrix<double, 6, 3> J_dw;
        Eigen::Matrix<double, 6, 3> J_f;
        J_w << Jg.w_b, Ja.w_b;
        J_dw << Jg.dw_b, Ja.dw_b;
        J_f << Jg.f_b, Ja.f_b;
        std::array<Eigen::Matrix<double, 6, 6>, kSplineOrder> J_pose;
        internal::ChainPoseJacobians<6>(evaluation.knots, seg, m, J_w, J_dw, J_f, &J_pose);
        for (int c = 0; c < kSplineOrder; ++c) {
          if (jacobians[c] == nullptr) continue;
          internal::LiftPoseJacobian(
              Eigen::Matrix<double, 6, 6>(inv_sigma * J_pose[c]),
              evaluation.lifts[c],
              jacobians[c] + kPoseBlockSize * row);
        }
      }
      for (int j = 0; j < nb; ++j) {
        const double wj = sample.bias_weights[j];
        if (double* J = jacobians[b.gyro_bias + j]; J != nullptr) {
          Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(J + 3 * row) =
              (wj * w(0)) * Eigen::Matrix3d::Identity();
        }
        if (double* J = jacobians[b.accel_bias + j]; J != nullptr) {
          Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(J + 3 * (row + 3)) =
              (wj * w(3)) * Eigen::Matrix3d::Identity();
        }
      }
      if (double* J = jacobians[b.gravity]; J != nullptr) {
        RowMajorRows<3>(J + 3 * row) = stack(Jg.f_b * m.J_f_gw, Ja.f_b * m.J_f_gw);
      }
      if (double* J = jacobians[b.q_i_b]; J != nullptr) {
        RowMajorRows<4>(J + 4 * row) = stack(Jg.phi_i_b, Ja.phi_i_b) * dphi_dq;
      }
      if (double* J = jacobians[b.r_b]; J != nullptr) {
        RowMajorRows<3>(J + 3 * row) = stack(Jg.r_b, Ja.r_b);
      }
      if (time_column) {
        Eigen::Map<Eigen::Matrix<double, 6, 1>>(jacobians[b.time_offset] + row) =
            inv_sigma * TimeOffsetColumn(s_, *dual_knots, u, g_w.cast<Dual>(), dual_p, b_g, b_a);
      }
      if (s_.kind == ImuModelKind::kCalibrated) continue;
      const Eigen::Matrix<double, 3, kLowerTriangularParameters> zero6 =
          Eigen::Matrix<double, 3, kLowerTriangularParameters>::Zero();
      const Eigen::Matrix3d zero3 = Eigen::Matrix3d::Zero();
      if (double* J = jacobians[b.m_a]; J != nullptr) {
        RowMajorRows<kLowerTriangularParameters>(J + kLowerTriangularParameters * row) =
            stack(zero6, Ja.M_a);
      }
      if (double* J = jacobians[b.m_g]; J != nullptr) {
        RowMajorRows<kLowerTriangularParameters>(J + kLowerTriangularParameters * row) =
            stack(Jg.M_g, zero6);
      }
      if (double* J = jacobians[b.a]; J != nullptr) {
        RowMajorRows<kFullMatrixParameters>(J + kFullMatrixParameters * row) =
            stack(Jg.A, Eigen::Matrix<double, 3, kFullMatrixParameters>::Zero());
      }
      if (double* J = jacobians[b.phi_gyro_i]; J != nullptr) {
        RowMajorRows<3>(J + 3 * row) = stack(Eigen::Matrix3d(Jg.phi_gyro_i * Jr_gyro), zero3);
      }
      if (s_.kind != ImuModelKind::kScaleMisalignmentSizeEffect) continue;
      if (double* J = jacobians[b.ry_i]; J != nullptr) {
        RowMajorRows<3>(J + 3 * row) = stack(zero3, Ja.ry_i);
      }
      if (double* J = jacobians[b.rz_i]; J != nullptr) {
        RowMajorRows<3>(J + 3 * row) = stack(zero3, Ja.rz_i);
      }
    }
    return true;
  }

 private:
  FurtherImuSegment s_;
};

}  // namespace

ceres::CostFunction* NewFurtherImuCost(const FurtherImuSegment& segment) {
  return new FurtherImuCostFunction(segment);
}

void PredictFurtherImu(const FurtherImuSegment& segment,
                       const FurtherImuSample& sample,
                       double const* const* blocks,
                       Eigen::Vector3d* gyro,
                       Eigen::Vector3d* accel) {
  const int nb = segment.bias_blocks;
  const FurtherImuBlockIndex b(nb);
  const SegmentKnotData<double> data = internal::KnotDataFromBlocks(blocks);
  PredictFurtherImuAt<double>(segment,
                              data,
                              sample.u0 + blocks[b.time_offset][0] / segment.dt_s,
                              Eigen::Map<const Eigen::Vector3d>(blocks[b.gravity]),
                              FurtherImuIntrinsics<double>(segment.kind, nb, blocks),
                              WeightedBias(sample, nb, blocks + b.gyro_bias),
                              WeightedBias(sample, nb, blocks + b.accel_bias),
                              gyro,
                              accel);
}

}  // namespace splinecal

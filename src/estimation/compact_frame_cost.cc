#include "splinecal/estimation/detail/compact_frame_cost.h"

#include <Eigen/Core>
#include <Eigen/Householder>
#include <Eigen/QR>
#include <algorithm>
#include <utility>
#include <vector>

#include "splinecal/camera/camera_model.h"
#include "splinecal/estimation/detail/pose_block_jacobian.h"

namespace splinecal {

namespace {

// Rows the compact form may need: g = 6 + 6 (T_w_t) + kNumIntrinsics columns of G, plus |q_rest|.
constexpr int kMaxCompactRows = 6 + 6 + kNumIntrinsics + 1;

// Writes the tangent Jacobian of a pose block, lifted to its 7 ambient columns
// (estimation/detail/pose_block_jacobian.h).
void WritePoseBlock(const Eigen::MatrixXd& J_tangent, const double* block, double* jacobian) {
  if (jacobian == nullptr) return;
  internal::LiftPoseJacobian(J_tangent, internal::MakePoseBlockLift(block), jacobian);
}

}  // namespace

const ceres::CostFunction& CompactResidual::RowsOf(const ceres::CostFunction& cost) {
  const auto* compact = dynamic_cast<const CompactResidual*>(&cost);
  return compact != nullptr ? compact->rows() : cost;
}

CompactFrameCostFunction::CompactFrameCostFunction(std::unique_ptr<TargetFrameCostFunction> frame)
    : frame_(std::move(frame)) {
  *mutable_parameter_block_sizes() = frame_->parameter_block_sizes();
  set_num_residuals(std::min(frame_->num_residuals(), kMaxCompactRows));
}

bool CompactFrameCostFunction::SavesRows(const TargetFrameCostFunction& frame) {
  return frame.num_residuals() > kMaxCompactRows;
}

bool CompactFrameCostFunction::Evaluate(double const* const* parameters,
                                        double* residuals,
                                        double** jacobians) const {
  const int rows = num_residuals();
  std::fill(residuals, residuals + rows, 0.0);
  if (jacobians == nullptr) {
    Eigen::VectorXd r(frame_->num_residuals());
    if (!frame_->Evaluate(parameters, r.data(), nullptr)) return false;
    residuals[0] = r.norm();
    return true;
  }
  const int n = frame_->window().num_poses;
  // Parameter blocks: control poses, T_cam_imu, time offset, line delay, T_w_t[, intrinsics].
  if (jacobians[n + 2] != nullptr) return false;  // a line delay held at 0 only (header)
  const bool with_target_pose = jacobians[n + 3] != nullptr;
  const bool with_intrinsics =
      parameter_block_sizes().size() > static_cast<size_t>(n + 4) && jacobians[n + 4] != nullptr;
  TargetFrameCostFunction::GlobalShutterLinearization frame;
  if (!frame_->LinearizeGlobalShutter(parameters, with_target_pose, with_intrinsics, &frame)) {
    return false;
  }
  const int g = static_cast<int>(frame.G.cols());
  if (frame.G.rows() <= g) return false;  // too few corners to compact (not built so)
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(frame.G);
  const Eigen::MatrixXd R = qr.matrixQR().topRows(g).triangularView<Eigen::Upper>();
  const Eigen::VectorXd q = qr.householderQ().adjoint() * frame.r;
  Eigen::Map<Eigen::VectorXd>(residuals, g) = q.head(g);
  residuals[g] = q.tail(q.size() - g).norm();

  for (size_t k = 0; k < parameter_block_sizes().size(); ++k) {
    if (jacobians[k] != nullptr) {
      std::fill(jacobians[k], jacobians[k] + rows * parameter_block_sizes()[k], 0.0);
    }
  }
  // Only the first g rows carry Jacobians; the map views them as rows x size, row-major.
  const Eigen::MatrixXd R_e = R.leftCols<6>();  // d r' / d e
  for (int b = 0; b < kSplineOrder; ++b) {
    const int slot = frame.J_pose.first_index + b - frame_->window().first_index;
    WritePoseBlock(R_e * frame.J_pose.blocks[b], parameters[slot], jacobians[slot]);
  }
  WritePoseBlock(-R_e, parameters[n], jacobians[n]);  // T_cam_imu: -d / d e
  if (jacobians[n + 1] != nullptr) {
    Eigen::Map<Eigen::VectorXd>(jacobians[n + 1], g) = R_e * frame.xi;
  }
  if (with_target_pose) {
    WritePoseBlock(R.middleCols<6>(6), parameters[n + 3], jacobians[n + 3]);
  }
  if (with_intrinsics) {
    Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, kNumIntrinsics, Eigen::RowMajor>>(
        jacobians[n + 4], g, kNumIntrinsics) = R.rightCols<kNumIntrinsics>();
  }
  return true;
}

}  // namespace splinecal

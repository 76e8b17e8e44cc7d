// How an ImuCovariance (calib/imu_covariance.h) is cut out of the calibration's reported
// covariance, and the per-entry standard deviations (ImuModelStd) read off its diagonal: shared by
// the reference IMU's model (calibration_results.cc) and the further IMUs (further_imus.cc).
// Private to src/calib/.
#ifndef SPLINECAL_SRC_CALIB_IMU_COVARIANCE_ROWS_H_
#define SPLINECAL_SRC_CALIB_IMU_COVARIANCE_ROWS_H_

#include <Eigen/Core>
#include <map>
#include <vector>

#include "splinecal/calib/calibrate.h"
#include "splinecal/calib/imu_covariance.h"
#include "splinecal/estimation/imu_model_parameters.h"
#include "splinecal/imu/imu_model_kind.h"

namespace splinecal {
namespace internal {

// One parameter block and the entry of each of its coordinates, in the block's order.
struct CovarianceBlock {
  const double* block = nullptr;
  std::vector<ImuCovarianceEntry> coordinates;
  std::vector<int> held;  // coordinates held (sorted): not in the block's tangent
};

// The blocks of a model (none for kCalibrated), in ImuCovariance's order: m_a, m_g, a,
// phi_gyro_i (, ry_i, rz_i). `held(block)` gives a block's held coordinates.
template <typename HeldFn>
std::vector<CovarianceBlock> ModelCovarianceBlocks(ImuModelKind kind,
                                                   const ImuModelParameters& p,
                                                   HeldFn held);

// Cuts the entries of `blocks` out of `cov` (rows offset.at(block) on, a held coordinate
// skipped as ceres::SubsetManifold's tangent does); a block not in `offset` (constant) has no row.
ImuCovariance CovarianceOfBlocks(const Eigen::MatrixXd& cov,
                                 const std::map<const double*, int>& offset,
                                 const std::vector<CovarianceBlock>& blocks);

// The model's stds from the covariance's diagonal: sqrt(max(0, diagonal)), rotations in degrees;
// NaN for an entry without a row.
ImuModelStd ModelStdOf(const ImuCovariance& covariance);

// The coordinates of a vector parameter (3) and of a lower-triangular or full 3x3 matrix in
// imu/matrix_parameters.h's layouts.
std::vector<ImuCovarianceEntry> VectorCoordinates(ImuParameter parameter, int size);
std::vector<ImuCovarianceEntry> LowerTriangleCoordinates(ImuParameter parameter);
std::vector<ImuCovarianceEntry> FullMatrixCoordinates(ImuParameter parameter);

template <typename HeldFn>
std::vector<CovarianceBlock> ModelCovarianceBlocks(ImuModelKind kind,
                                                   const ImuModelParameters& p,
                                                   HeldFn held) {
  if (kind == ImuModelKind::kCalibrated) return {};
  std::vector<CovarianceBlock> blocks = {
      {p.m_a.data(), LowerTriangleCoordinates(ImuParameter::kMa), {}},
      {p.m_g.data(), LowerTriangleCoordinates(ImuParameter::kMg), {}},
      {p.a.data(), FullMatrixCoordinates(ImuParameter::kA), {}},
      {p.phi_gyro_i.data(), VectorCoordinates(ImuParameter::kCGyroI, 3), {}}};
  if (kind == ImuModelKind::kScaleMisalignmentSizeEffect) {
    blocks.push_back({p.ry_i.data(), VectorCoordinates(ImuParameter::kRyI, 3), {}});
    blocks.push_back({p.rz_i.data(), VectorCoordinates(ImuParameter::kRzI, 3), {}});
  }
  for (CovarianceBlock& b : blocks) b.held = held(b.block);
  return blocks;
}

}  // namespace internal
}  // namespace splinecal

#endif  // SPLINECAL_SRC_CALIB_IMU_COVARIANCE_ROWS_H_

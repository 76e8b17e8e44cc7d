// The joint covariance of an IMU's estimated calibration parameters, as `splinecal calibrate`
// reports it (CalibrationResult::imu_model_covariance, FurtherImuEstimate::covariance): the
// block of the calibration's marginal covariance (calib/calibrate.h, the same matrix, inflation
// factors included, that the per-entry standard deviations are the square roots of the diagonal
// of) over one IMU's parameters, cross-covariances included; exactly symmetric. docs/imu_models.md
// says how to read it.
#ifndef SPLINECAL_CALIB_IMU_COVARIANCE_H_
#define SPLINECAL_CALIB_IMU_COVARIANCE_H_

#include <Eigen/Core>
#include <string>
#include <vector>

namespace splinecal {

// A parameter of an IMU's calibration (imu/imu_intrinsics.h, ImuCalibration) with a row in an
// ImuCovariance. Units are SI; rotations are rotation vectors in radians.
enum class ImuParameter {
  kMa,          // M_a, the accelerometer's scale/misalignment, lower triangle [1]
  kMg,          // M_g, the gyroscope's, lower triangle [1]
  kA,           // A, the gyroscope's g-sensitivity, all 9 entries [rad/s per m/s^2]
  kCGyroI,      // phi, C_gyro_i = Exp(phi) [rad] (the model's parameter itself)
  kRyI,         // ry_i, the accelerometers' size effect [m]
  kRzI,         // rz_i [m]
  kCIB,         // phi, C_i_b's right tangent C_i_b Exp(phi) (b axes) [rad] (a further IMU)
  kRB,          // r_b, the lever arm [m] (a further IMU; absent when held)
  kTimeOffset,  // time_offset_s [s] (a further IMU)
};

// One row (and column) of an ImuCovariance: a parameter's entry (row, col) of a matrix (M_a,
// M_g: row >= col; A), or its component `row` of a vector (col 0), 0 for the time offset.
struct ImuCovarianceEntry {
  ImuParameter parameter = ImuParameter::kMa;
  int row = 0;
  int col = 0;
};

// Its name as the docs and result.yaml write it: "M_a(1,0)", "A(2,1)", "C_gyro_i.phi(0)",
// "ry_i(2)", "C_i_b.phi(1)", "r_b(0)", "time_offset".
std::string ImuCovarianceEntryName(const ImuCovarianceEntry& entry);

// The covariance of the estimated entries only: an entry held at its nominal value (estimation/
// imu_model_observability.h) or a held lever arm has no row; empty (no entries) when the
// covariance was not computed or nothing is estimated (the `calibrated` model of the reference).
// Rows follow `entries`: for a further IMU C_i_b's phi, r_b, the time offset, then the model's
// entries; the model's in the order M_a, M_g (row-major lower triangles), A (row-major),
// C_gyro_i's phi, ry_i, rz_i. The diagonal's square roots are the reported standard deviations
// bit for bit (rotations: std_deg = sqrt(diagonal) * kRadToDeg).
//
// The error whose covariance it is: estimate - truth for the vector and matrix entries and for
// C_gyro_i's phi (Log(C_gyro_i) of each: phi itself is the parameter); Log(C_true^T C_est) for
// C_i_b (its right tangent).
struct ImuCovariance {
  std::vector<ImuCovarianceEntry> entries;
  Eigen::MatrixXd matrix;  // entries.size() x entries.size()

  bool empty() const { return entries.empty(); }
  // The rows of the entries of `parameters`, in the order of `entries`.
  std::vector<int> Rows(const std::vector<ImuParameter>& parameters) const;
  // The covariance of the entries of `parameters` (e.g. {kRyI, kRzI}: the size effect's lever
  // arms, cross terms included), in the order of `entries`; 0 x 0 when none is estimated.
  Eigen::MatrixXd Block(const std::vector<ImuParameter>& parameters) const;
};

}  // namespace splinecal

#endif  // SPLINECAL_CALIB_IMU_COVARIANCE_H_

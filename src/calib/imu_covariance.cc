#include "splinecal/calib/imu_covariance.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "imu_covariance_rows.h"
#include "splinecal/imu/matrix_parameters.h"
#include "splinecal/units.h"

namespace splinecal {

std::string ImuCovarianceEntryName(const ImuCovarianceEntry& entry) {
  const std::string r = std::to_string(entry.row);
  const std::string rc = "(" + r + "," + std::to_string(entry.col) + ")";
  switch (entry.parameter) {
    case ImuParameter::kMa:
      return "M_a" + rc;
    case ImuParameter::kMg:
      return "M_g" + rc;
    case ImuParameter::kA:
      return "A" + rc;
    case ImuParameter::kCGyroI:
      return "C_gyro_i.phi(" + r + ")";
    case ImuParameter::kRyI:
      return "ry_i(" + r + ")";
    case ImuParameter::kRzI:
      return "rz_i(" + r + ")";
    case ImuParameter::kCIB:
      return "C_i_b.phi(" + r + ")";
    case ImuParameter::kRB:
      return "r_b(" + r + ")";
    case ImuParameter::kTimeOffset:
      return "time_offset";
  }
  return "?";
}

std::vector<int> ImuCovariance::Rows(const std::vector<ImuParameter>& parameters) const {
  std::vector<int> rows;
  for (size_t k = 0; k < entries.size(); ++k) {
    if (std::find(parameters.begin(), parameters.end(), entries[k].parameter) != parameters.end()) {
      rows.push_back(static_cast<int>(k));
    }
  }
  return rows;
}

Eigen::MatrixXd ImuCovariance::Block(const std::vector<ImuParameter>& parameters) const {
  const std::vector<int> rows = Rows(parameters);
  const int n = static_cast<int>(rows.size());
  Eigen::MatrixXd block(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) block(i, j) = matrix(rows[i], rows[j]);
  }
  return block;
}

namespace internal {

std::vector<ImuCovarianceEntry> VectorCoordinates(ImuParameter parameter, int size) {
  std::vector<ImuCovarianceEntry> coordinates;
  for (int a = 0; a < size; ++a) coordinates.push_back({parameter, a, 0});
  return coordinates;
}

std::vector<ImuCovarianceEntry> LowerTriangleCoordinates(ImuParameter parameter) {
  std::vector<ImuCovarianceEntry> coordinates(kLowerTriangularParameters);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c <= r; ++c) coordinates[LowerTriangularIndex(r, c)] = {parameter, r, c};
  }
  return coordinates;
}

std::vector<ImuCovarianceEntry> FullMatrixCoordinates(ImuParameter parameter) {
  // imu/matrix_parameters.h: row-major.
  std::vector<ImuCovarianceEntry> coordinates;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) coordinates.push_back({parameter, r, c});
  }
  return coordinates;
}

ImuCovariance CovarianceOfBlocks(const Eigen::MatrixXd& cov,
                                 const std::map<const double*, int>& offset,
                                 const std::vector<CovarianceBlock>& blocks) {
  ImuCovariance out;
  std::vector<int> rows;  // in cov
  for (const CovarianceBlock& b : blocks) {
    const auto it = offset.find(b.block);
    if (it == offset.end()) continue;
    int row = it->second;
    for (size_t j = 0; j < b.coordinates.size(); ++j) {
      if (std::find(b.held.begin(), b.held.end(), static_cast<int>(j)) != b.held.end()) continue;
      out.entries.push_back(b.coordinates[j]);
      rows.push_back(row++);
    }
  }
  // Made exactly symmetric (the marginal covariance is symmetric only to rounding, ~1e-16
  // relative); the diagonal is taken as it is, so its square roots are the reported stds.
  const int n = static_cast<int>(rows.size());
  out.matrix.resize(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      out.matrix(i, j) = 0.5 * (cov(rows[i], rows[j]) + cov(rows[j], rows[i]));
    }
  }
  return out;
}

ImuModelStd ModelStdOf(const ImuCovariance& covariance) {
  ImuModelStd out;
  for (size_t k = 0; k < covariance.entries.size(); ++k) {
    const ImuCovarianceEntry& e = covariance.entries[k];
    const double s = std::sqrt(std::max(0.0, covariance.matrix(k, k)));
    switch (e.parameter) {
      case ImuParameter::kMa:
        out.M_a(e.row, e.col) = s;
        break;
      case ImuParameter::kMg:
        out.M_g(e.row, e.col) = s;
        break;
      case ImuParameter::kA:
        out.A(e.row, e.col) = s;
        break;
      case ImuParameter::kCGyroI:
        out.C_gyro_i_deg[e.row] = s * kRadToDeg;
        break;
      case ImuParameter::kRyI:
        out.ry_i[e.row] = s;
        break;
      case ImuParameter::kRzI:
        out.rz_i[e.row] = s;
        break;
      default:  // not the model's (a further IMU's pose and clock)
        break;
    }
  }
  return out;
}

}  // namespace internal
}  // namespace splinecal

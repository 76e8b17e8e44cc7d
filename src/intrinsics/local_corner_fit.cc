#include "splinecal/intrinsics/local_corner_fit.h"

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace splinecal {
namespace {

// A point more than this far off the plane z = 0, relative to the neighbourhood's extent, is not
// on a planar target.
constexpr double kPlanarTolerance = 1e-6;

}  // namespace

std::vector<Eigen::Vector2d> LocalFitResiduals(const std::vector<Eigen::Vector3d>& p_t,
                                               const std::vector<Eigen::Vector2d>& uv) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  const int n = static_cast<int>(p_t.size());
  std::vector<Eigen::Vector2d> residuals(n, Eigen::Vector2d::Constant(kNaN));
  if (n < kLocalFitNeighbours + 1 || uv.size() != p_t.size()) return residuals;
  std::vector<int> order(n);
  std::vector<double> distance_sq(n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) distance_sq[j] = (p_t[j] - p_t[i]).head<2>().squaredNorm();
    std::iota(order.begin(), order.end(), 0);
    // The corner itself is at distance 0: the first after sorting, skipped below.
    std::partial_sort(order.begin(),
                      order.begin() + kLocalFitNeighbours + 1,
                      order.end(),
                      [&](int a, int b) { return distance_sq[a] < distance_sq[b]; });
    const double extent = std::sqrt(distance_sq[order[kLocalFitNeighbours]]);
    if (!(extent > 0.0)) continue;  // repeated points
    bool planar = std::abs(p_t[i].z()) <= kPlanarTolerance * extent;
    Eigen::Matrix<double, kLocalFitNeighbours, 6> A;
    Eigen::Matrix<double, kLocalFitNeighbours, 2> b;
    int row = 0;
    for (int k = 0; k <= kLocalFitNeighbours; ++k) {
      const int j = order[k];
      if (j == i) continue;
      if (row == kLocalFitNeighbours) break;  // a repeated point took the corner's place
      planar = planar && std::abs(p_t[j].z()) <= kPlanarTolerance * extent;
      // Coordinates in units of the neighbourhood's extent: a well-conditioned design.
      const double dx = (p_t[j].x() - p_t[i].x()) / extent;
      const double dy = (p_t[j].y() - p_t[i].y()) / extent;
      A.row(row) << 1.0, dx, dy, dx * dx, dx * dy, dy * dy;
      b.row(row) = uv[j].transpose();
      ++row;
    }
    if (!planar || row < kLocalFitNeighbours) continue;
    Eigen::ColPivHouseholderQR<Eigen::Matrix<double, kLocalFitNeighbours, 6>> qr(A);
    // Neighbours on one line (or on two, for the quadratic terms) leave the fit undetermined.
    qr.setThreshold(1e-6);
    if (qr.rank() < 6) continue;
    const Eigen::Matrix<double, 6, 2> coefficients = qr.solve(b);
    // The prediction's noise gain: h = e0^T (A^T A)^-1 e0 (header).
    const Eigen::Matrix<double, 6, 6> information = A.transpose() * A;
    const double h = information.ldlt().solve(Eigen::Matrix<double, 6, 1>::Unit(0))(0);
    residuals[i] = (uv[i] - coefficients.row(0).transpose()) / std::sqrt(1.0 + h);
  }
  return residuals;
}

}  // namespace splinecal

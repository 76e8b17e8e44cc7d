#include "information_factor.h"

#include <Eigen/OrderingMethods>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <utility>

#include "splinecal/error.h"

namespace splinecal {
namespace internal {
namespace {

// Pivots below this fraction of their diagonal entry are rounding, not information: H is
// treated as singular (double precision leaves ~1e-16 relative where a direction is exactly
// undetermined).
constexpr double kMinRelativePivot = 1e-14;

}  // namespace

std::vector<int> BlockEliminationOrder(int num_blocks,
                                       const std::vector<std::vector<int>>& cliques) {
  // The block graph's pattern: the blocks of a clique are pairwise coupled.
  std::vector<std::vector<int>> neighbours(num_blocks);
  for (const std::vector<int>& clique : cliques) {
    for (int a : clique) neighbours[a].insert(neighbours[a].end(), clique.begin(), clique.end());
  }
  std::vector<int> outer(num_blocks + 1, 0);
  for (int b = 0; b < num_blocks; ++b) {
    std::vector<int>& row = neighbours[b];
    row.push_back(b);  // every block on the diagonal, coupled or not
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
    outer[b + 1] = outer[b] + static_cast<int>(row.size());
  }
  std::vector<int> inner;
  inner.reserve(outer[num_blocks]);
  for (const std::vector<int>& row : neighbours) inner.insert(inner.end(), row.begin(), row.end());
  const std::vector<double> values(inner.size(), 1.0);
  const Eigen::SparseMatrix<double> graph = Eigen::Map<const Eigen::SparseMatrix<double>>(
      num_blocks, num_blocks, static_cast<Eigen::Index>(inner.size()), outer.data(),
      inner.data(), values.data());
  // Eigen's AMD returns the inverse permutation: entry k is the block eliminated k-th.
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> eliminated;
  Eigen::AMDOrdering<int> amd;
  amd(graph, eliminated);
  return std::vector<int>(eliminated.indices().data(),
                          eliminated.indices().data() + num_blocks);
}

InformationFactor::InformationFactor(const Eigen::SparseMatrix<double>& H) {
  if (H.rows() != H.cols()) return;
  ldlt_.compute(H);
  if (ldlt_.info() != Eigen::Success) return;
  diagonal_ = ldlt_.vectorD();
  // LDL^T does not check definiteness. A pivot is H_jj less what the columns eliminated before
  // explain of column j; one that is not positive, or that rounding alone could have left
  // (kMinRelativePivot of H_jj), means a direction the data does not determine.
  const Eigen::VectorXd h = H.diagonal();
  ok_ = true;
  for (Eigen::Index j = 0; j < diagonal_.size(); ++j) {
    if (!(diagonal_[j] > kMinRelativePivot * h[j] && std::isfinite(diagonal_[j]))) ok_ = false;
  }
}

Eigen::MatrixXd InformationFactor::Solve(const Eigen::MatrixXd& B) const {
  if (!ok_) return Eigen::MatrixXd();
  return ldlt_.solve(B);
}

bool InformationFactor::ComputeSelectedInverse() {
  if (!ok_) return false;
  if (!inverse_.empty() || size() == 0) return true;
  // L's strictly lower entries by column, rows ascending (Eigen's up-looking factorisation
  // appends row k to each column in increasing k); the unit diagonal is not stored.
  const Eigen::SparseMatrix<double>& L = ldlt_.matrixL().nestedExpression();
  const int* start = L.outerIndexPtr();
  const int* row = L.innerIndexPtr();
  const double* value = L.valuePtr();
  const int n = static_cast<int>(size());
  inverse_.assign(static_cast<size_t>(start[n]), 0.0);
  inverse_diagonal_.resize(n);
  // position[r] = where row r sits in the current column's pattern, -1 when absent.
  std::vector<int> position(n, -1);
  std::vector<double> sums;
  for (int j = n - 1; j >= 0; --j) {
    const int first = start[j];
    const int count = start[j + 1] - first;
    sums.assign(count, 0.0);
    for (int a = 0; a < count; ++a) position[row[first + a]] = a;
    // sums[a] = sum_{k in S_j} Z(r_a, k) L(k, j), Z taken from the columns r_a > j done already.
    for (int a = 0; a < count; ++a) {
      const int column = row[first + a];
      const double l_a = value[first + a];
      sums[a] += inverse_diagonal_[column] * l_a;
      for (int p = start[column]; p < start[column + 1]; ++p) {
        const int b = position[row[p]];
        if (b < 0) continue;
        const double z = inverse_[p];  // Z(r_b, r_a), r_b > r_a
        sums[b] += z * l_a;
        sums[a] += z * value[first + b];
      }
    }
    double diagonal = 1.0 / diagonal_[j];
    for (int a = 0; a < count; ++a) {
      inverse_[first + a] = -sums[a];
      diagonal += value[first + a] * sums[a];
      position[row[first + a]] = -1;
    }
    inverse_diagonal_[j] = diagonal;
  }
  return true;
}

Eigen::MatrixXd InformationFactor::InverseOn(const std::vector<int>& indices) const {
  const int m = static_cast<int>(indices.size());
  Eigen::MatrixXd Z(m, m);
  // Indices by position in H, each with its place in the result.
  std::vector<std::pair<int, int>> sorted(m);
  for (int k = 0; k < m; ++k) sorted[k] = {indices[k], k};
  std::sort(sorted.begin(), sorted.end());
  const Eigen::SparseMatrix<double>& L = ldlt_.matrixL().nestedExpression();
  const int* start = L.outerIndexPtr();
  const int* row = L.innerIndexPtr();
  for (int a = 0; a < m; ++a) {
    const auto [column, place_a] = sorted[a];
    Z(place_a, place_a) = inverse_diagonal_[column];
    // The later indices in column `column` of Z: both lists ascend, one merge.
    int p = start[column];
    const int end = start[column + 1];
    for (int b = a + 1; b < m; ++b) {
      const auto [target, place_b] = sorted[b];
      while (p < end && row[p] < target) ++p;
      if (p == end || row[p] != target) {
        throw Error("InformationFactor::InverseOn: (" + std::to_string(target) + ", " +
                    std::to_string(column) + ") is not in the factor's pattern");
      }
      Z(place_a, place_b) = Z(place_b, place_a) = inverse_[p];
    }
  }
  return Z;
}

}  // namespace internal
}  // namespace splinecal

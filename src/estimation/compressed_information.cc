#include "compressed_information.h"

#include <ceres/ceres.h>
#include <glog/logging.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <random>

#include "sparse_cholesky.h"
#include "splinecal/estimation/compact_frame_cost.h"

namespace splinecal {
namespace estimation_internal {

namespace {

// The diagonally scaled Schur complement must have eigenvalues above this fraction of its
// largest: below, a parameter is not determined (its std would be > ~1e6 x its scale).
constexpr double kMinScaledEigenvalue = 1e-12;
// Hutchinson's probes are reproducible: the same problem gives the same traces.
constexpr uint32_t kProbeSeed = 20261124;

// r = R [d_0; d_1; ...]: a linear residual over Euclidean (tangent) blocks d_k.
class LinearCostFunction : public ceres::CostFunction {
 public:
  LinearCostFunction(Eigen::MatrixXd R, const std::vector<int>& block_sizes) : R_(std::move(R)) {
    set_num_residuals(static_cast<int>(R_.rows()));
    *mutable_parameter_block_sizes() = block_sizes;
  }
  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override {
    Eigen::Map<Eigen::VectorXd> r(residuals, R_.rows());
    r.setZero();
    int column = 0;
    const std::vector<int32_t>& sizes = parameter_block_sizes();
    for (size_t k = 0; k < sizes.size(); ++k) {
      r += R_.middleCols(column, sizes[k]) *
           Eigen::Map<const Eigen::VectorXd>(parameters[k], sizes[k]);
      if (jacobians != nullptr && jacobians[k] != nullptr) {
        Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> J(
            jacobians[k], R_.rows(), sizes[k]);
        J = R_.middleCols(column, sizes[k]);
      }
      column += sizes[k];
    }
    return true;
  }

 private:
  Eigen::MatrixXd R_;
};

}  // namespace

int CompressedInformation::Group::Index(const double* block, int size) {
  for (size_t k = 0; k < blocks.size(); ++k) {
    if (blocks[k] == block) return static_cast<int>(k);
  }
  blocks.push_back(block);
  sizes.push_back(size);
  offsets.push_back(offsets.empty() ? 0 : offsets.back() + sizes[sizes.size() - 2]);
  return static_cast<int>(blocks.size()) - 1;
}

void CompressedInformation::Group::Resize() {
  const int n = offsets.empty() ? 0 : offsets.back() + sizes.back();
  if (H.rows() == n) return;
  Eigen::MatrixXd bigger = Eigen::MatrixXd::Zero(n, n);
  bigger.topLeftCorner(H.rows(), H.cols()) = H;
  H = std::move(bigger);
}

CompressedInformation::CompressedInformation(ceres::Problem* problem,
                                             const ResidualLabel& label_of,
                                             const ResidualLabel& cluster_of) {
  std::vector<ceres::ResidualBlockId> residual_blocks;
  problem->GetResidualBlocks(&residual_blocks);
  std::vector<double*> blocks;
  std::vector<std::vector<double>> jacobians;
  std::vector<double*> jacobian_pointers;
  std::vector<double> residuals;
  for (ceres::ResidualBlockId id : residual_blocks) {
    const int label = label_of ? label_of(id) : 0;
    if (label < 0) continue;
    // The rows themselves, also where Ceres sees them compacted (their count matters here).
    const ceres::CostFunction* cost =
        &CompactResidual::RowsOf(*problem->GetCostFunctionForResidualBlock(id));
    problem->GetParameterBlocksForResidualBlock(id, &blocks);
    const int rows = cost->num_residuals();
    residuals.resize(rows);
    jacobians.resize(blocks.size());
    jacobian_pointers.resize(blocks.size());
    for (size_t k = 0; k < blocks.size(); ++k) {
      if (problem->IsParameterBlockConstant(blocks[k])) {
        jacobian_pointers[k] = nullptr;
        continue;
      }
      jacobians[k].resize(static_cast<size_t>(rows) * problem->ParameterBlockSize(blocks[k]));
      jacobian_pointers[k] = jacobians[k].data();
    }
    if (!cost->Evaluate(blocks.data(), residuals.data(), jacobian_pointers.data())) {
      evaluation_failed_ = true;
      continue;
    }
    num_residuals_[label] += rows;
    double& squares = squared_sum_[label];
    for (double r : residuals) squares += r * r;
    Group& group = groups_[GroupKey(label, blocks[0])];
    // Tangent Jacobians of this residual block, column-stacked in the group's block order.
    std::vector<std::pair<int, Eigen::MatrixXd>> parts;
    for (size_t k = 0; k < blocks.size(); ++k) {
      if (jacobian_pointers[k] == nullptr) continue;
      const int ambient = problem->ParameterBlockSize(blocks[k]);
      const int tangent = problem->ParameterBlockTangentSize(blocks[k]);
      Eigen::MatrixXd J =
          Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
              jacobians[k].data(), rows, ambient);
      const ceres::Manifold* manifold = problem->GetManifold(blocks[k]);
      if (manifold != nullptr) {
        Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> plus(ambient,
                                                                                    tangent);
        CHECK(manifold->PlusJacobian(blocks[k], plus.data()));
        J = J * plus;
      }
      block_sizes_[blocks[k]] = tangent;
      parts.emplace_back(group.Index(blocks[k], tangent), std::move(J));
    }
    group.Resize();
    if (cluster_of) {
      std::map<const double*, Eigen::VectorXd>& gradient = cluster_gradients_[cluster_of(id)];
      const Eigen::Map<const Eigen::VectorXd> e(residuals.data(), rows);
      for (const auto& [a, J_a] : parts) {
        Eigen::VectorXd& g = gradient[group.blocks[a]];
        if (g.size() == 0) g = Eigen::VectorXd::Zero(J_a.cols());
        g += J_a.transpose() * e;
      }
    }
    for (const auto& [a, J_a] : parts) {
      for (const auto& [b, J_b] : parts) {
        group.H.block(group.offsets[a], group.offsets[b], J_a.cols(), J_b.cols()) +=
            J_a.transpose() * J_b;
      }
    }
  }
}

double CompressedInformation::CompressedEntries() const {
  double entries = 0.0;
  for (const auto& [key, group] : groups_) entries += static_cast<double>(group.H.size());
  return entries;
}

void CompressedInformation::BuildCeresProblem() {
  ceres::Problem::Options options;
  options.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  compressed_ = std::make_unique<ceres::Problem>(options);
  for (auto it = groups_.begin(); it != groups_.end(); it = groups_.erase(it)) {
    const Group& group = it->second;
    std::vector<double*> tangent_blocks;
    for (size_t k = 0; k < group.blocks.size(); ++k) {
      std::vector<double>& storage = tangent_blocks_[group.blocks[k]];
      storage.assign(group.sizes[k], 0.0);
      tangent_blocks.push_back(storage.data());
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(group.H);
    const Eigen::VectorXd& lambda = eigen.eigenvalues();
    const double floor = 1e-14 * std::max(0.0, lambda.maxCoeff());
    int rank = 0;
    for (int k = 0; k < lambda.size(); ++k) rank += lambda[k] > floor ? 1 : 0;
    if (rank == 0) continue;
    Eigen::MatrixXd R(rank, group.H.cols());
    int row = 0;
    for (int k = 0; k < lambda.size(); ++k) {
      if (lambda[k] <= floor) continue;
      R.row(row++) = std::sqrt(lambda[k]) * eigen.eigenvectors().col(k).transpose();
    }
    compressed_->AddResidualBlock(
        new LinearCostFunction(std::move(R), group.sizes), nullptr, tangent_blocks);
  }
}

const double* CompressedInformation::TangentBlock(const double* block) const {
  const auto it = tangent_blocks_.find(block);
  return it == tangent_blocks_.end() ? nullptr : it->second.data();
}

Eigen::SparseMatrix<double> CompressedInformation::Assemble(
    const std::map<const double*, int>& offsets, int size) const {
  // Straight into compressed columns, block by block (a triplet per entry, ~5x the non-zeros,
  // took longer than the Cholesky factorisation of the result). Each entry sums the groups in
  // their order, as setFromTriplets' duplicates would.
  std::vector<const double*> blocks;  // in offset order: block ids
  std::map<const double*, int> id;
  for (const auto& [block, offset] : offsets) blocks.push_back(block);
  std::sort(blocks.begin(), blocks.end(), [&](const double* a, const double* b) {
    return offsets.at(a) < offsets.at(b);
  });
  for (size_t i = 0; i < blocks.size(); ++i) id[blocks[i]] = static_cast<int>(i);
  std::vector<int> block_size(blocks.size(), 0);
  std::vector<std::vector<int>> group_ids;               // per group: its blocks' ids
  std::vector<std::vector<int>> rows_of(blocks.size());  // per column block: its row blocks
  for (const auto& [key, group] : groups_) {
    std::vector<int>& ids = group_ids.emplace_back();
    for (size_t k = 0; k < group.blocks.size(); ++k) {
      ids.push_back(id.at(group.blocks[k]));
      block_size[ids.back()] = group.sizes[k];
    }
    for (int b : ids) rows_of[b].insert(rows_of[b].end(), ids.begin(), ids.end());
  }
  // Per column block: its sorted row blocks and where each starts within a column.
  std::vector<std::vector<int>> start_in_column(blocks.size());
  std::vector<int> outer(size + 1, 0);
  for (size_t b = 0; b < blocks.size(); ++b) {
    std::vector<int>& rows = rows_of[b];
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
    int height = 0;
    for (int a : rows) {
      start_in_column[b].push_back(height);
      height += block_size[a];
    }
    const int column0 = offsets.at(blocks[b]);
    for (int c = 0; c < block_size[b]; ++c) outer[column0 + c + 1] = height;
  }
  for (int c = 0; c < size; ++c) outer[c + 1] += outer[c];
  std::vector<int> inner(outer[size]);
  std::vector<double> values(outer[size], 0.0);
  for (size_t b = 0; b < blocks.size(); ++b) {
    const int column0 = offsets.at(blocks[b]);
    for (int c = 0; c < block_size[b]; ++c) {
      int position = outer[column0 + c];
      for (int a : rows_of[b]) {
        const int row0 = offsets.at(blocks[a]);
        for (int r = 0; r < block_size[a]; ++r) inner[position++] = row0 + r;
      }
    }
  }
  size_t g = 0;
  for (const auto& [key, group] : groups_) {
    const std::vector<int>& ids = group_ids[g++];
    for (size_t kb = 0; kb < ids.size(); ++kb) {
      const int b = ids[kb];
      const int column0 = offsets.at(blocks[b]);
      for (size_t ka = 0; ka < ids.size(); ++ka) {
        const int a = ids[ka];
        const auto it = std::lower_bound(rows_of[b].begin(), rows_of[b].end(), a);
        const int start = start_in_column[b][it - rows_of[b].begin()];
        for (int c = 0; c < block_size[b]; ++c) {
          double* column = values.data() + outer[column0 + c] + start;
          for (int r = 0; r < block_size[a]; ++r) {
            column[r] += group.H(group.offsets[ka] + r, group.offsets[kb] + c);
          }
        }
      }
    }
  }
  return Eigen::Map<const Eigen::SparseMatrix<double>>(
      size, size, outer[size], outer.data(), inner.data(), values.data());
}

bool CompressedInformation::SchurCovariance(const std::vector<const double*>& requested,
                                            Eigen::MatrixXd* covariance,
                                            SchurExtras* extras) {
  std::map<const double*, int> wanted_offsets;
  int num_wanted = 0;
  for (const double* block : requested) {
    const auto size = block_sizes_.find(block);
    if (size == block_sizes_.end() || wanted_offsets.count(block) != 0) return false;
    wanted_offsets[block] = num_wanted;
    num_wanted += size->second;
  }
  // Nuisance blocks first (in the order they were met), then the wanted ones.
  std::map<const double*, int> offsets;
  int num_nuisance = 0;
  for (const auto& [key, group] : groups_) {
    for (size_t k = 0; k < group.blocks.size(); ++k) {
      const double* block = group.blocks[k];
      if (wanted_offsets.count(block) != 0) continue;
      if (offsets.emplace(block, num_nuisance).second) num_nuisance += group.sizes[k];
    }
  }
  for (const auto& [block, offset] : wanted_offsets) offsets[block] = num_nuisance + offset;
  const int size = num_nuisance + num_wanted;
  const Eigen::SparseMatrix<double> H = Assemble(offsets, size);
  const int na = num_nuisance;
  Eigen::MatrixXd schur = Eigen::MatrixXd(H.bottomRightCorner(num_wanted, num_wanted));
  Eigen::MatrixXd X;  // H_aa^-1 H_ac
  if (na > 0) {
    const Eigen::SparseMatrix<double> H_aa = H.topLeftCorner(na, na);
    const Eigen::MatrixXd H_ac = Eigen::MatrixXd(H.topRightCorner(na, num_wanted));
    const SparseCholesky cholesky(H_aa);
    if (!cholesky.ok()) return false;
    X = cholesky.Solve(H_ac);
    if (X.rows() != na || !X.allFinite()) return false;
    schur -= H_ac.transpose() * X;
  }
  // Inverse through the eigen-decomposition of the diagonally scaled complement: refuses one
  // that is numerically singular (a parameter the data does not determine).
  const Eigen::VectorXd scale = schur.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd scaled = scale.asDiagonal() * schur * scale.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(scaled);
  const Eigen::VectorXd lambda = eigen.eigenvalues();
  if (!(lambda.minCoeff() > kMinScaledEigenvalue * lambda.maxCoeff())) return false;
  *covariance = scale.asDiagonal() *
                (eigen.eigenvectors() * lambda.cwiseInverse().asDiagonal() *
                 eigen.eigenvectors().transpose()) *
                scale.asDiagonal();
  if (extras != nullptr) {
    const Eigen::MatrixXd A =
        extras->A.size() == 0 ? Eigen::MatrixXd(Eigen::MatrixXd::Identity(num_wanted, num_wanted))
                              : extras->A;
    const Eigen::MatrixXd W = *covariance * A.transpose();  // Cov(c) A^T
    extras->mapped = A * W;
    if (cluster_gradients_.size() >= 2) {
      const double clusters = static_cast<double>(cluster_gradients_.size());
      Eigen::MatrixXd meat = Eigen::MatrixXd::Zero(A.rows(), A.rows());
      for (const auto& [cluster, gradient] : cluster_gradients_) {
        Eigen::VectorXd g = Eigen::VectorXd::Zero(size);
        for (const auto& [block, g_block] : gradient) {
          const auto offset = offsets.find(block);
          if (offset != offsets.end()) g.segment(offset->second, g_block.size()) += g_block;
        }
        Eigen::VectorXd v = g.tail(num_wanted);
        if (na > 0) v -= X.transpose() * g.head(na);
        const Eigen::VectorXd x = W.transpose() * v;
        meat += x * x.transpose();
      }
      extras->robust = clusters / (clusters - 1.0) * meat;  // small-sample factor G / (G - 1)
    }
    if (!extras->label_factors.empty()) {
      const Eigen::MatrixXd XW = na > 0 ? Eigen::MatrixXd(X * W) : Eigen::MatrixXd();
      Eigen::MatrixXd noise = extras->mapped;
      for (const auto& [key, group] : groups_) {
        const auto factor = extras->label_factors.find(key.first);
        if (factor == extras->label_factors.end() || factor->second == 1.0) continue;
        Eigen::MatrixXd TW_g(group.H.rows(), A.rows());
        for (size_t k = 0; k < group.blocks.size(); ++k) {
          const int offset = offsets.at(group.blocks[k]);
          TW_g.middleRows(group.offsets[k], group.sizes[k]) =
              offset >= na ? Eigen::MatrixXd(W.middleRows(offset - na, group.sizes[k]))
                           : Eigen::MatrixXd(-XW.middleRows(offset, group.sizes[k]));
        }
        noise += (factor->second - 1.0) * TW_g.transpose() * group.H * TW_g;
      }
      extras->noise = noise;
    }
  }
  groups_.clear();
  return covariance->allFinite();
}

bool CompressedInformation::LabelTraces(int probes, std::map<int, double>* traces) const {
  std::map<const double*, int> offsets;
  int size = 0;
  for (const auto& [key, group] : groups_) {
    for (size_t k = 0; k < group.blocks.size(); ++k) {
      if (offsets.emplace(group.blocks[k], size).second) size += group.sizes[k];
    }
  }
  traces->clear();
  for (const auto& [label, rows] : num_residuals_) (*traces)[label] = 0.0;
  if (size == 0 || probes < 1) return size == 0;
  const Eigen::SparseMatrix<double> H = Assemble(offsets, size);
  const SparseCholesky cholesky(H);
  if (!cholesky.ok()) return false;
  std::mt19937 random(kProbeSeed);
  std::bernoulli_distribution coin(0.5);
  Eigen::MatrixXd Z(size, probes);
  for (int p = 0; p < probes; ++p) {
    for (int i = 0; i < size; ++i) Z(i, p) = coin(random) ? 1.0 : -1.0;
  }
  // W = P^T L^-T Z: E[w w^T] = P^T L^-T L^-1 P = H^-1 for each column w (P H P^T = L L^T).
  const Eigen::MatrixXd W = cholesky.SolveLt(Z);
  if (W.rows() != size || !W.allFinite()) return false;
  for (const auto& [key, group] : groups_) {
    Eigen::MatrixXd W_group(group.H.rows(), probes);
    for (size_t k = 0; k < group.blocks.size(); ++k) {
      W_group.middleRows(group.offsets[k], group.sizes[k]) =
          W.middleRows(offsets.at(group.blocks[k]), group.sizes[k]);
    }
    // sum over the probes of w_g^T H_g w_g
    (*traces)[key.first] += (group.H * W_group).cwiseProduct(W_group).sum() / probes;
  }
  return true;
}

}  // namespace estimation_internal
}  // namespace splinecal

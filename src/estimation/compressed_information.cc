#include "compressed_information.h"

#include <ceres/ceres.h>
#include <glog/logging.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "information_factor.h"
#include "splinecal/estimation/detail/compact_frame_cost.h"
#include "splinecal/estimation/model_noise_cluster.h"
#include "splinecal/run_tasks.h"

namespace splinecal {
namespace internal {

namespace {

// The reported covariance's correlation matrix must have eigenvalues above this fraction of its
// largest: below, a combination of the reported quantities is not determined.
constexpr double kMinScaledEigenvalue = 1e-12;

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

int CompressedInformation::Group::Size() const {
  return offsets.empty() ? 0 : offsets.back() + sizes.back();
}

Eigen::MatrixXd& CompressedInformation::Group::Pair(int a, int b) {
  const auto [it, added] = H.try_emplace(std::make_pair(a, b));
  if (added) it->second = Eigen::MatrixXd::Zero(sizes[a], sizes[b]);
  return it->second;
}

Eigen::MatrixXd CompressedInformation::Group::Dense() const {
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(Size(), Size());
  for (const auto& [pair, H_ab] : H) {
    const auto [a, b] = pair;
    dense.block(offsets[a], offsets[b], sizes[a], sizes[b]) = H_ab;
    if (a != b) dense.block(offsets[b], offsets[a], sizes[b], sizes[a]) = H_ab.transpose();
  }
  return dense;
}

namespace {

// One residual block's share of the information, computed without touching any shared state
// (so that blocks linearise in parallel): its rows' J^T J and J^T e over the stacked tangent
// columns of its free parameter blocks.
struct Linearization {
  // The residual block's cost function as Ceres sees it, compact or not: a compact form
  // (estimation/detail/compact_frame_cost.h) has the same J^T J, J^T e and |e|^2 as its rows,
  // from its few rows (a calibration frame's ~7 against ~250: the rows' Jacobian and its product
  // were most of a variance-component update, docs/performance.md "The slow tests' CPU time").
  const ceres::CostFunction* cost = nullptr;
  int rows = 0;  // the rows it stands for (CompactResidual::RowsOf), which n_l counts
  std::vector<double*> blocks;
  std::vector<int> tangent;  // per block; 0 for a constant block (no columns)
  int label = 0;
  std::vector<int> clusters;  // one per clustering
  bool ok = false;
  double squared_sum = 0.0;
  Eigen::MatrixXd JtJ;
  Eigen::VectorXd Jte;  // with clusters only
};

// Residual blocks linearised at once before their shares are merged in order: bounds the memory
// of the parallel part.
constexpr int kChunk = 1024;

void Linearize(const ceres::Problem& problem, bool with_gradient, Linearization* out) {
  const std::vector<double*>& blocks = out->blocks;
  const int rows = out->cost->num_residuals();
  std::vector<std::vector<double>> jacobians(blocks.size());
  std::vector<double*> pointers(blocks.size(), nullptr);
  int columns = 0;
  for (size_t k = 0; k < blocks.size(); ++k) {
    if (out->tangent[k] == 0) continue;
    jacobians[k].resize(static_cast<size_t>(rows) * problem.ParameterBlockSize(blocks[k]));
    pointers[k] = jacobians[k].data();
    columns += out->tangent[k];
  }
  Eigen::VectorXd e(rows);
  out->ok = out->cost->Evaluate(blocks.data(), e.data(), pointers.data());
  if (!out->ok) return;
  out->squared_sum = e.squaredNorm();
  // The tangent Jacobian J (rows x columns): each block's ambient Jacobian times its manifold's
  // PlusJacobian.
  Eigen::MatrixXd J(rows, columns);
  int column = 0;
  for (size_t k = 0; k < blocks.size(); ++k) {
    if (pointers[k] == nullptr) continue;
    const int ambient = problem.ParameterBlockSize(blocks[k]);
    const int tangent = out->tangent[k];
    const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>
        J_ambient(pointers[k], rows, ambient);
    const ceres::Manifold* manifold = problem.GetManifold(blocks[k]);
    if (manifold != nullptr) {
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> plus(ambient,
                                                                                  tangent);
      CHECK(manifold->PlusJacobian(blocks[k], plus.data()));
      J.middleCols(column, tangent).noalias() = J_ambient * plus;
    } else {
      J.middleCols(column, tangent) = J_ambient;
    }
    column += tangent;
  }
  out->JtJ.noalias() = J.transpose() * J;
  if (with_gradient) out->Jte.noalias() = J.transpose() * e;
}

}  // namespace

CompressedInformation::CompressedInformation(ceres::Problem* problem,
                                             const ResidualLabel& label_of,
                                             const std::vector<ResidualLabel>& clusterings,
                                             int num_threads)
    : cluster_gradients_(clusterings.size()), model_noise_groups_(clusterings.size()) {
  // Ordinals by first appearance in the residual blocks, which Problem::GetResidualBlocks lists
  // in the order they were added. Not Problem::GetParameterBlocks' order: Ceres 2.1 lists the
  // parameter blocks from a std::map keyed by their address, so that order moves with the heap
  // layout (an IMU file name 35 characters longer changed the cluster gradients' summation
  // order, and calibrate's standard deviations in the 16th digit).
  ordinal_.reserve(2 * static_cast<size_t>(problem->NumParameterBlocks()));
  std::vector<ceres::ResidualBlockId> residual_blocks;
  problem->GetResidualBlocks(&residual_blocks);
  std::vector<Linearization> chunk;
  for (size_t first = 0; first < residual_blocks.size(); first += kChunk) {
    const size_t last = std::min(residual_blocks.size(), first + kChunk);
    // What the problem says of each block, read on this thread; the linearisations in parallel.
    chunk.clear();
    for (size_t i = first; i < last; ++i) {
      const ceres::ResidualBlockId id = residual_blocks[i];
      const int label = label_of ? label_of(id) : 0;
      if (label < 0) continue;
      Linearization& item = chunk.emplace_back();
      item.label = label;
      for (const ResidualLabel& cluster_of : clusterings) item.clusters.push_back(cluster_of(id));
      item.cost = problem->GetCostFunctionForResidualBlock(id);
      item.rows = CompactResidual::RowsOf(*item.cost).num_residuals();
      problem->GetParameterBlocksForResidualBlock(id, &item.blocks);
      for (double* block : item.blocks) {
        if (ordinal_.emplace(block, static_cast<int>(blocks_by_ordinal_.size())).second) {
          blocks_by_ordinal_.push_back(block);
        }
        item.tangent.push_back(problem->IsParameterBlockConstant(block)
                                   ? 0
                                   : problem->ParameterBlockTangentSize(block));
      }
    }
    RunTasks(num_threads, static_cast<int64_t>(chunk.size()), [&](int64_t i) {
      Linearize(*problem, !clusterings.empty(), &chunk[i]);
    });
    // Merged in the residual blocks' order: the sums do not depend on the threads.
    for (const Linearization& item : chunk) {
      if (!item.ok) {
        evaluation_failed_ = true;
        continue;
      }
      num_residuals_[item.label] += item.rows;
      squared_sum_[item.label] += item.squared_sum;
      Group& group = groups_[GroupKey(item.label, ordinal_.at(item.blocks[0]))];
      std::vector<std::pair<int, int>> parts;  // (index in the group, first column in J)
      int column = 0;
      for (size_t k = 0; k < item.blocks.size(); ++k) {
        if (item.tangent[k] == 0) continue;
        block_sizes_[item.blocks[k]] = item.tangent[k];
        parts.emplace_back(group.Index(item.blocks[k], item.tangent[k]), column);
        column += item.tangent[k];
      }
      for (size_t c = 0; c < clusterings.size(); ++c) {
        if (item.clusters[c] == kModelNoiseCluster) {
          Group& model_noise =
              model_noise_groups_[c][GroupKey(item.label, ordinal_.at(item.blocks[0]))];
          std::vector<std::pair<int, int>> model_parts;
          for (const auto& [a, column_a] : parts) {
            model_parts.emplace_back(model_noise.Index(group.blocks[a], group.sizes[a]),
                                     column_a);
          }
          AddInformation(item.JtJ, model_parts, &model_noise);
        } else {
          std::map<int, Eigen::VectorXd>& gradient = cluster_gradients_[c][item.clusters[c]];
          for (const auto& [a, column_a] : parts) {
            Eigen::VectorXd& g = gradient[ordinal_.at(group.blocks[a])];
            if (g.size() == 0) g = Eigen::VectorXd::Zero(group.sizes[a]);
            g += item.Jte.segment(column_a, group.sizes[a]);
          }
        }
      }
      AddInformation(item.JtJ, parts, &group);
    }
  }
}

void CompressedInformation::AddInformation(const Eigen::MatrixXd& JtJ,
                                           const std::vector<std::pair<int, int>>& parts,
                                           Group* group) {
  for (size_t i = 0; i < parts.size(); ++i) {
    for (size_t j = i; j < parts.size(); ++j) {
      // H_ab with a <= b: J^T J's block of the pair in that order.
      const bool in_order = parts[i].first <= parts[j].first;
      const auto& [a, column_a] = in_order ? parts[i] : parts[j];
      const auto& [b, column_b] = in_order ? parts[j] : parts[i];
      group->Pair(a, b) += JtJ.block(column_a, column_b, group->sizes[a], group->sizes[b]);
    }
  }
}

double CompressedInformation::CompressedEntries() const {
  double entries = 0.0;
  for (const auto& [key, group] : groups_) {
    entries += static_cast<double>(group.Size()) * group.Size();
  }
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
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(group.Dense());
    const Eigen::VectorXd& lambda = eigen.eigenvalues();
    const double floor = 1e-14 * std::max(0.0, lambda.maxCoeff());
    int rank = 0;
    for (int k = 0; k < lambda.size(); ++k) rank += lambda[k] > floor ? 1 : 0;
    if (rank == 0) continue;
    Eigen::MatrixXd R(rank, group.Size());
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
  // took longer than the factorisation of the result). Each entry sums the groups in their
  // order, as setFromTriplets' duplicates would.
  // Blocks by id, ids in offset order (so that sorted ids are sorted rows).
  std::vector<std::pair<int, const double*>> by_offset;
  by_offset.reserve(offsets.size());
  for (const auto& [block, offset] : offsets) by_offset.emplace_back(offset, block);
  std::sort(by_offset.begin(), by_offset.end());
  const int num_blocks = static_cast<int>(by_offset.size());
  std::unordered_map<const double*, int> id;
  id.reserve(2 * by_offset.size());
  std::vector<int> block_offset(num_blocks);
  std::vector<int> block_size(num_blocks, 0);
  for (int b = 0; b < num_blocks; ++b) {
    id[by_offset[b].second] = b;
    block_offset[b] = by_offset[b].first;
  }
  // Per group its blocks' ids; per column block the row blocks at or above it that some
  // group's pair couples with it.
  std::vector<std::vector<int>> group_ids;
  group_ids.reserve(groups_.size());
  std::vector<std::vector<int>> rows_of(num_blocks);
  for (const auto& [key, group] : groups_) {
    std::vector<int>& ids = group_ids.emplace_back();
    for (size_t k = 0; k < group.blocks.size(); ++k) {
      ids.push_back(id.at(group.blocks[k]));
      block_size[ids.back()] = group.sizes[k];
    }
    for (const auto& [pair, H_ab] : group.H) {
      const int a = ids[pair.first];
      const int b = ids[pair.second];
      rows_of[std::max(a, b)].push_back(std::min(a, b));
    }
  }
  // Column c of block b holds every row of the row blocks a < b, then rows 0..c of block b.
  std::vector<std::vector<int>> start_in_column(num_blocks);  // of each row block
  Eigen::SparseMatrix<double> H(size, size);
  int* outer = H.outerIndexPtr();
  outer[0] = 0;
  for (int b = 0; b < num_blocks; ++b) {
    std::vector<int>& rows = rows_of[b];
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
    int height = 0;
    for (int a : rows) {
      start_in_column[b].push_back(height);
      height += block_size[a];
    }
    const int above = height - block_size[b];  // rows of the blocks before the diagonal one
    for (int c = 0; c < block_size[b]; ++c) outer[block_offset[b] + c + 1] = above + c + 1;
  }
  for (int c = 0; c < size; ++c) outer[c + 1] += outer[c];
  H.resizeNonZeros(outer[size]);
  int* inner = H.innerIndexPtr();
  double* values = H.valuePtr();
  std::fill(values, values + outer[size], 0.0);
  for (int b = 0; b < num_blocks; ++b) {
    for (int c = 0; c < block_size[b]; ++c) {
      int position = outer[block_offset[b] + c];
      for (int a : rows_of[b]) {
        const int last = a == b ? c : block_size[a] - 1;
        for (int r = 0; r <= last; ++r) inner[position++] = block_offset[a] + r;
      }
    }
  }
  size_t g = 0;
  for (const auto& [key, group] : groups_) {
    const std::vector<int>& ids = group_ids[g++];
    for (const auto& [pair, H_pair] : group.H) {
      // Row block a, column block b of H (ids a <= b): H_pair or its transpose.
      const bool in_order = ids[pair.first] <= ids[pair.second];
      const int a = in_order ? ids[pair.first] : ids[pair.second];
      const int b = in_order ? ids[pair.second] : ids[pair.first];
      const auto it = std::lower_bound(rows_of[b].begin(), rows_of[b].end(), a);
      const int start = start_in_column[b][it - rows_of[b].begin()];
      for (int c = 0; c < block_size[b]; ++c) {
        double* column = values + outer[block_offset[b] + c] + start;
        const int last = a == b ? c : block_size[a] - 1;
        for (int r = 0; r <= last; ++r) column[r] += in_order ? H_pair(r, c) : H_pair(c, r);
      }
    }
  }
  return H;
}

int CompressedInformation::EliminationOffsets(std::map<const double*, int>* offsets) const {
  std::map<const double*, int> id;
  std::vector<const double*> blocks;
  std::vector<std::vector<int>> cliques;
  cliques.reserve(groups_.size());
  for (const auto& [key, group] : groups_) {
    std::vector<int>& clique = cliques.emplace_back();
    for (const double* block : group.blocks) {
      const auto [it, added] = id.emplace(block, static_cast<int>(blocks.size()));
      if (added) blocks.push_back(block);
      clique.push_back(it->second);
    }
  }
  offsets->clear();
  int size = 0;
  for (int b : BlockEliminationOrder(static_cast<int>(blocks.size()), cliques)) {
    (*offsets)[blocks[b]] = size;
    size += block_sizes_.at(blocks[b]);
  }
  return size;
}

Eigen::MatrixXd CompressedInformation::QuadraticForm(const Group& group,
                                                     const Eigen::MatrixXd& Y,
                                                     const std::map<const double*, int>& offsets) {
  // Y_g^T (H_g Y_g), H_g Y_g block by block over the pairs.
  Eigen::MatrixXd Y_g(group.Size(), Y.cols());
  for (size_t k = 0; k < group.blocks.size(); ++k) {
    Y_g.middleRows(group.offsets[k], group.sizes[k]) =
        Y.middleRows(offsets.at(group.blocks[k]), group.sizes[k]);
  }
  Eigen::MatrixXd HY = Eigen::MatrixXd::Zero(group.Size(), Y.cols());
  for (const auto& [pair, H_ab] : group.H) {
    const auto [a, b] = pair;
    HY.middleRows(group.offsets[a], group.sizes[a]).noalias() +=
        H_ab * Y_g.middleRows(group.offsets[b], group.sizes[b]);
    if (a != b) {
      HY.middleRows(group.offsets[b], group.sizes[b]).noalias() +=
          H_ab.transpose() * Y_g.middleRows(group.offsets[a], group.sizes[a]);
    }
  }
  return Y_g.transpose() * HY;
}

bool CompressedInformation::MappedCovariance(const std::vector<const double*>& requested,
                                             Eigen::MatrixXd* covariance,
                                             CovarianceExtras* extras) {
  std::map<const double*, int> requested_offsets;  // in x
  int num_requested = 0;
  for (const double* block : requested) {
    const auto size = block_sizes_.find(block);
    if (size == block_sizes_.end() || requested_offsets.count(block) != 0) return false;
    requested_offsets[block] = num_requested;
    num_requested += size->second;
  }
  const Eigen::MatrixXd A =
      extras == nullptr || extras->A.size() == 0
          ? Eigen::MatrixXd(Eigen::MatrixXd::Identity(num_requested, num_requested))
          : extras->A;
  if (A.cols() != num_requested) return false;
  std::map<const double*, int> offsets;  // in H
  const int size = EliminationOffsets(&offsets);
  const InformationFactor factor(Assemble(offsets, size));
  if (!factor.ok()) return false;
  // B = E_c A^T: the reported coordinates' directions in H.
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(size, A.rows());
  for (const auto& [block, x_offset] : requested_offsets) {
    const int block_size = block_sizes_.at(block);
    B.middleRows(offsets.at(block), block_size) = A.middleCols(x_offset, block_size).transpose();
  }
  const Eigen::MatrixXd Y = factor.Solve(B);
  if (Y.rows() != size || !Y.allFinite()) return false;
  Eigen::MatrixXd Q = B.transpose() * Y;
  Q = 0.5 * (Q + Q.transpose());
  // A combination of the reported quantities that the data does not determine shows as a
  // (numerically) singular correlation matrix.
  const Eigen::VectorXd scale = Q.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(scale.asDiagonal() * Q *
                                                             scale.asDiagonal());
  const Eigen::VectorXd& lambda = eigen.eigenvalues();
  if (!(lambda.minCoeff() > kMinScaledEigenvalue * lambda.maxCoeff())) return false;
  *covariance = Q;
  if (extras != nullptr) {
    extras->robust.assign(cluster_gradients_.size(), Eigen::MatrixXd());
    for (size_t c = 0; c < cluster_gradients_.size(); ++c) {
      if (cluster_gradients_[c].size() < 2) continue;
      const double clusters = static_cast<double>(cluster_gradients_[c].size());
      Eigen::MatrixXd meat = Eigen::MatrixXd::Zero(A.rows(), A.rows());
      for (const auto& [cluster, gradient] : cluster_gradients_[c]) {
        Eigen::VectorXd x = Eigen::VectorXd::Zero(A.rows());  // Y^T g_k
        for (const auto& [ordinal, g_block] : gradient) {
          const auto offset = offsets.find(blocks_by_ordinal_[ordinal]);
          if (offset == offsets.end()) continue;
          x += Y.middleRows(offset->second, g_block.size()).transpose() * g_block;
        }
        meat += x * x.transpose();
      }
      // Small-sample factor G / (G - 1) on the clusters' scatter; the model-noise residuals'
      // variance is stated, not estimated (kModelNoiseCluster).
      extras->robust[c] = clusters / (clusters - 1.0) * meat;
      for (const auto& [key, group] : model_noise_groups_[c]) {
        extras->robust[c] += QuadraticForm(group, Y, offsets);
      }
    }
    extras->noise.resize(0, 0);
    if (!extras->label_factors.empty()) {
      Eigen::MatrixXd noise = Q;
      for (const auto& [key, group] : groups_) {
        const auto factor_of_label = extras->label_factors.find(key.first);
        if (factor_of_label == extras->label_factors.end() || factor_of_label->second == 1.0) {
          continue;
        }
        noise += (factor_of_label->second - 1.0) * QuadraticForm(group, Y, offsets);
      }
      extras->noise = noise;
    }
  }
  groups_.clear();
  return covariance->allFinite();
}

bool CompressedInformation::LabelTraces(std::map<int, double>* traces) const {
  traces->clear();
  for (const auto& [label, rows] : num_residuals_) (*traces)[label] = 0.0;
  std::map<const double*, int> offsets;
  const int size = EliminationOffsets(&offsets);
  if (size == 0) return true;
  InformationFactor factor(Assemble(offsets, size));
  if (!factor.ComputeSelectedInverse()) return false;
  std::vector<int> indices;
  for (const auto& [key, group] : groups_) {
    // tr(H^-1 H_g) = sum_ij (H^-1)_ij (H_g)_ji, both symmetric: per pair (a, b) of the group's
    // blocks the entries of H^-1 on the pair's rows and columns, twice when a != b.
    for (const auto& [pair, H_ab] : group.H) {
      const auto [a, b] = pair;
      indices.clear();
      for (int k = 0; k < (a == b ? 1 : 2); ++k) {
        const int block = k == 0 ? a : b;
        const int offset = offsets.at(group.blocks[block]);
        for (int c = 0; c < group.sizes[block]; ++c) indices.push_back(offset + c);
      }
      const Eigen::MatrixXd inverse = factor.InverseOn(indices);
      const double sum =
          a == b ? inverse.cwiseProduct(H_ab).sum()
                 : 2.0 * inverse.block(0, group.sizes[a], group.sizes[a], group.sizes[b])
                             .cwiseProduct(H_ab)
                             .sum();
      (*traces)[key.first] += sum;
    }
  }
  return true;
}

}  // namespace internal
}  // namespace splinecal

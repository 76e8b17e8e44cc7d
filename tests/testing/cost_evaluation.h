// Evaluations of a ceres::CostFunction for the cost tests that compare two costs or a cost
// against differences (tests/estimation/imu_model_costs_test.cc, further_imu_cost_test.cc,
// reprojection_cost_test.cc, tests/calib/target_scale_cost_test.cc, camchain_prior_test.cc):
// with every Jacobian, with the Jacobians of some blocks, or with one block moved.
#ifndef SPLINECAL_TESTS_TESTING_COST_EVALUATION_H_
#define SPLINECAL_TESTS_TESTING_COST_EVALUATION_H_

#include <ceres/cost_function.h>
#include <glog/logging.h>
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <random>
#include <vector>

#include "splinecal/lie/se3.h"
#include "splinecal/lie/se3_manifold.h"

namespace splinecal {
namespace testing {

struct Evaluation {
  Eigen::VectorXd residuals;
  std::vector<Eigen::MatrixXd> jacobians;  // ambient, per block
};

inline Evaluation Evaluate(const ceres::CostFunction& cost, const std::vector<double*>& blocks) {
  Evaluation e;
  const int rows = cost.num_residuals();
  e.residuals.resize(rows);
  std::vector<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> J;
  std::vector<double*> pointers;
  for (int size : cost.parameter_block_sizes()) J.emplace_back(rows, size);
  for (auto& j : J) pointers.push_back(j.data());
  EXPECT_TRUE(cost.Evaluate(blocks.data(), e.residuals.data(), pointers.data()));
  for (auto& j : J) e.jacobians.emplace_back(j);
  return e;
}

// The ambient Jacobians of the blocks of `cost` marked free, as Evaluate writes them: `pointers`
// is its jacobians argument, nullptr for a block not free (a constant block in Ceres).
struct FreeBlockJacobians {
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

  FreeBlockJacobians(const ceres::CostFunction& cost, const std::vector<bool>& free)
      : rows(cost.num_residuals()),
        sizes(cost.parameter_block_sizes()),
        storage(sizes.size()),
        pointers(sizes.size(), nullptr) {
    for (size_t i = 0; i < sizes.size(); ++i) {
      if (!free[i]) continue;
      storage[i].assign(rows * sizes[i], 0.0);
      pointers[i] = storage[i].data();
    }
  }
  // Every block free.
  explicit FreeBlockJacobians(const ceres::CostFunction& cost)
      : FreeBlockJacobians(cost, std::vector<bool>(cost.parameter_block_sizes().size(), true)) {}

  // Block i's Jacobian, rows x its ambient size.
  Eigen::Map<const RowMajor> Ambient(size_t i) const {
    return Eigen::Map<const RowMajor>(storage[i].data(), rows, sizes[i]);
  }

  int rows;
  std::vector<int32_t> sizes;
  std::vector<std::vector<double>> storage;
  std::vector<double*> pointers;
};

// The residuals of `cost` at `blocks` with block b moved by `delta` in its tangent space: on
// SE(3) (SE3Manifold::Plus) for a pose block (7 parameters), by addition for any other.
inline Eigen::VectorXd ResidualsWithBlockMoved(const ceres::CostFunction& cost,
                                               std::vector<double*> blocks,
                                               size_t b,
                                               const Eigen::VectorXd& delta) {
  const int size = cost.parameter_block_sizes()[b];
  std::vector<double> x(size);
  if (size == 7) {
    SE3Manifold().Plus(blocks[b], delta.data(), x.data());
  } else {
    for (int k = 0; k < size; ++k) x[k] = blocks[b][k] + delta[k];
  }
  blocks[b] = x.data();
  Eigen::VectorXd residuals(cost.num_residuals());
  CHECK(cost.Evaluate(blocks.data(), residuals.data(), nullptr));
  return residuals;
}

// The largest absolute difference relative to max(1, the largest entry of b).
inline double RelativeError(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / std::max(1.0, b.cwiseAbs().maxCoeff());
}

// The blocks every IMU cost of one segment reads: four lively control poses (rotation steps
// ~0.35 rad, translation ~1 m per 0.1 s knot), four gyro and accelerometer bias points, gravity.
struct SegmentBlocks {
  std::vector<std::array<double, 7>> poses;
  std::vector<std::array<double, 3>> gyro_bias;
  std::vector<std::array<double, 3>> accel_bias;
  std::array<double, 3> gravity = {0.3, -0.2, -9.8};

  explicit SegmentBlocks(uint64_t seed) {
    std::mt19937 rng(static_cast<unsigned>(seed));
    std::normal_distribution<double> normal(0.0, 1.0);
    SE3d T = SE3d::Exp((Vector6d() << 1.0, -2.0, 0.5, 0.3, -1.2, 2.0).finished());
    poses.resize(4);
    for (auto& pose : poses) {
      Vector6d xi;
      for (int k = 0; k < 6; ++k) xi[k] = (k < 3 ? 1.0 : 0.35) * normal(rng);
      T = T * SE3d::Exp(xi);
      PoseToBlock(T, pose.data());
    }
    gyro_bias.resize(4);
    accel_bias.resize(4);
    for (int j = 0; j < 4; ++j) {
      for (int a = 0; a < 3; ++a) {
        gyro_bias[j][a] = 0.01 * normal(rng);
        accel_bias[j][a] = 0.1 * normal(rng);
      }
    }
  }
};

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_TESTING_COST_EVALUATION_H_

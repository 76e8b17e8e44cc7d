// The further IMU's residuals (estimation/detail/further_imu_cost.h): mounted at the reference
// IMU's pose and clock they are the reference's own gyro and accelerometer residuals
// (estimation/detail/imu_costs.h, through their autodiff twins); under every model the analytic
// residuals and Jacobians w.r.t. every block -- the control poses, biases, gravity, C_i_b, r_b,
// the time offset and the model's M_a, M_g, A, C_gyro_i, ry_i, rz_i -- match the automatic
// differentiation of the same templated prediction (testing/autodiff_further_imu_cost.h) and
// central differences of the residuals.
#include "splinecal/estimation/detail/further_imu_cost.h"

#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <random>
#include <vector>

#include "splinecal/estimation/detail/imu_costs.h"
#include "splinecal/estimation/imu_model_parameters.h"
#include "splinecal/lie/se3_manifold.h"
#include "testing/autodiff_costs.h"
#include "testing/autodiff_further_imu_cost.h"
#include "testing/cost_evaluation.h"

namespace splinecal {
namespace {

// Two differentiations (automatic or analytic) of the same double function: rounding only
// (~1e-14 of the O(10) entries, times the few hundred flops of a chain).
constexpr double kExactTolerance = 1e-9;
// Central differences with step 1e-6 on O(1) blocks: truncation ~1e-12 |f'''|, rounding
// ~1e-16 |f| / 1e-6 = 1e-10 |f|, relative to the block's largest entry.
constexpr double kNumericTolerance = 1e-6;
constexpr double kStep = 1e-6;
constexpr double kDtS = 0.1;
constexpr double kSigmaGyro = 0.01;
constexpr double kSigmaAccel = 0.1;

// A segment's blocks (testing/cost_evaluation.h) and a further IMU's mounting.
struct Fixture : testing::SegmentBlocks {
  std::array<double, 4> q_i_b = {0.0, 0.0, 0.0, 1.0};
  std::array<double, 3> r_b = {0.0, 0.0, 0.0};
  double time_offset_s = 0.0;
  ImuModelParameters model;

  explicit Fixture(uint64_t seed) : SegmentBlocks(seed) {}
  // A consumer MEMS IMU's errors (Rehder et al., ICRA 2016: scale ~1%, misalignment ~1 deg),
  // g-sensitivity 1e-3 (rad/s)/(m/s^2), a 2 deg gyro frame, axes ~1 cm apart: every model
  // Jacobian away from its nominal point.
  void Distort() {
    model.m_a = {1.01, 0.012, 0.985, -0.008, 0.015, 1.02};
    model.m_g = {0.99, -0.01, 1.012, 0.017, -0.006, 0.993};
    model.a = {1e-3, -2e-3, 5e-4, 3e-4, 1.5e-3, -1e-3, 2e-4, -4e-4, 8e-4};
    model.phi_gyro_i = {0.02, -0.035, 0.01};
    model.ry_i = {0.008, -0.004, 0.012};
    model.rz_i = {-0.006, 0.011, 0.003};
  }
  // A turned IMU (~75 deg), 11 cm away, its clock 2 ms late.
  void Mount() {
    RotationToBlock(SO3d::Exp(Eigen::Vector3d(0.3, -0.5, 1.2)), q_i_b.data());
    r_b = {0.05, -0.10, 0.02};
    time_offset_s = 0.002;
  }
  // The blocks in further_imu_cost.h's order.
  std::vector<double*> Blocks(int nb, ImuModelKind kind = ImuModelKind::kCalibrated) {
    std::vector<double*> p;
    for (auto& pose : poses) p.push_back(pose.data());
    for (int j = 0; j < nb; ++j) p.push_back(gyro_bias[j].data());
    for (int j = 0; j < nb; ++j) p.push_back(accel_bias[j].data());
    p.insert(p.end(), {gravity.data(), q_i_b.data(), r_b.data(), &time_offset_s});
    if (kind != ImuModelKind::kCalibrated) {
      p.insert(p.end(),
               {model.m_a.data(), model.m_g.data(), model.a.data(), model.phi_gyro_i.data()});
    }
    if (kind == ImuModelKind::kScaleMisalignmentSizeEffect) {
      p.insert(p.end(), {model.ry_i.data(), model.rz_i.data()});
    }
    return p;
  }
};

FurtherImuSegment MakeSegment(int nb, ImuModelKind kind = ImuModelKind::kCalibrated) {
  FurtherImuSegment s;
  s.kind = kind;
  s.segment_index = 2;
  s.dt_s = kDtS;
  s.sigma_gyro = kSigmaGyro;
  s.sigma_accel = kSigmaAccel;
  s.bias_blocks = nb;
  std::mt19937 rng(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (double u : {0.0, 0.37, 0.81}) {
    FurtherImuSample sample;
    sample.u0 = u;
    for (int a = 0; a < 3; ++a) {
      sample.gyro[a] = normal(rng);
      sample.accel[a] = 10.0 * normal(rng);
    }
    if (nb == 4) sample.bias_weights = {0.1, 0.5, 0.3, 0.1};
    s.samples.push_back(sample);
  }
  return s;
}

using testing::Evaluate;
using testing::Evaluation;
using testing::RelativeError;

Eigen::VectorXd Residuals(const ceres::CostFunction& cost, const std::vector<double*>& blocks) {
  Eigen::VectorXd r(cost.num_residuals());
  EXPECT_TRUE(cost.Evaluate(blocks.data(), r.data(), nullptr));
  return r;
}

// At C_i_b = I, r_b = 0 and no clock offset the further IMU is the reference: each sample's gyro
// and accelerometer rows, and their pose, bias and gravity Jacobians, are the reference costs'.
TEST(FurtherImuCost, AtTheReferencePoseEqualsTheReferenceCosts) {
  for (int nb : {1, 4}) {
    Fixture f(3);
    const FurtherImuSegment segment = MakeSegment(nb);
    const std::unique_ptr<ceres::CostFunction> cost(NewFurtherImuCost(segment));
    const std::vector<double*> blocks = f.Blocks(nb);
    const Evaluation e = Evaluate(*cost, blocks);
    for (size_t k = 0; k < segment.samples.size(); ++k) {
      ImuResidualSegment reference;
      reference.segment_index = segment.segment_index;
      reference.dt_s = kDtS;
      ImuResidualSample sample;
      sample.u = segment.samples[k].u0;
      sample.bias_weights = segment.samples[k].bias_weights;
      reference.sigma = kSigmaGyro;
      sample.measured = segment.samples[k].gyro;
      const std::unique_ptr<ceres::CostFunction> gyro(
          testing::NewAutoDiffGyroCost(nb, reference, sample));
      reference.sigma = kSigmaAccel;
      sample.measured = segment.samples[k].accel;
      const std::unique_ptr<ceres::CostFunction> accel(
          testing::NewAutoDiffAccelCost(nb, reference, sample));
      // The reference costs' blocks: poses, their bias points (+ gravity for the accelerometer).
      std::vector<double*> gyro_blocks(blocks.begin(), blocks.begin() + 4 + nb);
      std::vector<double*> accel_blocks(blocks.begin(), blocks.begin() + 4);
      accel_blocks.insert(accel_blocks.end(), blocks.begin() + 4 + nb, blocks.begin() + 5 + 2 * nb);
      const Evaluation g = Evaluate(*gyro, gyro_blocks);
      const Evaluation a = Evaluate(*accel, accel_blocks);
      const int row = 6 * static_cast<int>(k);
      EXPECT_LE(RelativeError(e.residuals.segment<3>(row), g.residuals), kExactTolerance);
      EXPECT_LE(RelativeError(e.residuals.segment<3>(row + 3), a.residuals), kExactTolerance);
      for (int b = 0; b < 4; ++b) {
        EXPECT_LE(RelativeError(e.jacobians[b].middleRows<3>(row), g.jacobians[b]),
                  kExactTolerance) << "gyro, pose " << b;
        EXPECT_LE(RelativeError(e.jacobians[b].middleRows<3>(row + 3), a.jacobians[b]),
                  kExactTolerance) << "accel, pose " << b;
      }
      for (int j = 0; j < nb; ++j) {
        EXPECT_LE(RelativeError(e.jacobians[4 + j].middleRows<3>(row), g.jacobians[4 + j]),
                  kExactTolerance) << "gyro bias " << j;
        EXPECT_LE(RelativeError(e.jacobians[4 + nb + j].middleRows<3>(row + 3), a.jacobians[4 + j]),
                  kExactTolerance) << "accel bias " << j;
      }
      EXPECT_LE(RelativeError(e.jacobians[4 + 2 * nb].middleRows<3>(row + 3),
                              a.jacobians[4 + nb]),
                kExactTolerance) << "gravity";
    }
  }
}

constexpr ImuModelKind kKinds[] = {ImuModelKind::kCalibrated, ImuModelKind::kScaleMisalignment,
                                   ImuModelKind::kScaleMisalignmentSizeEffect};

// check(f, kind, nb) for every model kind and 1 and 4 bias points, each on a fixture of `seed`
// mounted away from the reference with a distorted model.
template <typename Check>
void ForEachMountedModel(uint64_t seed, const Check& check) {
  for (ImuModelKind kind : kKinds) {
    for (int nb : {1, 4}) {
      Fixture f(seed);
      f.Mount();
      f.Distort();
      check(f, kind, nb);
    }
  }
}

// Mounted away from the reference with a distorted model: the analytic residuals and every
// block's Jacobian (ambient coordinates, as Ceres asks) equal the automatic differentiation's.
TEST(FurtherImuCost, AnalyticMatchesAutoDiff) {
  ForEachMountedModel(5, [](Fixture& f, ImuModelKind kind, int nb) {
    const FurtherImuSegment segment = MakeSegment(nb, kind);
    const std::unique_ptr<ceres::CostFunction> cost(NewFurtherImuCost(segment));
    const std::unique_ptr<ceres::CostFunction> oracle(testing::NewAutoDiffFurtherImuCost(segment));
    const std::vector<double*> blocks = f.Blocks(nb, kind);
    ASSERT_EQ(cost->parameter_block_sizes().size(), blocks.size());
    const Evaluation e = Evaluate(*cost, blocks);
    const Evaluation o = Evaluate(*oracle, blocks);
    EXPECT_LE(RelativeError(e.residuals, o.residuals), kExactTolerance) << ImuModelName(kind);
    for (size_t b = 0; b < blocks.size(); ++b) {
      EXPECT_LE(RelativeError(e.jacobians[b], o.jacobians[b]), kExactTolerance)
          << ImuModelName(kind) << ", block " << b << ", " << nb << " bias point(s)";
    }
  });
}

// The same against central differences of the residuals; every block moves them.
TEST(FurtherImuCost, JacobiansMatchCentralDifferences) {
  ForEachMountedModel(4, [](Fixture& f, ImuModelKind kind, int nb) {
    const std::unique_ptr<ceres::CostFunction> cost(NewFurtherImuCost(MakeSegment(nb, kind)));
    const std::vector<double*> blocks = f.Blocks(nb, kind);
    const Evaluation e = Evaluate(*cost, blocks);
    const std::vector<int32_t>& sizes = cost->parameter_block_sizes();
    for (size_t b = 0; b < blocks.size(); ++b) {
      Eigen::MatrixXd numeric(cost->num_residuals(), sizes[b]);
      for (int j = 0; j < sizes[b]; ++j) {
        const double x = blocks[b][j];
        blocks[b][j] = x + kStep;
        const Eigen::VectorXd plus = Residuals(*cost, blocks);
        blocks[b][j] = x - kStep;
        const Eigen::VectorXd minus = Residuals(*cost, blocks);
        blocks[b][j] = x;
        numeric.col(j) = (plus - minus) / (2.0 * kStep);
      }
      EXPECT_LE(RelativeError(e.jacobians[b], numeric), kNumericTolerance)
          << ImuModelName(kind) << ", block " << b << " of " << blocks.size() << ", " << nb
          << " bias point(s)";
      EXPECT_GT(e.jacobians[b].cwiseAbs().maxCoeff(), 0.0) << ImuModelName(kind) << ", block " << b;
    }
  });
}

// At the model's nominal values (M = I, A = 0, C_gyro_i = I, ry_i = rz_i = 0) every model
// predicts what `calibrated` does.
TEST(FurtherImuCost, NominalModelsEqualCalibrated) {
  Fixture f(6);
  f.Mount();
  const std::unique_ptr<ceres::CostFunction> calibrated(NewFurtherImuCost(MakeSegment(1)));
  const Eigen::VectorXd reference = Residuals(*calibrated, f.Blocks(1));
  for (ImuModelKind kind : kKinds) {
    const std::unique_ptr<ceres::CostFunction> cost(NewFurtherImuCost(MakeSegment(1, kind)));
    EXPECT_LE(RelativeError(Residuals(*cost, f.Blocks(1, kind)), reference), kExactTolerance)
        << ImuModelName(kind);
  }
}

}  // namespace
}  // namespace splinecal

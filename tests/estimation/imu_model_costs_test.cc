#include "splinecal/estimation/detail/imu_model_costs.h"

#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "testing/autodiff_costs.h"
#include "testing/autodiff_imu_model_costs.h"
#include "testing/cost_evaluation.h"
#include "splinecal/estimation/detail/imu_costs.h"
#include "splinecal/imu/imu_intrinsic_model.h"
#include "splinecal/lie/se3_manifold.h"
#include "splinecal/spline/angular_acceleration_jacobian.h"
#include "splinecal/spline/trajectory_evaluation.h"

namespace splinecal {
namespace {

// Autodiff and the analytic Jacobians are exact derivatives of the same double-precision
// function: they differ by rounding (~1e-14 of the O(10) entries), so 1e-9 relative to
// max(1, |entry|) has a wide margin.
constexpr double kExactTolerance = 1e-9;
// Central differences with step 1e-6: truncation ~1e-12 |f'''|, rounding ~1e-16 |f| / 1e-6,
// relative to the block's largest entry.
constexpr double kNumericTolerance = 1e-6;
constexpr double kDtS = 0.1;

using testing::Evaluate;
using testing::Evaluation;
using testing::RelativeError;

// A segment's blocks (testing/cost_evaluation.h) and the model's parameters.
struct Fixture : testing::SegmentBlocks {
  ImuModelParameters model;

  explicit Fixture(uint64_t seed) : SegmentBlocks(seed) {}
  // A miscalibrated IMU: scale 2%, misalignment 0.01, A 0.005, C_gyro_i 0.02 rad, lever arms
  // of a few cm (values of the order Rehder et al. report, magnified).
  void Perturb(bool rotate_gyro) {
    model.m_a = {1.02, 0.01, 0.98, -0.012, 0.008, 1.01};
    model.m_g = {0.99, -0.01, 1.015, 0.007, -0.009, 1.02};
    for (int j = 0; j < 9; ++j) model.a[j] = 0.005 * (j % 3 - 1) + 0.001 * j;
    if (rotate_gyro) model.phi_gyro_i = {0.02, -0.015, 0.01};
    model.ry_i = {0.01, 0.03, -0.02};
    model.rz_i = {-0.02, 0.01, 0.04};
  }
  std::vector<double*> Common(int nb, bool gyro) {
    std::vector<double*> p;
    for (auto& pose : poses) p.push_back(pose.data());
    for (int j = 0; j < nb; ++j) p.push_back(gyro ? gyro_bias[j].data() : accel_bias[j].data());
    p.push_back(gravity.data());
    return p;
  }
  std::vector<double*> GyroBlocks(int nb) {
    std::vector<double*> p = Common(nb, true);
    p.insert(p.end(), {model.m_g.data(), model.a.data(), model.phi_gyro_i.data()});
    return p;
  }
  std::vector<double*> AccelBlocks(int nb, ImuModelKind kind) {
    std::vector<double*> p = Common(nb, false);
    p.push_back(model.m_a.data());
    if (kind == ImuModelKind::kScaleMisalignmentSizeEffect) {
      p.insert(p.end(), {model.ry_i.data(), model.rz_i.data()});
    }
    return p;
  }
};

ImuModelSegment MakeModelSegment(ImuModelKind kind,
                                 int nb,
                                 double sigma,
                                 bool gyro,
                                 TrajectoryModel model = TrajectoryModel::kSE3) {
  ImuModelSegment s;
  s.kind = kind;
  s.segment.model = model;
  s.segment.segment_index = 2;
  s.segment.dt_s = kDtS;
  s.segment.sigma = sigma;
  s.bias_blocks = nb;
  std::mt19937 rng(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (double u : {0.0, 0.37, 0.81}) {
    ImuResidualSample sample;
    sample.u = u;
    for (int a = 0; a < 3; ++a) sample.measured[a] = (gyro ? 1.0 : 10.0) * normal(rng);
    if (nb == 4) sample.bias_weights = {0.1, 0.5, 0.3, 0.1};
    s.samples.push_back(sample);
  }
  return s;
}

// At the nominal model the residuals are the `calibrated` model's: the same values and pose,
// bias and gravity Jacobians as the analytic costs of estimation/detail/imu_costs.h.
TEST(ImuModelCosts, AtNominalEqualTheAnalyticCalibratedCosts) {
  for (int nb : {1, 4}) {
    Fixture f(3);
    const ImuModelSegment gyro_segment =
        MakeModelSegment(ImuModelKind::kScaleMisalignmentSizeEffect, nb, 0.01, true);
    const ImuModelSegment accel_segment =
        MakeModelSegment(ImuModelKind::kScaleMisalignmentSizeEffect, nb, 0.1, false);
    const std::unique_ptr<ceres::CostFunction> gyro(NewImuModelGyroCost(gyro_segment));
    const std::unique_ptr<ceres::CostFunction> accel(NewImuModelAccelCost(accel_segment));
    const Evaluation g = Evaluate(*gyro, f.GyroBlocks(nb));
    const Evaluation a = Evaluate(*accel, f.AccelBlocks(nb, gyro_segment.kind));
    for (size_t k = 0; k < gyro_segment.samples.size(); ++k) {
      std::unique_ptr<ceres::CostFunction> g_ref(
          testing::NewAutoDiffGyroCost(nb, gyro_segment.segment, gyro_segment.samples[k]));
      std::unique_ptr<ceres::CostFunction> a_ref(
          testing::NewAutoDiffAccelCost(nb, accel_segment.segment, accel_segment.samples[k]));
      std::vector<double*> gyro_blocks = f.Common(nb, true);
      gyro_blocks.pop_back();  // the calibrated gyro does not read gravity
      const Evaluation g0 = Evaluate(*g_ref, gyro_blocks);
      const Evaluation a0 = Evaluate(*a_ref, f.Common(nb, false));
      EXPECT_LE(RelativeError(g.residuals.segment<3>(3 * k), g0.residuals), kExactTolerance);
      EXPECT_LE(RelativeError(a.residuals.segment<3>(3 * k), a0.residuals), kExactTolerance);
      for (size_t b = 0; b < gyro_blocks.size(); ++b) {
        EXPECT_LE(RelativeError(g.jacobians[b].middleRows<3>(3 * k), g0.jacobians[b]),
                  kExactTolerance) << "gyro block " << b;
      }
      // With A = 0 the gyro does not depend on gravity.
      EXPECT_EQ(g.jacobians[4 + nb].middleRows<3>(3 * k).cwiseAbs().maxCoeff(), 0.0);
      for (int b = 0; b < 5 + nb; ++b) {
        EXPECT_LE(RelativeError(a.jacobians[b].middleRows<3>(3 * k), a0.jacobians[b]),
                  kExactTolerance) << "accel block " << b;
      }
    }
  }
}

// Away from nominal: the residuals are PredictImuReadings' on the segment's motion, and the
// Jacobians of the model's blocks are imu/imu_intrinsic_model.h's analytic ones.
TEST(ImuModelCosts, ModelJacobiansMatchTheAnalyticModel) {
  for (ImuModelKind kind :
       {ImuModelKind::kScaleMisalignment, ImuModelKind::kScaleMisalignmentSizeEffect}) {
    Fixture f(4);
    // phi = 0 keeps d C_gyro_i / d phi the right perturbation's (Exp's Jacobian at 0 is I).
    f.Perturb(/*rotate_gyro=*/false);
    const double sigma_g = 0.01;
    const double sigma_a = 0.1;
    const ImuModelSegment gs = MakeModelSegment(kind, 1, sigma_g, true);
    const ImuModelSegment as = MakeModelSegment(kind, 1, sigma_a, false);
    const std::unique_ptr<ceres::CostFunction> gyro(NewImuModelGyroCost(gs));
    const std::unique_ptr<ceres::CostFunction> accel(NewImuModelAccelCost(as));
    const Evaluation g = Evaluate(*gyro, f.GyroBlocks(1));
    const Evaluation a = Evaluate(*accel, f.AccelBlocks(1, kind));
    std::vector<double*> pose_blocks = f.Common(1, true);
    const SegmentKnotData<double> data =
        internal::KnotDataFromBlocks<double>(pose_blocks.data());
    const ImuIntrinsicsd p = f.model.Intrinsics();
    for (size_t k = 0; k < gs.samples.size(); ++k) {
      const Segment<double> seg = splinecal::MakeSegment(2, gs.samples[k].u, kDtS);
      BodyMotion<double> motion;
      Eigen::Matrix3d R_w_s;
      Eigen::Vector3d a_s;
      internal::EvaluateSegmentBody(TrajectoryModel::kSE3, data.knots(), seg, nullptr, &R_w_s,
                                    &motion.w_b, &motion.dw_b, nullptr, &a_s);
      motion.f_b = a_s - R_w_s.transpose() * Eigen::Map<const Eigen::Vector3d>(f.gravity.data());
      Eigen::Vector3d gyro_pred;
      Eigen::Vector3d accel_pred;
      ImuGyroJacobians Jg;
      ImuAccelJacobians Ja;
      PredictImuReadings(kind, p, motion, Eigen::Map<const Eigen::Vector3d>(f.gyro_bias[0].data()),
                         Eigen::Map<const Eigen::Vector3d>(f.accel_bias[0].data()), &gyro_pred,
                         &accel_pred, &Jg, &Ja);
      EXPECT_LE(RelativeError(g.residuals.segment<3>(3 * k),
                              (gyro_pred - gs.samples[k].measured) / sigma_g),
                kExactTolerance);
      EXPECT_LE(RelativeError(a.residuals.segment<3>(3 * k),
                              (accel_pred - as.samples[k].measured) / sigma_a),
                kExactTolerance);
      EXPECT_LE(RelativeError(sigma_g * g.jacobians[6].middleRows<3>(3 * k), Jg.M_g),
                kExactTolerance);
      EXPECT_LE(RelativeError(sigma_g * g.jacobians[7].middleRows<3>(3 * k), Jg.A),
                kExactTolerance);
      EXPECT_LE(RelativeError(sigma_g * g.jacobians[8].middleRows<3>(3 * k), Jg.phi_gyro_i),
                kExactTolerance);
      EXPECT_LE(RelativeError(sigma_a * a.jacobians[6].middleRows<3>(3 * k), Ja.M_a),
                kExactTolerance);
      if (kind == ImuModelKind::kScaleMisalignmentSizeEffect) {
        EXPECT_LE(RelativeError(sigma_a * a.jacobians[7].middleRows<3>(3 * k), Ja.ry_i),
                  kExactTolerance);
        EXPECT_LE(RelativeError(sigma_a * a.jacobians[8].middleRows<3>(3 * k), Ja.rz_i),
                  kExactTolerance);
        EXPECT_GT(Ja.ry_i.cwiseAbs().maxCoeff(), 0.0);  // the size effect is exercised
      }
    }
  }
}

// d f / d block i by central differences in the block's tangent (poses: SE3Manifold's right
// perturbation; other blocks Euclidean), with f(blocks) any vector function of the blocks.
template <typename F>
Eigen::MatrixXd NumericBlockJacobian(const F& f,
                                     std::vector<double*>* blocks,
                                     size_t i,
                                     int ambient,
                                     bool pose) {
  const SE3Manifold se3;
  const int tangent = pose ? 6 : ambient;
  const std::vector<double> original((*blocks)[i], (*blocks)[i] + ambient);
  constexpr double kStep = 1e-6;
  Eigen::MatrixXd J;
  for (int c = 0; c < tangent; ++c) {
    Eigen::VectorXd r[2];
    for (int side = 0; side < 2; ++side) {
      Eigen::VectorXd delta = Eigen::VectorXd::Zero(tangent);
      delta[c] = side == 0 ? kStep : -kStep;
      if (pose) {
        se3.Plus(original.data(), delta.data(), (*blocks)[i]);
      } else {
        for (int k = 0; k < ambient; ++k) (*blocks)[i][k] = original[k] + delta[k];
      }
      r[side] = f(*blocks);
    }
    std::copy(original.begin(), original.end(), (*blocks)[i]);
    if (c == 0) J.resize(r[0].size(), tangent);
    J.col(c) = (r[0] - r[1]) / (2.0 * kStep);
  }
  return J;
}

// The ambient Jacobian of block i in its tangent (poses times SE3Manifold's PlusJacobian).
Eigen::MatrixXd TangentJacobian(const Eigen::MatrixXd& J, const double* block, bool pose) {
  if (!pose) return J;
  Eigen::Matrix<double, 7, 6, Eigen::RowMajor> plus;
  SE3Manifold().PlusJacobian(block, plus.data());
  return J * plus;
}

// The new link of the chain: the body angular acceleration's Jacobian w.r.t. the control poses
// (spline/angular_acceleration_jacobian.h) against central differences at several u (both ends
// of the segment included).
TEST(ImuModelCosts, AngularAccelerationJacobianMatchesNumericDifferentiation) {
  Fixture f(6);
  std::vector<double*> poses = f.Common(1, true);
  poses.resize(4);
  for (double u : {0.0, 0.23, 0.5, 0.91, 1.0}) {
    const Segment<double> seg = splinecal::MakeSegment(2, u, kDtS);
    const auto dw_of = [&](const std::vector<double*>& blocks) {
      const SegmentKnotData<double> data = internal::KnotDataFromBlocks<double>(blocks.data());
      Eigen::Vector3d dw;
      EvaluateAngularAccelerationJacobian(data.knots(), seg, &dw, nullptr);
      return Eigen::VectorXd(dw);
    };
    const SegmentKnotData<double> data(PoseFromBlock(poses[0]), PoseFromBlock(poses[1]),
                                       PoseFromBlock(poses[2]), PoseFromBlock(poses[3]));
    ControlPoseJacobian<3> J_dw;
    Eigen::Vector3d dw;
    EvaluateAngularAccelerationJacobian(data.knots(), seg, &dw, &J_dw);
    EXPECT_GT(dw.norm(), 1.0);  // a lively segment: ~10 rad/s^2 and more
    for (size_t k = 0; k < 4; ++k) {
      const Eigen::MatrixXd J_num = NumericBlockJacobian(dw_of, &poses, k, 7, true);
      EXPECT_LE(RelativeError(J_dw.blocks[k], J_num), kNumericTolerance)
          << "u " << u << " block " << k;
    }
  }
}

struct Case {
  ImuModelKind kind;
  int nb;
  TrajectoryModel model;
};

std::vector<Case> AllCases() {
  std::vector<Case> cases;
  for (ImuModelKind kind :
       {ImuModelKind::kScaleMisalignment, ImuModelKind::kScaleMisalignmentSizeEffect}) {
    for (int nb : {1, 4}) {
      for (TrajectoryModel model : {TrajectoryModel::kSE3, TrajectoryModel::kSplitSO3R3}) {
        cases.push_back({kind, nb, model});
      }
    }
  }
  return cases;
}

// The analytic costs against their automatic-differentiation twins (the oracle,
// testing/autodiff_imu_model_costs.h), away from nominal (C_gyro_i's rotation vector non-zero, so
// that its Jr(phi) is exercised): every residual and every Jacobian block, both models, both
// trajectory models, both bias layouts.
TEST(ImuModelCosts, AnalyticEqualsAutoDiff) {
  for (const Case& c : AllCases()) {
    Fixture f(8);
    f.Perturb(/*rotate_gyro=*/true);
    for (bool is_gyro : {true, false}) {
      const ImuModelSegment segment =
          MakeModelSegment(c.kind, c.nb, is_gyro ? 0.01 : 0.1, is_gyro, c.model);
      const std::unique_ptr<ceres::CostFunction> analytic(
          is_gyro ? NewImuModelGyroCost(segment) : NewImuModelAccelCost(segment));
      const std::unique_ptr<ceres::CostFunction> autodiff(
          is_gyro ? testing::NewAutoDiffImuModelGyroCost(segment)
                  : testing::NewAutoDiffImuModelAccelCost(segment));
      const std::vector<double*> blocks =
          is_gyro ? f.GyroBlocks(c.nb) : f.AccelBlocks(c.nb, c.kind);
      const Evaluation e = Evaluate(*analytic, blocks);
      const Evaluation o = Evaluate(*autodiff, blocks);
      const std::string name = std::string(is_gyro ? "gyro" : "accel") + " " +
                               ImuModelName(c.kind) + " nb " + std::to_string(c.nb) + " " +
                               TrajectoryModelName(c.model);
      EXPECT_LE(RelativeError(e.residuals, o.residuals), kExactTolerance) << name;
      ASSERT_EQ(e.jacobians.size(), o.jacobians.size());
      for (size_t b = 0; b < blocks.size(); ++b) {
        EXPECT_LE(RelativeError(e.jacobians[b], o.jacobians[b]), kExactTolerance)
            << name << " block " << b;
      }
    }
  }
}

// Every block, poses through their manifold, against central differences: the chain from the
// angular acceleration dw_b (size effect) to the control poses included.
TEST(ImuModelCosts, JacobiansMatchNumericDifferentiation) {
  for (const Case& c : AllCases()) {
    Fixture f(5);
    f.Perturb(/*rotate_gyro=*/true);
    for (bool is_gyro : {true, false}) {
      const std::unique_ptr<ceres::CostFunction> cost(
          is_gyro ? NewImuModelGyroCost(MakeModelSegment(c.kind, c.nb, 0.01, true, c.model))
                  : NewImuModelAccelCost(MakeModelSegment(c.kind, c.nb, 0.1, false, c.model)));
      std::vector<double*> blocks = is_gyro ? f.GyroBlocks(c.nb) : f.AccelBlocks(c.nb, c.kind);
      const Evaluation e = Evaluate(*cost, blocks);
      const auto residuals = [&](const std::vector<double*>& b) {
        Eigen::VectorXd r(cost->num_residuals());
        cost->Evaluate(b.data(), r.data(), nullptr);
        return r;
      };
      for (size_t i = 0; i < blocks.size(); ++i) {
        const bool pose = i < 4;
        const Eigen::MatrixXd J_num = NumericBlockJacobian(
            residuals, &blocks, i, cost->parameter_block_sizes()[i], pose);
        EXPECT_LE(RelativeError(TangentJacobian(e.jacobians[i], blocks[i], pose), J_num),
                  kNumericTolerance)
            << (is_gyro ? "gyro" : "accel") << " " << ImuModelName(c.kind) << " block " << i
            << " nb " << c.nb << " " << TrajectoryModelName(c.model);
      }
    }
  }
}

// Ceres' contract: residuals alone (jacobians == nullptr) and a subset of blocks (the others
// nullptr) give the same numbers as the full evaluation.
TEST(ImuModelCosts, PartialJacobianRequestsGiveTheSameBlocks) {
  Fixture f(9);
  f.Perturb(/*rotate_gyro=*/true);
  const ImuModelKind kind = ImuModelKind::kScaleMisalignmentSizeEffect;
  for (bool is_gyro : {true, false}) {
    const std::unique_ptr<ceres::CostFunction> cost(
        is_gyro ? NewImuModelGyroCost(MakeModelSegment(kind, 4, 0.01, true))
                : NewImuModelAccelCost(MakeModelSegment(kind, 4, 0.1, false)));
    const std::vector<double*> blocks = is_gyro ? f.GyroBlocks(4) : f.AccelBlocks(4, kind);
    const Evaluation full = Evaluate(*cost, blocks);
    Eigen::VectorXd r(cost->num_residuals());
    ASSERT_TRUE(cost->Evaluate(blocks.data(), r.data(), nullptr));
    EXPECT_EQ(r, full.residuals);
    for (size_t only = 0; only < blocks.size(); ++only) {
      std::vector<double*> pointers(blocks.size(), nullptr);
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> J(
          cost->num_residuals(), cost->parameter_block_sizes()[only]);
      pointers[only] = J.data();
      ASSERT_TRUE(cost->Evaluate(blocks.data(), r.data(), pointers.data()));
      EXPECT_EQ(Eigen::MatrixXd(J), full.jacobians[only]) << "block " << only;
    }
  }
}

}  // namespace
}  // namespace splinecal

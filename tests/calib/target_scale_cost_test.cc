#include "splinecal/calib/detail/target_scale_cost.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "calib/camera_cost_test.h"
#include "calib/camera_test_scene.h"
#include "splinecal/estimation/detail/compact_frame_cost.h"
#include "splinecal/estimation/reprojection_cost.h"
#include "splinecal/lie/se3_manifold.h"
#include "testing/cost_evaluation.h"
#include "testing/numeric_diff.h"

namespace splinecal {
namespace {

// The scaled frame against a frame built with the scaled points: the same model evaluated two
// ways (scaled translations vs scaled points), equal to rounding: 1e-9 px.
constexpr double kEquivalencePx = 1e-9;
// Analytic vs Ridders' Jacobians in each block's tangent, relative to the block's largest entry;
// Ridders reaches ~1e-9 here (reprojection_cost_test.cc), a wrong term is O(1).
constexpr double kRelativeJacobianTolerance = 1e-6;
constexpr double kScale = 1.3;

class TargetScaleCostTest : public testing::CameraCostTest {
 protected:
  // Every target corner (scaled by `scale`), observed at a pixel near the image centre (the
  // residuals need not be small; no robust loss).
  std::vector<TargetCornerObservation> Corners(double scale) const {
    std::vector<TargetCornerObservation> corners;
    int k = 0;
    for (const auto& [id, p_t] : scene_.target.points) {
      corners.push_back({scale * p_t, Eigen::Vector2d(370.0 + 3.0 * (k % 7), 240.0 + 2.0 * (k % 5))});
      ++k;
    }
    return corners;
  }

  std::vector<double*> Blocks(const ControlPoseWindow& window) {
    std::vector<double*> b;
    for (int i = 0; i < window.num_poses; ++i) b.push_back(scene_.poses[window.first_index + i].data());
    b.insert(b.end(), {scene_.T_c_s.data(), &scene_.shift, &scene_.line_delay, scene_.T_w_t.data()});
    return b;
  }

  // J (tangent coordinates of the blocks marked free) and r at `blocks`.
  void Linearize(const ceres::CostFunction& cost, const std::vector<double*>& blocks,
                 const std::vector<bool>& free, Eigen::MatrixXd* J, Eigen::VectorXd* r) {
    testing::FreeBlockJacobians ambient(cost, free);
    const int rows = ambient.rows;
    r->resize(rows);
    ASSERT_TRUE(cost.Evaluate(blocks.data(), r->data(), ambient.pointers.data()));
    J->resize(rows, 0);
    for (size_t i = 0; i < ambient.sizes.size(); ++i) {
      if (!free[i]) continue;
      Eigen::MatrixXd block = ambient.Ambient(i);
      if (ambient.sizes[i] == 7) {
        testing::FreeBlockJacobians::RowMajor P(7, 6);
        manifold_.PlusJacobian(blocks[i], P.data());
        block = block * P;
      }
      J->conservativeResize(rows, J->cols() + block.cols());
      J->rightCols(block.cols()) = block;
    }
  }

  SE3Manifold manifold_;
};

TEST_F(TargetScaleCostTest, ScaledTranslationsSeeTheScaledTargetAndJacobiansMatch) {
  const double t_frame = 0.45;
  ControlPoseWindow window;
  ASSERT_TRUE(settings_.layout.WindowCovering(t_frame - 0.02, t_frame + 0.07, &window));
  const TargetScaleCostFunction cost(
      std::make_unique<TargetFrameCostFunction>(settings_, window, t_frame, Corners(1.0)),
      window.num_poses);
  const TargetFrameCostFunction scaled_points(settings_, window, t_frame, Corners(kScale));
  std::vector<double*> blocks = Blocks(window);
  const std::vector<double*> unscaled_blocks = blocks;
  double s = kScale;
  blocks.push_back(&s);
  const int rows = cost.num_residuals();
  Eigen::VectorXd r(rows);
  Eigen::VectorXd r_points(rows);
  ASSERT_TRUE(cost.Evaluate(blocks.data(), r.data(), nullptr));
  ASSERT_TRUE(scaled_points.Evaluate(unscaled_blocks.data(), r_points.data(), nullptr));
  EXPECT_LT((r - r_points).cwiseAbs().maxCoeff() * settings_.sigma_px, kEquivalencePx);
  EXPECT_GT(r.cwiseAbs().maxCoeff(), 1.0);  // not trivially zero

  // Jacobians, every block (the line delay is > 0: central differences stay valid).
  const std::vector<bool> all(blocks.size(), true);
  Eigen::MatrixXd J;
  Eigen::VectorXd r0;
  Linearize(cost, blocks, all, &J, &r0);
  int column = 0;
  for (size_t b = 0; b < blocks.size(); ++b) {
    const int size = cost.parameter_block_sizes()[b];
    const bool pose = size == 7;
    const int tangent = pose ? 6 : size;
    auto f = [&](const Eigen::VectorXd& d) {
      return testing::ResidualsWithBlockMoved(cost, blocks, b, d);
    };
    testing::RiddersOptions options;
    options.initial_step = pose ? 1e-3 : 1e-3 * std::max(1e-6, std::abs(blocks[b][0]));
    const Eigen::MatrixXd numeric =
        testing::RiddersJacobian(f, Eigen::VectorXd::Zero(tangent), options);
    const Eigen::MatrixXd analytic = J.middleCols(column, tangent);
    column += tangent;
    const double largest = std::max(analytic.cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT((analytic - numeric).cwiseAbs().maxCoeff() / largest, kRelativeJacobianTolerance)
        << "block " << b << " of " << blocks.size();
  }
}

TEST_F(TargetScaleCostTest, CompactFrameKeepsTheNormalEquations) {
  // Global shutter: calibrate compacts the frame (estimation/detail/compact_frame_cost.h) and wraps the
  // compact form; J^T J and J^T r must be the scaled rows', and rows() must be those rows.
  const double t_frame = 0.62;
  scene_.line_delay = 0.0;
  ControlPoseWindow window;
  ASSERT_TRUE(settings_.layout.WindowCovering(t_frame - 0.02, t_frame + 0.02, &window));
  auto frame = std::make_unique<TargetFrameCostFunction>(settings_, window, t_frame, Corners(1.0));
  ASSERT_TRUE(CompactFrameCostFunction::SavesRows(*frame));
  const TargetScaleCostFunction compact(
      std::make_unique<CompactFrameCostFunction>(std::move(frame)), window.num_poses);
  const ceres::CostFunction& rows = CompactResidual::RowsOf(compact);
  EXPECT_NE(&rows, &compact);
  EXPECT_EQ(rows.num_residuals(), 2 * static_cast<int>(scene_.target.points.size()));
  std::vector<double*> blocks = Blocks(window);
  double s = 0.8;
  blocks.push_back(&s);
  std::vector<bool> free(blocks.size(), true);
  free[window.num_poses + 2] = false;  // the line delay, held at 0
  free[window.num_poses + 3] = false;  // T_w_t, held as in calibrate
  Eigen::MatrixXd J_c, J_r;
  Eigen::VectorXd r_c, r_r;
  Linearize(compact, blocks, free, &J_c, &r_c);
  Linearize(rows, blocks, free, &J_r, &r_r);
  const Eigen::MatrixXd H_c = J_c.transpose() * J_c;
  const Eigen::MatrixXd H_r = J_r.transpose() * J_r;
  // Rounding of the QR: relative 1e-9 of the largest entry.
  EXPECT_LT((H_c - H_r).cwiseAbs().maxCoeff(), 1e-9 * H_r.cwiseAbs().maxCoeff());
  const Eigen::VectorXd g_c = J_c.transpose() * r_c;
  const Eigen::VectorXd g_r = J_r.transpose() * r_r;
  EXPECT_LT((g_c - g_r).cwiseAbs().maxCoeff(), 1e-9 * g_r.cwiseAbs().maxCoeff());
  EXPECT_NEAR(r_c.squaredNorm(), r_r.squaredNorm(), 1e-9 * r_r.squaredNorm());
  // A scale <= 0 is refused.
  s = 0.0;
  Eigen::VectorXd r(compact.num_residuals());
  EXPECT_FALSE(compact.Evaluate(blocks.data(), r.data(), nullptr));
}

}  // namespace
}  // namespace splinecal

#include "splinecal/estimation/reprojection_cost.h"

#include <ceres/manifold.h>
#include <ceres/normal_prior.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numeric>
#include <random>
#include <vector>

#include "calib/camera_cost_test.h"
#include "calib/camera_test_scene.h"
#include "splinecal/estimation/detail/compact_frame_cost.h"
#include "splinecal/estimation/variance_components.h"
#include "splinecal/lie/se3_manifold.h"
#include "testing/cost_evaluation.h"
#include "testing/numeric_diff.h"

namespace splinecal {
namespace {

// Analytic vs numeric Jacobians in the tangent spaces (Ridders' extrapolation through the
// blocks' manifolds, what ceres::GradientChecker does; written out here because the checker's
// central differences step a line delay of 0 to a negative, invalid value). Per block, the largest
// error must be below this fraction of the block's largest entry: Ridders reaches ~1e-9 relative
// here (the time solve converges to ~1e-16 s, far below its steps), and a wrong term would be O(1)
// relative.
constexpr double kRelativeJacobianTolerance = 1e-6;
// The cost's forward model against the independent reference below (pose from SE3Spline::Pose,
// exposure time by bisection) [px].
constexpr double kModelTolerancePx = 1e-8;

// Pixel of X_w = (x_w, w) at the exposure time, found by bisection on the spline's Pose (an
// implementation independent of the cost functions').
bool ReferencePixel(const SE3Splined& spline,
                    const Camera& camera,
                    const SE3d& T_c_s,
                    double t_base,
                    double line_delay,
                    const Eigen::Vector3d& x_w,
                    double w,
                    Eigen::Vector2d* uv) {
  auto pixel = [&](double tau, Eigen::Vector2d* out) {
    const SE3d T_w_s = spline.Pose(t_base + tau);
    const Eigen::Vector3d x_s = T_w_s.so3().inverse() * (x_w - w * T_w_s.translation());
    return camera.Project(T_c_s.so3() * x_s + w * T_c_s.translation(), out);
  };
  double lo = 0.0;
  double hi = line_delay * (camera.height - 1);
  for (int i = 0; i < 200 && hi - lo > 0.0; ++i) {
    const double mid = 0.5 * (lo + hi);
    Eigen::Vector2d p;
    if (!pixel(mid, &p)) return false;
    if (mid - line_delay * p.y() < 0.0) {
      lo = mid;
    } else {
      hi = mid;
    }
    if (line_delay == 0.0) break;
  }
  return pixel(0.5 * (lo + hi), uv);
}

struct Blocks {
  std::vector<double*> parameters;
  std::vector<const ceres::Manifold*> manifolds;
};

class ReprojectionCostTest : public testing::CameraCostTest {
 protected:
  // Checks every Jacobian block of `cost` at `blocks` against Ridders' numeric Jacobians in the
  // block's tangent space (x (+) d through its manifold, d = 0 .. step). A block whose value is
  // 0 and must stay >= 0 (a line delay of 0) is differentiated one-sided (forward differences
  // extrapolated by Ridders on h > 0).
  void ExpectJacobiansMatch(const ceres::CostFunction& cost, const Blocks& blocks) {
    testing::FreeBlockJacobians J_ambient(cost);
    const std::vector<int32_t>& sizes = J_ambient.sizes;
    const int rows = J_ambient.rows;
    std::vector<double> r0(rows);
    ASSERT_TRUE(cost.Evaluate(blocks.parameters.data(), r0.data(), J_ambient.pointers.data()));
    for (size_t i = 0; i < sizes.size(); ++i) {
      const ceres::Manifold* manifold = blocks.manifolds[i];
      const int tangent = manifold != nullptr ? manifold->TangentSize() : sizes[i];
      Eigen::MatrixXd plus(sizes[i], tangent);
      if (manifold != nullptr) {
        Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> P(sizes[i], tangent);
        manifold->PlusJacobian(blocks.parameters[i], P.data());
        plus = P;
      } else {
        plus.setIdentity();
      }
      const Eigen::MatrixXd analytic = J_ambient.Ambient(i) * plus;
      const std::vector<double> x0(blocks.parameters[i], blocks.parameters[i] + sizes[i]);
      const bool one_sided = manifold == nullptr && sizes[i] == 1 && x0[0] == 0.0;
      auto f = [&](const Eigen::VectorXd& d) -> Eigen::VectorXd {
        std::vector<double> x(sizes[i]);
        if (manifold != nullptr) {
          manifold->Plus(x0.data(), d.data(), x.data());
        } else {
          for (int k = 0; k < sizes[i]; ++k) x[k] = x0[k] + (one_sided ? std::abs(d[k]) : d[k]);
        }
        std::vector<double*> parameters = blocks.parameters;
        parameters[i] = x.data();
        Eigen::VectorXd r(rows);
        CHECK(cost.Evaluate(parameters.data(), r.data(), nullptr));
        return r;
      };
      Eigen::MatrixXd numeric;
      testing::RiddersOptions options;
      options.initial_step =
          1e-3 *
          std::max(1e-6,
                   Eigen::Map<const Eigen::VectorXd>(x0.data(), sizes[i]).cwiseAbs().maxCoeff());
      if (manifold != nullptr) options.initial_step = 1e-3;
      // Intrinsics mix pixels (~500) and coefficients (~0.1): one step for all of them sized by
      // the focal length would move a distortion coefficient by several times its value.
      if (sizes[i] == kNumIntrinsics) options.initial_step = 1e-4;
      if (one_sided) {
        // Forward differences: (f(h) - f(0)) / h, Richardson-extrapolated over h.
        std::vector<Eigen::VectorXd> level;
        double h = 1e-7;
        for (int k = 0; k < 6; ++k, h /= 2.0) {
          level.push_back((f(Eigen::VectorXd::Constant(1, h)) - f(Eigen::VectorXd::Zero(1))) / h);
        }
        for (int m = 1; m < 6; ++m) {  // error c1 h + c2 h^2 + ...: remove one power per level
          const double factor = std::pow(2.0, m);
          for (int k = 5; k >= m; --k)
            level[k] = (factor * level[k] - level[k - 1]) / (factor - 1.0);
        }
        numeric = level[5];
      } else {
        numeric = testing::RiddersJacobian(f, Eigen::VectorXd::Zero(tangent), options);
      }
      const double scale = std::max(analytic.cwiseAbs().maxCoeff(), 1e-12);
      EXPECT_LT((analytic - numeric).cwiseAbs().maxCoeff() / scale, kRelativeJacobianTolerance)
          << "block " << i << " of " << sizes.size() << ", largest entry " << scale;
    }
  }

  // The blocks of both costs: the control poses `pose_indices`, T_c_s, the time shift and the
  // line delay, then `last` (the target pose T_w_t, or a landmark's inverse depth).
  Blocks CostBlocks(const std::vector<int>& pose_indices,
                    double* last,
                    const ceres::Manifold* last_manifold) {
    Blocks b;
    for (int i : pose_indices) {
      b.parameters.push_back(scene_.poses[i].data());
      b.manifolds.push_back(&pose_manifold_);
    }
    b.parameters.insert(b.parameters.end(),
                        {scene_.T_c_s.data(), &scene_.shift, &scene_.line_delay, last});
    b.manifolds.insert(b.manifolds.end(), {&pose_manifold_, nullptr, nullptr, last_manifold});
    return b;
  }

  Blocks TargetBlocks(const ControlPoseWindow& window) {
    std::vector<int> indices(window.num_poses);
    std::iota(indices.begin(), indices.end(), window.first_index);
    return CostBlocks(indices, scene_.T_w_t.data(), &pose_manifold_);
  }

  // A frame calibrate would compact (estimation/detail/compact_frame_cost.h): global shutter
  // (the line delay held at 0), Huber active on part of its corners; nullptr if no window covers
  // it.
  std::unique_ptr<TargetFrameCostFunction> CompactableFrame(ControlPoseWindow* window) {
    const double t_frame = 0.62;
    scene_.line_delay = 0.0;
    settings_.huber_px = 1.5;
    if (!settings_.layout.WindowCovering(t_frame - 0.02, t_frame + 0.02, window)) return nullptr;
    return std::make_unique<TargetFrameCostFunction>(
        settings_, *window, t_frame, Corners(t_frame, 2.0));
  }

  // Every target corner with its true pixel, plus `offset_px` of seeded noise. Offsets within
  // 30% of the Huber threshold are redrawn: Huber's loss is only C^1 there, and a numeric
  // derivative whose steps straddle the threshold is not accurate to 1e-6.
  std::vector<TargetCornerObservation> Corners(double t_frame, double offset_px) {
    const SE3Splined spline = scene_.Spline();
    const SE3d T_c_s = PoseFromBlock(scene_.T_c_s.data());
    const SE3d T_w_t = PoseFromBlock(scene_.T_w_t.data());
    std::mt19937 rng(11);
    std::normal_distribution<double> normal(0.0, offset_px);
    std::vector<TargetCornerObservation> corners;
    for (const auto& [id, p_t] : scene_.target.points) {
      Eigen::Vector2d uv;
      if (!ReferencePixel(spline,
                          scene_.camera,
                          T_c_s,
                          t_frame + scene_.shift,
                          scene_.line_delay,
                          T_w_t * p_t,
                          1.0,
                          &uv) ||
          !scene_.camera.InImage(uv)) {
        continue;
      }
      Eigen::Vector2d offset(normal(rng), normal(rng));
      while (settings_.huber_px > 0.0 &&
             std::abs(offset.norm() - settings_.huber_px) < 0.3 * settings_.huber_px) {
        offset = Eigen::Vector2d(normal(rng), normal(rng));
      }
      corners.push_back({p_t, uv + offset});
    }
    return corners;
  }

  SE3Manifold pose_manifold_;
};

TEST_F(ReprojectionCostTest, TargetResidualIsZeroAtTheTruePixels) {
  const double t_frame = 0.45;
  const std::vector<TargetCornerObservation> corners = Corners(t_frame, 0.0);
  ASSERT_GE(corners.size(), 40u);
  ControlPoseWindow window;
  ASSERT_TRUE(settings_.layout.WindowCovering(t_frame - 0.02, t_frame + 0.07, &window));
  const TargetFrameCostFunction cost(settings_, window, t_frame, corners);
  Blocks blocks = TargetBlocks(window);
  std::vector<double> residuals(cost.num_residuals());
  ASSERT_TRUE(cost.Evaluate(blocks.parameters.data(), residuals.data(), nullptr));
  for (double r : residuals) EXPECT_LT(std::abs(r) * settings_.sigma_px, kModelTolerancePx);
}

TEST_F(ReprojectionCostTest, TargetJacobiansRollingShutterRobust) {
  const double t_frame = 0.45;
  settings_.huber_px = 1.5;  // some corners beyond it: the robust branch is exercised
  ControlPoseWindow window;
  ASSERT_TRUE(settings_.layout.WindowCovering(t_frame - 0.02, t_frame + 0.07, &window));
  EXPECT_GE(window.num_poses, 5);
  const TargetFrameCostFunction cost(settings_, window, t_frame, Corners(t_frame, 2.0));
  ExpectJacobiansMatch(cost, TargetBlocks(window));
}

TEST_F(ReprojectionCostTest, TargetJacobiansGlobalShutter) {
  const double t_frame = 0.62;
  scene_.line_delay = 0.0;
  ControlPoseWindow window;
  ASSERT_TRUE(settings_.layout.WindowCovering(t_frame - 0.02, t_frame + 0.02, &window));
  const TargetFrameCostFunction cost(settings_, window, t_frame, Corners(t_frame, 1.0));
  ExpectJacobiansMatch(cost, TargetBlocks(window));
}

TEST_F(ReprojectionCostTest, TargetJacobiansWithEstimatedIntrinsicsAndAHeldChain) {
  // `calibrate --estimate-intrinsics` with a camera held to a reference camera
  // (ReprojectionOptions::estimate_intrinsics, T_cam_cref): the intrinsics block's Jacobian
  // goes through the rolling-shutter correction like every other partial.
  const double t_frame = 0.45;
  settings_.huber_px = 1.5;
  settings_.estimate_intrinsics = true;
  settings_.T_cam_cref =
      SE3d(SO3d::Exp(Eigen::Vector3d(0.01, -0.02, 0.005)), Eigen::Vector3d(-0.1, 0.002, 0.001));
  ControlPoseWindow window;
  ASSERT_TRUE(settings_.layout.WindowCovering(t_frame - 0.02, t_frame + 0.07, &window));
  // The corners as the held camera sees them: its T_c_s is T_cam_cref times the block.
  const std::array<double, 7> block = scene_.T_c_s;
  PoseToBlock(settings_.T_cam_cref.inverse() * PoseFromBlock(block.data()), scene_.T_c_s.data());
  std::vector<TargetCornerObservation> corners;
  {
    const std::array<double, 7> held = scene_.T_c_s;
    scene_.T_c_s = block;
    corners = Corners(t_frame, 2.0);
    scene_.T_c_s = held;
  }
  const TargetFrameCostFunction cost(settings_, window, t_frame, corners);
  IntrinsicsVector intrinsics = scene_.camera.intrinsics();
  Blocks blocks = TargetBlocks(window);
  blocks.parameters.push_back(intrinsics.data());
  blocks.manifolds.push_back(nullptr);
  ExpectJacobiansMatch(cost, blocks);
  // At the true pixels and the true intrinsics the residual vanishes: the held camera's pose
  // is the composite.
  const TargetFrameCostFunction exact(settings_, window, t_frame, [&] {
    const std::array<double, 7> held = scene_.T_c_s;
    scene_.T_c_s = block;
    std::vector<TargetCornerObservation> c = Corners(t_frame, 0.0);
    scene_.T_c_s = held;
    return c;
  }());
  std::vector<double> residuals(exact.num_residuals());
  ASSERT_TRUE(exact.Evaluate(blocks.parameters.data(), residuals.data(), nullptr));
  for (double r : residuals) EXPECT_LT(std::abs(r) * settings_.sigma_px, kModelTolerancePx);
}

// What Ceres sees of a residual block in tangent coordinates: 1/2 |r|^2, J^T r and J^T J over
// the blocks marked free (the others get no Jacobian, as constant blocks in Ceres).
struct NormalEquations {
  double cost = 0.0;
  Eigen::VectorXd gradient;
  Eigen::MatrixXd information;
};

NormalEquations NormalEquationsOf(const ceres::CostFunction& cost,
                                  const Blocks& blocks,
                                  const std::vector<bool>& free) {
  testing::FreeBlockJacobians ambient(cost, free);
  const std::vector<int32_t>& sizes = ambient.sizes;
  const int rows = ambient.rows;
  Eigen::VectorXd r(rows);
  EXPECT_TRUE(cost.Evaluate(blocks.parameters.data(), r.data(), ambient.pointers.data()));
  std::vector<Eigen::MatrixXd> parts;
  int columns = 0;
  for (size_t i = 0; i < sizes.size(); ++i) {
    if (!free[i]) continue;
    Eigen::MatrixXd plus = Eigen::MatrixXd::Identity(sizes[i], sizes[i]);
    if (blocks.manifolds[i] != nullptr) {
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> P(
          sizes[i], blocks.manifolds[i]->TangentSize());
      blocks.manifolds[i]->PlusJacobian(blocks.parameters[i], P.data());
      plus = P;
    }
    parts.push_back(ambient.Ambient(i) * plus);
    columns += static_cast<int>(parts.back().cols());
  }
  Eigen::MatrixXd J(rows, columns);
  for (size_t k = 0, column = 0; k < parts.size(); column += parts[k].cols(), ++k) {
    J.middleCols(column, parts[k].cols()) = parts[k];
  }
  // A residual-only evaluation has the same cost.
  Eigen::VectorXd r_only(rows);
  EXPECT_TRUE(cost.Evaluate(blocks.parameters.data(), r_only.data(), nullptr));
  EXPECT_NEAR(r_only.squaredNorm(), r.squaredNorm(), 1e-12 * r.squaredNorm());
  return {0.5 * r.squaredNorm(), J.transpose() * r, J.transpose() * J};
}

void ExpectSameNormalEquations(const NormalEquations& got, const NormalEquations& rows) {
  // Householder QR is backward stable: the products agree to rounding of the largest entries.
  EXPECT_NEAR(got.cost, rows.cost, 1e-12 * rows.cost);
  EXPECT_LT((got.gradient - rows.gradient).cwiseAbs().maxCoeff(),
            1e-10 * rows.gradient.cwiseAbs().maxCoeff());
  EXPECT_LT((got.information - rows.information).cwiseAbs().maxCoeff(),
            1e-10 * rows.information.cwiseAbs().maxCoeff());
}

TEST_F(ReprojectionCostTest, CompactFrameHasTheRowsNormalEquations) {
  // estimation/detail/compact_frame_cost.h: Ceres must take the same steps on the compact frame. Huber
  // active on part of the corners; the line delay held at 0 (no Jacobian), as in calibrate.
  // Both trajectory models: the compact form takes the pose Jacobian of the model it is given.
  for (TrajectoryModel model : {TrajectoryModel::kSE3, TrajectoryModel::kSplitSO3R3}) {
    SCOPED_TRACE(TrajectoryModelName(model));
    settings_.model = model;
    scene_.model = model;
    ControlPoseWindow window;
    auto rows = CompactableFrame(&window);
    ASSERT_NE(rows, nullptr);
    const TargetFrameCostFunction* frame = rows.get();
    ASSERT_TRUE(CompactFrameCostFunction::SavesRows(*frame));
    const CompactFrameCostFunction compact(std::move(rows));
    EXPECT_EQ(&CompactResidual::RowsOf(compact), frame);
    EXPECT_EQ(compact.num_residuals(), 6 + 6 + kNumIntrinsics + 1);
    const Blocks blocks = TargetBlocks(window);
    const int n = window.num_poses;
    // Control poses, T_cam_imu and the time offset free; then the target pose free too.
    std::vector<bool> free(blocks.parameters.size(), true);
    free[n + 2] = false;  // line delay
    free[n + 3] = false;  // T_w_t
    ExpectSameNormalEquations(NormalEquationsOf(compact, blocks, free),
                              NormalEquationsOf(*frame, blocks, free));
    free[n + 3] = true;
    ExpectSameNormalEquations(NormalEquationsOf(compact, blocks, free),
                              NormalEquationsOf(*frame, blocks, free));
    // An estimated line delay cannot be compacted: the evaluation refuses.
    std::vector<double*> jacobians(blocks.parameters.size(), nullptr);
    std::vector<double> line_delay_jacobian(compact.num_residuals());
    jacobians[n + 2] = line_delay_jacobian.data();
    std::vector<double> residuals(compact.num_residuals());
    EXPECT_FALSE(compact.Evaluate(blocks.parameters.data(), residuals.data(), jacobians.data()));
  }
}

TEST_F(ReprojectionCostTest, CompactFrameWithEstimatedIntrinsics) {
  const double t_frame = 0.45;
  scene_.line_delay = 0.0;
  settings_.estimate_intrinsics = true;
  ControlPoseWindow window;
  ASSERT_TRUE(settings_.layout.WindowCovering(t_frame - 0.02, t_frame + 0.02, &window));
  auto rows =
      std::make_unique<TargetFrameCostFunction>(settings_, window, t_frame, Corners(t_frame, 1.0));
  const TargetFrameCostFunction* frame = rows.get();
  const CompactFrameCostFunction compact(std::move(rows));
  IntrinsicsVector intrinsics = scene_.camera.intrinsics();
  Blocks blocks = TargetBlocks(window);
  blocks.parameters.push_back(intrinsics.data());
  blocks.manifolds.push_back(nullptr);
  std::vector<bool> free(blocks.parameters.size(), true);
  free[window.num_poses + 2] = false;  // line delay
  ExpectSameNormalEquations(NormalEquationsOf(compact, blocks, free),
                            NormalEquationsOf(*frame, blocks, free));
}

// The variance components (estimation/variance_components.h) of a compact frame: computed from
// the form Ceres sees (estimation/compressed_information.cc), they must be those of the frame's
// rows, whose number n_l counts. A unit prior on every free block makes H positive definite (one
// frame does not determine its four control poses). Tolerances: the compact form's J^T J and
// |e|^2 equal the rows' to rounding (CompactFrameHasTheRowsNormalEquations: 1e-12 of the cost,
// 1e-10 of the largest entry); tr(H^-1 H_l) goes through H^-1, whose condition (unit priors
// beside the corners' information) amplifies that rounding: measured 2e-8 for the priors' share,
// bounded at 1e-6 (a wrong row count or a missing share moves r_l by 1 or more).
TEST_F(ReprojectionCostTest, CompactFrameHasTheRowsVarianceComponents) {
  ControlPoseWindow window;
  auto rows = CompactableFrame(&window);
  ASSERT_NE(rows, nullptr);
  const TargetFrameCostFunction* frame = rows.get();
  CompactFrameCostFunction compact(std::move(rows));
  const Blocks blocks = TargetBlocks(window);
  const int n = window.num_poses;
  auto components = [&](ceres::CostFunction* cost) {
    ceres::Problem::Options options;
    options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::Problem problem(options);
    const ceres::ResidualBlockId frame_id =
        problem.AddResidualBlock(cost, nullptr, blocks.parameters);
    std::vector<std::unique_ptr<ceres::CostFunction>> priors;
    for (size_t k = 0; k < blocks.parameters.size(); ++k) {
      double* block = blocks.parameters[k];
      if (blocks.manifolds[k] != nullptr) {
        problem.SetManifold(block, const_cast<ceres::Manifold*>(blocks.manifolds[k]));
      }
      if (k == static_cast<size_t>(n + 2) || k == static_cast<size_t>(n + 3)) {
        problem.SetParameterBlockConstant(block);  // line delay held at 0, T_w_t
        continue;
      }
      const int size = problem.ParameterBlockSize(block);
      priors.push_back(std::make_unique<ceres::NormalPrior>(
          Eigen::MatrixXd::Identity(size, size), Eigen::Map<const Eigen::VectorXd>(block, size)));
      problem.AddResidualBlock(priors.back().get(), nullptr, block);
    }
    return EstimateVarianceComponents(
        &problem, [frame_id](ceres::ResidualBlockId id) { return id == frame_id ? 0 : 1; });
  };
  const VarianceComponents of_compact = components(&compact);
  const VarianceComponents of_rows = components(const_cast<TargetFrameCostFunction*>(frame));
  ASSERT_TRUE(of_compact.ok);
  ASSERT_TRUE(of_rows.ok);
  for (int label : {0, 1}) {
    SCOPED_TRACE(label);
    const VarianceComponent& got = of_compact.groups.at(label);
    const VarianceComponent& want = of_rows.groups.at(label);
    EXPECT_EQ(got.num_residuals, want.num_residuals);
    EXPECT_NEAR(got.squared_sum, want.squared_sum, 1e-12 * want.squared_sum + 1e-15);
    EXPECT_NEAR(got.redundancy, want.redundancy, 1e-6);
  }
  EXPECT_EQ(of_compact.groups.at(0).num_residuals, frame->num_residuals());
  // The frame's corners determine parameters: its redundancy is below its row count.
  EXPECT_LT(of_rows.groups.at(0).redundancy, frame->num_residuals() - 1.0);
}

TEST_F(ReprojectionCostTest, TargetEvaluationOutsideTheWindowFails) {
  const double t_frame = 0.45;
  ControlPoseWindow window;
  ASSERT_TRUE(settings_.layout.WindowCovering(t_frame, t_frame + 0.015, &window));
  const TargetFrameCostFunction cost(settings_, window, t_frame, Corners(t_frame, 0.0));
  Blocks blocks = TargetBlocks(window);
  std::vector<double> residuals(cost.num_residuals());
  EXPECT_TRUE(cost.Evaluate(blocks.parameters.data(), residuals.data(), nullptr));
  scene_.shift = 0.3;  // exposure far outside the window's segments
  EXPECT_FALSE(cost.Evaluate(blocks.parameters.data(), residuals.data(), nullptr));
}

class LandmarkCostTest : public ReprojectionCostTest {
 protected:
  // A landmark first seen in the frame at t_ref at pixel (u, v) and depth `depth`.
  LandmarkObservation Observe(double t_ref,
                              const Eigen::Vector2d& uv_ref,
                              double depth,
                              double t_frame,
                              double offset_px,
                              double* rho) {
    const SE3Splined spline = scene_.Spline();
    const SE3d T_c_s = PoseFromBlock(scene_.T_c_s.data());
    LandmarkObservation o;
    o.t_reference_frame_s = t_ref;
    o.reference_row = uv_ref.y();
    CHECK(scene_.camera.Unproject(uv_ref, &o.ray));
    *rho = 1.0 / depth;
    const double t_r = t_ref + scene_.shift + scene_.line_delay * uv_ref.y();
    const Eigen::Vector3d p_w = spline.Pose(t_r) * (T_c_s.inverse() * (o.ray * depth));
    o.t_frame_s = t_frame;
    Eigen::Vector2d uv;
    CHECK(ReferencePixel(
        spline, scene_.camera, T_c_s, t_frame + scene_.shift, scene_.line_delay, p_w, 1.0, &uv));
    o.uv = uv + Eigen::Vector2d(offset_px, -0.5 * offset_px);
    return o;
  }

  Blocks LandmarkBlocks(const std::vector<int>& indices, double* rho) {
    return CostBlocks(indices, rho, nullptr);
  }

  std::vector<int> Indices(double t_ref, double t_frame) {
    ControlPoseWindow a;
    ControlPoseWindow b;
    CHECK(settings_.layout.WindowCovering(t_ref - 0.02, t_ref + 0.05, &a));
    CHECK(settings_.layout.WindowCovering(t_frame - 0.02, t_frame + 0.05, &b));
    return LandmarkCostFunction::UnionOfWindows(a, b);
  }
};

TEST_F(LandmarkCostTest, ResidualIsZeroAtTheTruePixel) {
  double rho = 0.0;
  const LandmarkObservation o = Observe(0.3, Eigen::Vector2d(300, 200), 1.4, 0.7, 0.0, &rho);
  const LandmarkCostFunction cost(settings_, Indices(0.3, 0.7), o);
  Blocks blocks = LandmarkBlocks(cost.pose_indices(), &rho);
  double r[2];
  ASSERT_TRUE(cost.Evaluate(blocks.parameters.data(), r, nullptr));
  EXPECT_LT(std::abs(r[0]) * settings_.sigma_px, kModelTolerancePx);
  EXPECT_LT(std::abs(r[1]) * settings_.sigma_px, kModelTolerancePx);
}

TEST_F(LandmarkCostTest, ReferenceObservationReprojectsExactly) {
  // The reference observation seen as a measurement of itself: zero for every rho.
  double rho = 0.0;
  LandmarkObservation o = Observe(0.5, Eigen::Vector2d(420, 310), 2.0, 0.5, 0.0, &rho);
  o.uv = Eigen::Vector2d(420, 310);
  const LandmarkCostFunction cost(settings_, Indices(0.5, 0.5), o);
  for (double r_value : {0.5, 0.01, 3.0}) {
    rho = r_value;
    Blocks blocks = LandmarkBlocks(cost.pose_indices(), &rho);
    double r[2];
    ASSERT_TRUE(cost.Evaluate(blocks.parameters.data(), r, nullptr));
    EXPECT_LT(std::abs(r[0]) * settings_.sigma_px, 1e-9) << rho;
    EXPECT_LT(std::abs(r[1]) * settings_.sigma_px, 1e-9) << rho;
  }
}

TEST_F(LandmarkCostTest, JacobiansSeparateSegments) {
  double rho = 0.0;
  settings_.huber_px = 1.0;
  const LandmarkObservation o = Observe(0.25, Eigen::Vector2d(150, 100), 1.2, 0.8, 2.5, &rho);
  const std::vector<int> indices = Indices(0.25, 0.8);
  const LandmarkCostFunction cost(settings_, indices, o);
  EXPECT_GE(indices.size(), 8u);
  ExpectJacobiansMatch(cost, LandmarkBlocks(indices, &rho));
}

TEST_F(LandmarkCostTest, JacobiansSharedSegments) {
  double rho = 0.0;
  const LandmarkObservation o = Observe(0.41, Eigen::Vector2d(600, 400), 0.9, 0.46, 1.5, &rho);
  const std::vector<int> indices = Indices(0.41, 0.46);
  const LandmarkCostFunction cost(settings_, indices, o);
  ExpectJacobiansMatch(cost, LandmarkBlocks(indices, &rho));
}

TEST_F(LandmarkCostTest, JacobiansGlobalShutter) {
  double rho = 0.0;
  scene_.line_delay = 0.0;
  const LandmarkObservation o = Observe(0.35, Eigen::Vector2d(500, 50), 1.7, 0.55, -1.0, &rho);
  const std::vector<int> indices = Indices(0.35, 0.55);
  const LandmarkCostFunction cost(settings_, indices, o);
  ExpectJacobiansMatch(cost, LandmarkBlocks(indices, &rho));
}

// The split SO(3) x R^3 trajectory model (ReprojectionOptions::model): the forward model against
// the independent reference pixel on the split spline, and every Jacobian block (target frame,
// rolling shutter and Huber active; a landmark over two segments). The compact form:
// CompactFrameHasTheRowsNormalEquations.
TEST_F(ReprojectionCostTest, SplitModelTargetResidualsAndJacobians) {
  settings_.model = TrajectoryModel::kSplitSO3R3;
  scene_.model = TrajectoryModel::kSplitSO3R3;
  const double t_frame = 0.45;
  ControlPoseWindow window;
  ASSERT_TRUE(settings_.layout.WindowCovering(t_frame - 0.02, t_frame + 0.07, &window));
  const std::vector<TargetCornerObservation> exact = Corners(t_frame, 0.0);
  const TargetFrameCostFunction zero(settings_, window, t_frame, exact);
  Blocks blocks = TargetBlocks(window);
  std::vector<double> residuals(zero.num_residuals());
  ASSERT_TRUE(zero.Evaluate(blocks.parameters.data(), residuals.data(), nullptr));
  for (double r : residuals) EXPECT_LT(std::abs(r) * settings_.sigma_px, kModelTolerancePx);
  // The coupled model sees the same pixels elsewhere: the setting is used.
  ReprojectionOptions coupled = settings_;
  coupled.model = TrajectoryModel::kSE3;
  const TargetFrameCostFunction other(coupled, window, t_frame, exact);
  ASSERT_TRUE(other.Evaluate(blocks.parameters.data(), residuals.data(), nullptr));
  EXPECT_GT(Eigen::Map<Eigen::VectorXd>(residuals.data(), residuals.size()).cwiseAbs().maxCoeff(),
            1e-3);
  settings_.huber_px = 1.5;
  const TargetFrameCostFunction cost(settings_, window, t_frame, Corners(t_frame, 2.0));
  ExpectJacobiansMatch(cost, TargetBlocks(window));
}

TEST_F(LandmarkCostTest, SplitModelResidualAndJacobians) {
  settings_.model = TrajectoryModel::kSplitSO3R3;
  scene_.model = TrajectoryModel::kSplitSO3R3;
  double rho = 0.0;
  const std::vector<int> indices = Indices(0.25, 0.8);
  const LandmarkObservation exact = Observe(0.25, Eigen::Vector2d(150, 100), 1.2, 0.8, 0.0, &rho);
  const LandmarkCostFunction zero(settings_, indices, exact);
  double r[2];
  ASSERT_TRUE(zero.Evaluate(LandmarkBlocks(indices, &rho).parameters.data(), r, nullptr));
  EXPECT_LT(std::abs(r[0]) * settings_.sigma_px, kModelTolerancePx);
  EXPECT_LT(std::abs(r[1]) * settings_.sigma_px, kModelTolerancePx);
  settings_.huber_px = 1.0;
  const LandmarkObservation o = Observe(0.25, Eigen::Vector2d(150, 100), 1.2, 0.8, 2.5, &rho);
  const LandmarkCostFunction cost(settings_, indices, o);
  ExpectJacobiansMatch(cost, LandmarkBlocks(indices, &rho));
}

TEST(RobustifyPoint, HuberCostAndContinuity) {
  const double k = 2.0;
  for (double n : {0.5, 2.0, 2.0 + 1e-9, 3.0, 50.0}) {
    Eigen::Vector2d r = n * Eigen::Vector2d(0.6, 0.8);
    internal::RobustifyPoint(k, &r, nullptr);
    const double huber = n <= k ? n * n : 2.0 * k * n - k * k;
    EXPECT_NEAR(r.squaredNorm(), huber, 1e-12 * huber) << n;
  }
  // d r' / d r against central differences beyond the threshold.
  const Eigen::Vector2d r0(3.0, -4.0);
  Eigen::Vector2d r = r0;
  Eigen::Matrix2d J;
  internal::RobustifyPoint(k, &r, &J);
  for (int j = 0; j < 2; ++j) {
    const double h = 1e-6;
    Eigen::Vector2d plus = r0;
    Eigen::Vector2d minus = r0;
    plus(j) += h;
    minus(j) -= h;
    internal::RobustifyPoint(k, &plus, nullptr);
    internal::RobustifyPoint(k, &minus, nullptr);
    EXPECT_LT(((plus - minus) / (2 * h) - J.col(j)).norm(), 1e-8);
  }
}

TEST(KnotLayout, WindowCoveringSegmentsOfTheRange) {
  KnotLayout layout;
  layout.dt_ns = 100'000'000;
  layout.num_control_poses = 10;  // valid [0.1, 0.8]
  ControlPoseWindow w;
  ASSERT_TRUE(layout.WindowCovering(0.35, 0.37, &w));
  EXPECT_EQ(w.first_index, 2);
  EXPECT_EQ(w.num_poses, 4);
  ASSERT_TRUE(layout.WindowCovering(0.35, 0.41, &w));
  EXPECT_EQ(w.num_poses, 5);
  ASSERT_TRUE(layout.WindowCovering(0.1, 0.8, &w));
  EXPECT_EQ(w.first_index, 0);
  EXPECT_EQ(w.num_poses, 10);
  EXPECT_FALSE(layout.WindowCovering(0.05, 0.3, &w));
  EXPECT_FALSE(layout.WindowCovering(0.3, 0.85, &w));
}

}  // namespace
}  // namespace splinecal

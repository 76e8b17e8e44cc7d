// The rig reprojection residual's analytic Jacobians against Ceres' numeric differentiation
// (ceres::GradientChecker through the blocks' manifolds), with and without the extrinsic and
// with Huber's loss active on some corners, flat and with a target shape or in-plane layout
// (target_deformation.h).
#include "splinecal/intrinsics/rig_reprojection_cost.h"

#include <ceres/manifold.h>
#include <gtest/gtest.h>

#include <vector>

#include "intrinsics/intrinsics_simulation.h"
#include "splinecal/intrinsics/robust_mean_pose.h"
#include "splinecal/lie/se3_manifold.h"

namespace splinecal {
namespace {

std::vector<TargetCornerObservation> Corners(const Camera& camera,
                                             const SE3d& T_cn_t,
                                             double offset_px) {
  std::vector<TargetCornerObservation> corners;
  const CalibrationTarget target = MakeAprilGrid(3, 3, 0.088, 0.3);
  int k = 0;
  for (const auto& [id, p_t] : target.points) {
    Eigen::Vector2d uv;
    if (!camera.Project(T_cn_t * p_t, &uv)) continue;
    // Alternate small and large offsets: some corners inside Huber's threshold, some beyond.
    const double scale = (k++ % 3 == 0) ? 4.0 : 0.3;
    corners.push_back({p_t, uv + scale * offset_px * Eigen::Vector2d(1.0, -0.7)});
  }
  return corners;
}

void CheckGradients(bool has_extrinsic,
                    TargetDeformationKind kind = TargetDeformationKind::kNone) {
  const Camera camera = testing::EurocCam0();
  const SE3d T_c0_t(SO3d::Exp(Eigen::Vector3d(2.9, 0.2, -0.1)), Eigen::Vector3d(-0.2, -0.1, 0.9));
  const SE3d T_cn_c0 = has_extrinsic ? SE3d(SO3d::Exp(Eigen::Vector3d(0.01, -0.02, 0.005)),
                                            Eigen::Vector3d(-0.11, 0.001, 0.002))
                                     : SE3d();
  RigViewOptions settings;
  settings.model = camera;
  settings.has_extrinsic = has_extrinsic;
  settings.sigma_px = 0.5;
  settings.huber_px = 1.0;
  settings.shape = MakeTargetShape(MakeAprilGrid(3, 3, 0.088, 0.3), kind);
  RigViewCostFunction cost(settings, Corners(camera, T_cn_c0 * T_c0_t, 0.5));
  ASSERT_GT(cost.num_residuals(), 20);

  std::vector<double> pose(7), extrinsic(7);
  PoseToBlock(T_c0_t, pose.data());
  PoseToBlock(T_cn_c0, extrinsic.data());
  IntrinsicsVector intrinsics = camera.intrinsics();
  std::vector<const double*> parameters = {pose.data(), intrinsics.data()};
  SE3Manifold se3;
  std::vector<const ceres::Manifold*> manifolds = {&se3, nullptr};
  if (has_extrinsic) {
    parameters.push_back(extrinsic.data());
    manifolds.push_back(&se3);
  }
  // A bow of a few millimetres with every coefficient non-zero (in plane: ratios of 1e-3).
  std::vector<double> shape = {2e-3, -1e-3, 1.5e-3, 0.7e-3, -0.4e-3, 0.3e-3, -0.8e-3};
  if (settings.shape.size() > 0) {
    parameters.push_back(shape.data());
    manifolds.push_back(nullptr);
  }
  // The view's own inset (in-plane-per-view): a blurred view's corners 1.2% nearer their tags'
  // centres.
  double inset = -1.2e-2;
  if (settings.shape.per_view_inset()) {
    parameters.push_back(&inset);
    manifolds.push_back(nullptr);
  }
  // Analytic Jacobians in the blocks' tangent coordinates (ambient J times the manifold's
  // PlusJacobian; intrinsics as they are) against central differences of the residuals along
  // each tangent direction (Plus for the poses).
  const int rows = cost.num_residuals();
  std::vector<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> J;
  std::vector<double*> jacobians;
  for (int size : cost.parameter_block_sizes()) {
    J.emplace_back(rows, size);
  }
  for (auto& j : J) jacobians.push_back(j.data());
  Eigen::VectorXd r0(rows);
  ASSERT_TRUE(cost.Evaluate(parameters.data(), r0.data(), jacobians.data()));
  for (size_t b = 0; b < parameters.size(); ++b) {
    const int size = cost.parameter_block_sizes()[b];
    const int tangent = manifolds[b] != nullptr ? manifolds[b]->TangentSize() : size;
    Eigen::MatrixXd analytic = J[b];
    if (manifolds[b] != nullptr) {
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> plus(size, tangent);
      manifolds[b]->PlusJacobian(parameters[b], plus.data());
      analytic = J[b] * plus;
    }
    for (int k = 0; k < tangent; ++k) {
      // Steps: 1e-6 rad or m on poses and on the shape's coefficients (m); 1e-6 relative on
      // intrinsics (pixels to coefficients).
      const double h =
          manifolds[b] != nullptr ? 1e-6 : 1e-6 * std::max(1.0, std::abs(parameters[b][k]));
      auto residuals_at = [&](double step) {
        std::vector<double> moved(parameters[b], parameters[b] + size);
        if (manifolds[b] != nullptr) {
          Eigen::VectorXd delta = Eigen::VectorXd::Zero(tangent);
          delta(k) = step;
          manifolds[b]->Plus(parameters[b], delta.data(), moved.data());
        } else {
          moved[k] += step;
        }
        std::vector<const double*> p = parameters;
        p[b] = moved.data();
        Eigen::VectorXd r(rows);
        EXPECT_TRUE(cost.Evaluate(p.data(), r.data(), nullptr));
        return r;
      };
      const Eigen::VectorXd numeric = (residuals_at(h) - residuals_at(-h)) / (2.0 * h);
      // Central differences: O(h^2) truncation plus rounding 1e-16 |r| / h; with |r| ~ 10 and
      // second derivatives of order 1e3 per unit, 1e-5 relative to the column's size.
      const double scale = std::max(1.0, analytic.col(k).norm());
      EXPECT_LT((analytic.col(k) - numeric).norm(), 1e-5 * scale)
          << "block " << b << " column " << k;
    }
  }
}

TEST(RigViewCostFunction, JacobiansMatchNumericDifferentiation) { CheckGradients(false); }

TEST(RigViewCostFunction, JacobiansWithTheExtrinsicMatchNumericDifferentiation) {
  CheckGradients(true);
}

TEST(RigViewCostFunction, JacobiansWithAQuadraticTargetMatchNumericDifferentiation) {
  CheckGradients(false, TargetDeformationKind::kQuadratic);
}

TEST(RigViewCostFunction, JacobiansWithACubicTargetAndTheExtrinsicMatchNumericDifferentiation) {
  CheckGradients(true, TargetDeformationKind::kCubic);
}

TEST(RigViewCostFunction, JacobiansInPlaneWithTheExtrinsicMatchNumericDifferentiation) {
  CheckGradients(true, TargetDeformationKind::kInPlane);
}

TEST(RigViewCostFunction, JacobiansWithAPerViewInsetMatchNumericDifferentiation) {
  CheckGradients(false, TargetDeformationKind::kInPlanePerView);
  CheckGradients(true, TargetDeformationKind::kInPlanePerView);
}

TEST(RigViewErrors, AreThePixelDifferences) {
  const Camera camera = testing::EurocCam0();
  const SE3d T(SO3d::Exp(Eigen::Vector3d(3.0, 0.1, 0.0)), Eigen::Vector3d(-0.2, -0.2, 1.0));
  const std::vector<TargetCornerObservation> corners = Corners(camera, T, 0.2);
  const std::vector<Eigen::Vector2d> errors = RigViewErrors(camera, T, corners);
  ASSERT_EQ(errors.size(), corners.size());
  for (size_t i = 0; i < corners.size(); ++i) {
    Eigen::Vector2d uv;
    ASSERT_TRUE(camera.Project(T * corners[i].p_t, &uv));
    EXPECT_LT((errors[i] - (uv - corners[i].uv)).norm(), 1e-12);
  }
}

TEST(RobustMeanPose, IgnoresAFifthOfWildCandidates) {
  const SE3d truth(SO3d::Exp(Eigen::Vector3d(0.01, 0.02, -0.01)), Eigen::Vector3d(-0.11, 0, 0));
  std::mt19937 rng(3);
  std::normal_distribution<double> small(0.0, 1e-3);
  std::uniform_real_distribution<double> wild(-1.0, 1.0);
  std::vector<SE3d> candidates;
  for (int i = 0; i < 100; ++i) {
    if (i % 5 == 0) {
      candidates.push_back(SE3d(SO3d::Exp(Eigen::Vector3d(wild(rng), wild(rng), wild(rng))),
                                Eigen::Vector3d(wild(rng), wild(rng), wild(rng))));
    } else {
      candidates.push_back(
          truth *
          SE3d::Exp(
              (Vector6d() << small(rng), small(rng), small(rng), small(rng), small(rng), small(rng))
                  .finished()));
    }
  }
  int inliers = 0;
  const SE3d mean = RobustMeanPose(candidates, &inliers);
  EXPECT_GE(inliers, 75);
  EXPECT_LE(inliers, 85);
  // 80 inliers with 1e-3 noise per coordinate: the mean is within ~1e-4 (3.5 sigma: 4e-4).
  EXPECT_LT((mean.inverse() * truth).Log().norm(), 1e-3);
}

}  // namespace
}  // namespace splinecal

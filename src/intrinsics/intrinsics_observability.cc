#include "splinecal/intrinsics/intrinsics_observability.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "splinecal/intrinsics/rig_reprojection_cost.h"
#include "splinecal/lie/se3_manifold.h"
#include "splinecal/string_printf.h"
#include "splinecal/units.h"

namespace splinecal {
namespace {

using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// The std of each coordinate of the information matrix H (inf where undetermined).
Eigen::VectorXd StdFromInformation(const Eigen::MatrixXd& H) {
  const int n = static_cast<int>(H.rows());
  Eigen::VectorXd scale(n);
  for (int j = 0; j < n; ++j) scale(j) = H(j, j) > 0.0 ? 1.0 / std::sqrt(H(j, j)) : 1.0;
  const Eigen::MatrixXd Hs = scale.asDiagonal() * H * scale.asDiagonal();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(Hs);
  const Eigen::VectorXd& lambda = eigen.eigenvalues();
  const double floor = 1e-12 * std::max(lambda.maxCoeff(), 0.0);
  Eigen::VectorXd variance = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd std(n);
  std.setZero();
  for (int k = 0; k < n; ++k) {
    const Eigen::VectorXd v = eigen.eigenvectors().col(k);
    if (!(lambda(k) > floor)) {
      // A null direction: every coordinate it moves is undetermined.
      for (int j = 0; j < n; ++j) {
        if (std::abs(v(j)) > 0.1) std(j) = std::numeric_limits<double>::infinity();
      }
      continue;
    }
    variance += v.cwiseAbs2() / lambda(k);
  }
  for (int j = 0; j < n; ++j) {
    if (std::isinf(std(j))) continue;
    std(j) = std::sqrt(variance(j)) * scale(j);
  }
  return std;
}

double TiltDeg(const SE3d& T_c_t) {
  const Eigen::Vector3d normal = T_c_t.so3().matrix().col(2);
  return std::acos(std::min(1.0, std::abs(normal.z()))) * 180.0 / kPi;
}

}  // namespace

std::string IntrinsicName(const Camera& camera, int index) {
  static const char* const kBase[] = {"fu", "fv", "pu", "pv"};
  if (index < 4) return kBase[index];
  if (index < 6) {
    switch (camera.projection) {
      case ProjectionModel::kOmni:
        return index == 4 ? "xi" : "m1";
      case ProjectionModel::kEucm:
        return index == 4 ? "alpha" : "beta";
      case ProjectionModel::kDoubleSphere:
        return index == 4 ? "xi" : "alpha";
      default:
        return StringPrintf("m%d", index - 4);
    }
  }
  const int d = index - 6;
  switch (camera.distortion) {
    case DistortionModel::kRadTan: {
      static const char* const kRadTan[] = {"k1", "k2", "p1", "p2", "k3"};
      return kRadTan[d];
    }
    case DistortionModel::kEquidistant:
      return StringPrintf("k%d", d + 1);
    case DistortionModel::kFov:
      return d == 0 ? "w" : StringPrintf("d%d", d);
    default:
      return StringPrintf("d%d", d);
  }
}

IntrinsicsObservability AnalyseObservability(const std::string& camera_name,
                                             const Camera& camera,
                                             const std::vector<int>& active,
                                             const std::vector<const TargetView*>& views,
                                             double sigma_px) {
  IntrinsicsObservability result;
  const int n = static_cast<int>(active.size());
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
  RigViewOptions settings;
  settings.model = camera;
  settings.sigma_px = sigma_px;
  IntrinsicsVector intrinsics = camera.intrinsics();
  SE3Manifold manifold;
  std::vector<int> cells(kCoverageCells * kCoverageCells, 0);
  for (const TargetView* view : views) {
    RigViewCostFunction cost(settings, view->corners);
    const int rows = cost.num_residuals();
    std::vector<double> pose(kPoseBlockSize);
    PoseToBlock(view->T_c_t, pose.data());
    const double* parameters[] = {pose.data(), intrinsics.data()};
    Eigen::VectorXd residuals(rows);
    RowMajorMatrix J_intrinsics(rows, kNumIntrinsics);
    RowMajorMatrix J_pose(rows, kPoseBlockSize);
    double* jacobians[] = {J_pose.data(), J_intrinsics.data()};
    if (!cost.Evaluate(parameters, residuals.data(), jacobians)) continue;
    RowMajorMatrix plus(kPoseBlockSize, 6);
    manifold.PlusJacobian(pose.data(), plus.data());
    const Eigen::MatrixXd Jp = J_pose * plus;
    Eigen::MatrixXd Ji(rows, n);
    for (int j = 0; j < n; ++j) Ji.col(j) = J_intrinsics.col(active[j]);
    const Eigen::MatrixXd Hpp = Jp.transpose() * Jp;
    const Eigen::MatrixXd Hpi = Jp.transpose() * Ji;
    H += Ji.transpose() * Ji - Hpi.transpose() * Hpp.ldlt().solve(Hpi);
    result.max_tilt_deg = std::max(result.max_tilt_deg, TiltDeg(view->T_c_t));
    for (const TargetCornerObservation& c : view->corners) {
      const int cu = std::clamp(
          static_cast<int>(c.uv.x() / camera.width * kCoverageCells), 0, kCoverageCells - 1);
      const int cv = std::clamp(
          static_cast<int>(c.uv.y() / camera.height * kCoverageCells), 0, kCoverageCells - 1);
      cells[cv * kCoverageCells + cu] = 1;
    }
    ++result.views;
  }
  result.coverage = static_cast<double>(std::count(cells.begin(), cells.end(), 1)) / cells.size();
  result.std = StdFromInformation(H);
  std::string named;
  for (int j = 0; j < n; ++j) {
    const bool pixel = active[j] < 4;
    const double threshold = pixel ? kUndeterminedPixelRatio * camera.width : kUndeterminedShapeStd;
    if (!(result.std(j) <= threshold)) {
      result.undetermined.push_back(active[j]);
      named += StringPrintf(
          "%s%s (std %s%s)",
          named.empty() ? "" : ", ",
          IntrinsicName(camera, active[j]).c_str(),
          std::isinf(result.std(j)) ? "unbounded" : StringPrintf("%.3g", result.std(j)).c_str(),
          pixel && !std::isinf(result.std(j)) ? " px" : "");
    }
  }
  if (named.empty()) return result;
  std::string lacks;
  if (result.max_tilt_deg < 15.0) {
    lacks += StringPrintf(
        "; the target is within %.1f deg of fronto-parallel in every view (tilt "
        "it 20-50 deg in some views)",
        result.max_tilt_deg);
  }
  if (result.coverage < 0.5) {
    lacks += StringPrintf(
        "; the corners cover %.0f%% of the image (move the target into the "
        "corners and edges)",
        100.0 * result.coverage);
  }
  if (result.views < 10) lacks += StringPrintf("; only %d view(s)", result.views);
  result.warning =
      StringPrintf("%s: these views do not determine %s", camera_name.c_str(), named.c_str()) +
      lacks;
  return result;
}

}  // namespace splinecal

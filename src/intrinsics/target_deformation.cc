#include "splinecal/intrinsics/target_deformation.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "splinecal/error.h"

namespace splinecal {

namespace {

struct KindRow {
  TargetDeformationKind kind;
  const char* name;
  int size;  // the basis functions the kind uses (header comment)
};
constexpr KindRow kKinds[] = {{TargetDeformationKind::kNone, "none", 0},
                              {TargetDeformationKind::kQuadratic, "quadratic", 3},
                              {TargetDeformationKind::kCubic, "cubic", 7}};

const KindRow& RowOf(TargetDeformationKind kind) {
  for (const KindRow& row : kKinds) {
    if (row.kind == kind) return row;
  }
  return kKinds[0];
}

}  // namespace

const char* TargetDeformationName(TargetDeformationKind kind) { return RowOf(kind).name; }

int TargetDeformationSize(TargetDeformationKind kind) { return RowOf(kind).size; }

Eigen::Matrix<double, kMaxTargetDeformationSize, 1> TargetShape::Basis(double x, double y) const {
  const double s = (x - centre.x()) / half_extent;
  const double t = (y - centre.y()) / half_extent;
  Eigen::Matrix<double, kMaxTargetDeformationSize, 1> b;
  b << s * s, s * t, t * t, s * s * s, s * s * t, s * t * t, t * t * t;
  return b;
}

Eigen::Vector3d TargetShape::Deform(const Eigen::Vector3d& p_t, const double* c) const {
  const int k = size();
  if (k == 0) return p_t;
  const Eigen::Matrix<double, kMaxTargetDeformationSize, 1> b = Basis(p_t.x(), p_t.y());
  double h = 0.0;
  for (int i = 0; i < k; ++i) h += c[i] * b(i);
  return Eigen::Vector3d(p_t.x(), p_t.y(), p_t.z() + h);
}

TargetShape MakeTargetShape(const CalibrationTarget& target, TargetDeformationKind kind) {
  TargetShape shape;
  shape.kind = kind;
  if (target.points.empty()) return shape;
  Eigen::Vector2d low = Eigen::Vector2d::Constant(1e300), high = -low;
  for (const auto& [id, p] : target.points) {
    if (kind != TargetDeformationKind::kNone && std::abs(p.z()) > 1e-12) {
      throw Error(
          "target deformation: the target's points must lie in its plane z = 0 (point " +
          std::to_string(id) + " does not)");
    }
    low = low.cwiseMin(p.head<2>());
    high = high.cwiseMax(p.head<2>());
  }
  shape.centre = 0.5 * (low + high);
  shape.half_extent = std::max(0.5 * (high - low).maxCoeff(), 1e-9);
  return shape;
}

std::vector<TargetCornerObservation> DeformedCorners(
    const std::vector<TargetCornerObservation>& corners, const TargetShape& shape,
    const double* c) {
  std::vector<TargetCornerObservation> moved = corners;
  if (shape.size() == 0) return moved;
  for (TargetCornerObservation& corner : moved) corner.p_t = shape.Deform(corner.p_t, c);
  return moved;
}

TargetDeformationHeights MakeTargetDeformationHeights(const CalibrationTarget& target,
                                                      const TargetShape& shape) {
  const int k = shape.size();
  TargetDeformationHeights heights;
  const double a = shape.half_extent;
  heights.names = {"centre", "corner_-x-y", "corner_+x-y", "corner_+x+y", "corner_-x+y"};
  heights.xy = {shape.centre,
                shape.centre + Eigen::Vector2d(-a, -a),
                shape.centre + Eigen::Vector2d(a, -a),
                shape.centre + Eigen::Vector2d(a, a),
                shape.centre + Eigen::Vector2d(-a, a)};
  // h at the points as B c; the least-squares plane through them, P = A (A^T A)^-1 A^T with
  // A = [1 x y], is (A^T A)^-1 A^T B c; a location's height above it is (b(x, y) - [1 x y]
  // (A^T A)^-1 A^T B) c.
  const int n = static_cast<int>(target.points.size());
  Eigen::MatrixXd A(n, 3), B(n, k);
  int i = 0;
  for (const auto& [id, p] : target.points) {
    A.row(i) << 1.0, p.x(), p.y();
    B.row(i) = shape.Basis(p.x(), p.y()).head(k).transpose();
    ++i;
  }
  const Eigen::MatrixXd plane = (A.transpose() * A).ldlt().solve(A.transpose() * B);  // 3 x k
  heights.M.resize(static_cast<int>(heights.xy.size()), k);
  for (size_t r = 0; r < heights.xy.size(); ++r) {
    const Eigen::Vector2d& q = heights.xy[r];
    heights.M.row(static_cast<int>(r)) = shape.Basis(q.x(), q.y()).head(k).transpose() -
                                         Eigen::RowVector3d(1.0, q.x(), q.y()) * plane;
  }
  return heights;
}

}  // namespace splinecal

#include "splinecal/intrinsics/target_deformation.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "splinecal/error.h"

namespace splinecal {

const char* TargetDeformationName(TargetDeformationKind kind) {
  return NameOf(kTargetDeformationKinds, kind);
}

int TargetDeformationSize(TargetDeformationKind kind) {
  return RowOf(kTargetDeformationKinds, kind).size;
}

std::vector<std::string> TargetDeformationCoefficientNames(TargetDeformationKind kind) {
  if (kind == TargetDeformationKind::kInPlane) return {"e1", "e2", "d"};
  if (kind == TargetDeformationKind::kInPlanePerView) return {"e1", "e2"};
  if (kind == TargetDeformationKind::kPoints || kind == TargetDeformationKind::kPointsInPlane) {
    return {"x", "y", "z"};  // each point's offset
  }
  const std::vector<std::string> basis = {"ss", "st", "tt", "sss", "sst", "stt", "ttt"};
  return {basis.begin(), basis.begin() + TargetDeformationSize(kind)};
}

Eigen::Matrix<double, kMaxTargetDeformationSize, 1> TargetShape::Basis(double x, double y) const {
  const double s = (x - centre.x()) / half_extent;
  const double t = (y - centre.y()) / half_extent;
  Eigen::Matrix<double, kMaxTargetDeformationSize, 1> b;
  b << s * s, s * t, t * t, s * s * s, s * s * t, s * t * t, t * t * t;
  return b;
}

TargetDisplacement TargetShape::Displacement(const Eigen::Vector3d& p_t) const {
  TargetDisplacement D = TargetDisplacement::Zero();
  if (per_point()) {
    D.leftCols<3>().setIdentity();
  } else if (out_of_plane()) {
    D.row(2) = Basis(p_t.x(), p_t.y()).transpose();
  } else if (in_plane()) {
    const Eigen::Vector2d u = p_t.head<2>() - centre;
    // The tag's centre: corners sit at k pitch + (0 or tag side) from the grid's origin
    // (camera/target.h), so (x - side / 2) / pitch is k +- side / (2 pitch), nearest k.
    const Eigen::Vector2d tag_centre =
        ((p_t.head<2>().array() - 0.5 * tag_size_m) / tag_pitch_m).round() * tag_pitch_m +
        0.5 * tag_size_m;
    const Eigen::Vector2d o = p_t.head<2>() - tag_centre;
    D.col(0).head<2>() << u.x(), -u.y();
    D.col(1).head<2>() << u.y(), u.x();
    D.col(kInsetColumn).head<2>() = o;
  }
  return D;
}

Eigen::Vector3d TargetShape::Deform(const Eigen::Vector3d& p_t,
                                    const double* c,
                                    double inset) const {
  const int k = size();
  if (k == 0) return p_t;
  const TargetDisplacement D = Displacement(p_t);
  Eigen::Vector3d moved = p_t;
  for (int i = 0; i < k; ++i) moved += c[i] * D.col(i);
  if (per_view_inset()) moved += inset * D.col(kInsetColumn);
  return moved;
}

TargetShape MakeTargetShape(const CalibrationTarget& target, TargetDeformationKind kind) {
  TargetShape shape;
  shape.kind = kind;
  if (target.points.empty()) return shape;
  Eigen::Vector2d low = Eigen::Vector2d::Constant(1e300), high = -low;
  for (const auto& [id, p] : target.points) {
    // Points may start from any geometry (a target refined before); the smooth kinds need the
    // plane their basis is defined in.
    if (kind != TargetDeformationKind::kNone && kind != TargetDeformationKind::kPoints &&
        kind != TargetDeformationKind::kPointsInPlane && std::abs(p.z()) > 1e-12) {
      throw Error(
          "target deformation: the target's points must lie in its plane z = 0 (point " +
          std::to_string(id) + " does not)");
    }
    low = low.cwiseMin(p.head<2>());
    high = high.cwiseMax(p.head<2>());
  }
  shape.centre = 0.5 * (low + high);
  shape.half_extent = std::max(0.5 * (high - low).maxCoeff(), 1e-9);
  if (shape.in_plane()) {
    if (target.type != "aprilgrid" || !(target.tag_spacing_ratio > 0.0)) {
      throw Error(
          "target deformation in-plane: needs an aprilgrid with tags apart (tagSpacing > 0), so "
          "that each corner belongs to one tag; got target type '" + target.type +
          "', tagSpacing " + std::to_string(target.tag_spacing_ratio));
    }
    shape.tag_size_m = target.tag_size_m;
    shape.tag_pitch_m = (1.0 + target.tag_spacing_ratio) * target.tag_size_m;
    // Every point a corner of its tag, half a side from its centre in x and y (the layout
    // Displacement assumes).
    for (const auto& [id, p] : target.points) {
      const Eigen::Vector3d o = shape.Displacement(p).col(TargetShape::kInsetColumn);
      if (((o.head<2>().cwiseAbs().array() - 0.5 * shape.tag_size_m).abs() > 1e-9).any()) {
        throw Error("target deformation in-plane: point " + std::to_string(id) +
                    " is not a tag corner of the aprilgrid's layout (camera/target.h)");
      }
    }
  }
  return shape;
}

std::vector<TargetCornerObservation> DeformedCorners(
    const std::vector<TargetCornerObservation>& corners,
    const TargetShape& shape,
    const double* c,
    double inset) {
  std::vector<TargetCornerObservation> moved = corners;
  if (shape.size() == 0) return moved;
  for (TargetCornerObservation& corner : moved) corner.p_t = shape.Deform(corner.p_t, c, inset);
  return moved;
}

TargetDeformationHeights MakeTargetDeformationHeights(const CalibrationTarget& target,
                                                      const TargetShape& shape) {
  const int k = shape.size();
  TargetDeformationHeights heights;
  if (!shape.out_of_plane()) {
    heights.M.resize(0, k);
    return heights;
  }
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

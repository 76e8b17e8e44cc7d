#include "splinecal/intrinsics/target_points_check.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>

#include "splinecal/string_printf.h"

namespace splinecal {

namespace {

// Per point: I_p, s_p, the number of views and the file's position.
struct PointScore {
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
  Eigen::Vector3d score = Eigen::Vector3d::Zero();
  int views = 0;
  Eigen::Vector3d p_t = Eigen::Vector3d::Zero();
};

}  // namespace

TargetPointsCheck CheckTargetPoints(const std::vector<TargetPointsCheckView>& views,
                                    int min_views) {
  std::map<int64_t, PointScore> by_point;  // ordered: the sums run in a fixed order
  for (const TargetPointsCheckView& v : views) {
    const Eigen::Matrix3d R_c_t = v.T_c_t.rotationMatrix();
    const double inv_sigma = 1.0 / v.sigma_px;
    for (size_t i = 0; i < v.view->corners.size(); ++i) {
      const TargetCornerObservation& corner = v.view->corners[i];
      Eigen::Vector2d uv;
      Eigen::Matrix<double, 2, 3> J_uv_p;
      if (!v.camera.Project(v.T_c_t * corner.p_t, &uv, &J_uv_p)) continue;
      const Eigen::Vector2d r = inv_sigma * (corner.uv - uv);
      const Eigen::Matrix<double, 2, 3> J = inv_sigma * J_uv_p * R_c_t;
      PointScore& p = by_point[v.view->point_ids[i]];
      p.information += J.transpose() * J;
      p.score += J.transpose() * r;
      p.p_t = corner.p_t;
      ++p.views;
    }
  }
  TargetPointsCheck check;
  double sum_squared_offsets = 0.0;
  for (const auto& [id, p] : by_point) {
    if (p.views < min_views) continue;
    const Eigen::LDLT<Eigen::Matrix3d> ldlt(p.information);
    if (ldlt.info() != Eigen::Success || !ldlt.isPositive() ||
        !(ldlt.vectorD().minCoeff() > 1e-12 * ldlt.vectorD().maxCoeff())) {
      continue;
    }
    const Eigen::Vector3d delta = ldlt.solve(p.score);
    check.chi_square += p.score.dot(delta);
    sum_squared_offsets += delta.squaredNorm();
    check.max_offset_m = std::max(check.max_offset_m, delta.norm());
    ++check.points;
    check.file_points_m[id] = p.p_t;
    check.offsets_m[id] = delta;
    check.offsets_std_m[id] =
        ldlt.solve(Eigen::Matrix3d::Identity()).diagonal().cwiseMax(0.0).cwiseSqrt();
  }
  if (check.points > 0) check.rms_offset_m = std::sqrt(sum_squared_offsets / check.points);
  check.dof = check.points >= 3 ? 3 * check.points - 7 : 0;
  return check;
}

std::string TargetPointsWarning(const TargetPointsCheck& check) {
  if (!(check.RatioToDof() > kTargetPointsWarnRatio)) return "";
  return StringPrintf(
      "the target's corners sit %.2f mm RMS (up to %.2f mm) off the points of its file "
      "(chi-square %.1f per degree of freedom over %d points, about 1 when the file is right): "
      "the file's layout biases the intrinsics; --target-deformation points estimates every "
      "point (docs/intrinsics.md, \"Every point free\")",
      1e3 * check.rms_offset_m, 1e3 * check.max_offset_m, check.RatioToDof(), check.points);
}

}  // namespace splinecal

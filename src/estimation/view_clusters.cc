#include "splinecal/estimation/view_clusters.h"

#include <algorithm>

namespace splinecal {
namespace {

int Cell(double coordinate, int size) {
  return std::clamp(static_cast<int>(coordinate / size * kViewClusterCells), 0,
                    kViewClusterCells - 1);
}

}  // namespace

int ViewCluster(const Camera& camera,
                const std::vector<TargetCornerObservation>& corners,
                const SE3d& T_c_t) {
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const TargetCornerObservation& corner : corners) centroid += corner.uv;
  centroid /= static_cast<double>(std::max<size_t>(corners.size(), 1));
  const int cell =
      Cell(centroid.y(), camera.height) * kViewClusterCells + Cell(centroid.x(), camera.width);
  // The target normal, turned towards the camera (z < 0 in the camera frame); its x and y say
  // which way the target tilts.
  Eigen::Vector3d normal = T_c_t.so3().matrix().col(2);
  if (normal.z() > 0.0) normal = -normal;
  const int quadrant = (normal.x() > 0.0 ? 1 : 0) + (normal.y() > 0.0 ? 2 : 0);
  return cell * 4 + quadrant;
}

}  // namespace splinecal

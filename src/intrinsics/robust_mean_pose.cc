#include "splinecal/intrinsics/robust_mean_pose.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "splinecal/lie/so3.h"
#include "splinecal/median.h"

namespace splinecal {
SE3d RobustMeanPose(const std::vector<SE3d>& candidates, int* inliers) {
  const size_t n = candidates.size();
  std::vector<double> norms;
  for (const SE3d& c : candidates) norms.push_back(c.translation().norm());
  const double scale = std::max(Median(norms), 1e-6);
  auto distance = [&](const SE3d& a, const SE3d& b) {
    const double angle = (a.so3().inverse() * b.so3()).Log().norm();
    return angle + (a.translation() - b.translation()).norm() / scale;
  };
  const size_t tries = std::min<size_t>(kMedoidCandidates, n);
  size_t medoid = 0;
  double medoid_spread = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < tries; ++k) {
    const size_t i = k * n / tries;
    std::vector<double> d;
    for (size_t j = 0; j < n; j += std::max<size_t>(1, n / kMedoidCandidates)) {
      d.push_back(distance(candidates[i], candidates[j]));
    }
    const double spread = Median(d);
    if (spread < medoid_spread) {
      medoid_spread = spread;
      medoid = i;
    }
  }
  const SE3d& center = candidates[medoid];
  const Eigen::Quaterniond q0 = center.so3().quaternion();
  Eigen::Vector4d q_sum = Eigen::Vector4d::Zero();
  Eigen::Vector3d t_sum = Eigen::Vector3d::Zero();
  int count = 0;
  const double radius = 3.0 * medoid_spread + 1e-12;
  for (const SE3d& c : candidates) {
    if (distance(center, c) > radius) continue;
    Eigen::Vector4d q = c.so3().quaternion().coeffs();
    if (q.dot(q0.coeffs()) < 0.0) q = -q;
    q_sum += q;
    t_sum += c.translation();
    ++count;
  }
  if (inliers != nullptr) *inliers = count;
  Eigen::Quaterniond q_mean;
  q_mean.coeffs() = q_sum.normalized();
  return SE3d(SO3d(q_mean), t_sum / count);
}

}  // namespace splinecal

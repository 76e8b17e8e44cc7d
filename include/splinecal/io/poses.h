// Pose sources: a trajectory in TUM format (`t_s tx ty tz qx qy qz qw`) or EuRoC ground truth
// (`t_ns, px py pz, qw qx qy qz, ...`), told apart by their separators (docs/conventions.md).
#ifndef SPLINECAL_IO_POSES_H_
#define SPLINECAL_IO_POSES_H_

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace splinecal {

// A timestamped pose T_a_b: q rotates b into a, p is b's origin in a.
struct StampedPose {
  int64_t t_ns = 0;
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();  // unit norm
};

// Reads a TUM trajectory. Times are seconds as decimal text, converted to int64 ns exactly.
std::vector<StampedPose> ReadTumTrajectory(const std::string& path);
void WriteTumTrajectory(const std::vector<StampedPose>& poses, std::ostream* out);

// Reads either format: comma-separated lines are EuRoC ground truth (at least 8 columns),
// whitespace-separated lines with 8 columns are TUM. Timestamps must be strictly increasing and
// quaternions of unit norm (within 1e-3; they are then normalised). At least 2 poses.
std::vector<StampedPose> ReadPoses(const std::string& path);

}  // namespace splinecal

#endif  // SPLINECAL_IO_POSES_H_

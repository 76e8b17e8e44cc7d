// Rotations and rigid transforms in YAML files (Kalibr's layout: a list of rows), checked: a
// matrix that is not a rotation is in another layout or corrupt, and is refused with its line.
#ifndef SPLINECAL_IO_YAML_TRANSFORMS_H_
#define SPLINECAL_IO_YAML_TRANSFORMS_H_

#include <Eigen/Core>
#include <string>

#include "splinecal/io/yaml_document.h"
#include "splinecal/lie/se3.h"

namespace splinecal {

// A rotation block this far from orthonormal (max |R^T R - I|) is not a rotation: the matrix is
// in another layout or corrupt, not rounded in its last digits.
inline constexpr double kMaxOrthonormalityError = 1e-6;

// The 3x3 rows at `key` (any numbers). Throws Error naming the file and line for another shape.
Eigen::Matrix3d ReadMatrix3(const YamlDocument& yaml, const std::string& key);

// The rotation matrix at `key` (3 rows of 3): orthonormal within kMaxOrthonormalityError, with
// determinant +1, re-orthonormalised (through its quaternion).
SO3d ReadRotation(const YamlDocument& yaml, const std::string& key);

// The 4x4 rigid transform at `key` (e.g. T_cam_imu, T_i_b): its rotation block a rotation, its
// last row 0 0 0 1, its translation within kMaxPosition (io/text_file.h).
SE3d ReadRigidTransform(const YamlDocument& yaml, const std::string& key);

}  // namespace splinecal

#endif  // SPLINECAL_IO_YAML_TRANSFORMS_H_

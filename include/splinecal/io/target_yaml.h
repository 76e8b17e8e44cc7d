// Calibration target YAML (camera/target.h), Kalibr's keys, read with io/yaml_document.h:
//
//   target_type: aprilgrid      tagCols, tagRows (integers), tagSize [m], tagSpacing (ratio)
//   target_type: checkerboard   targetCols, targetRows (inner corners), rowSpacingMeters,
//                               colSpacingMeters
//   target_type: points         points: [[id, x, y, z], ...]   (integer ids >= 0, metres)
#ifndef SPLINECAL_IO_TARGET_YAML_H_
#define SPLINECAL_IO_TARGET_YAML_H_

#include <string>

#include "splinecal/camera/target.h"

namespace splinecal {

// Throws splinecal::Error (file:line: what is wrong) for an unknown target_type, missing or
// invalid keys, duplicate or negative point ids, fewer than 4 points.
CalibrationTarget ReadTargetYaml(const std::string& path);

// The YAML text of a `points` target holding every point of `target` (any type).
std::string TargetPointsYamlText(const CalibrationTarget& target);

}  // namespace splinecal

#endif  // SPLINECAL_IO_TARGET_YAML_H_

// Rotation helpers the tests share: random unit quaternions from a seeded generator and the angle
// between two directions.
#ifndef SPLINECAL_TESTS_TESTING_ROTATIONS_H_
#define SPLINECAL_TESTS_TESTING_ROTATIONS_H_

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "splinecal/units.h"

namespace splinecal {
namespace testing {

// Uniform on the rotations: a normalised 4-D Gaussian draw.
inline Eigen::Quaterniond RandomQuaternion(std::mt19937* rng) {
  std::normal_distribution<double> normal;
  return Eigen::Quaterniond(normal(*rng), normal(*rng), normal(*rng), normal(*rng)).normalized();
}

// The angle between directions a and b [deg], accurate near 0 and 180 (atan2, not acos).
inline double AngleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * kRadToDeg;
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_TESTING_ROTATIONS_H_

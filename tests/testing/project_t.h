// Camera::Project for any scalar (ceres::Jet for automatic differentiation): the oracle the
// camera model's analytic Jacobians are tested against (tests/camera/camera_jacobian_test.cc). It
// shares the valid-region test (internal::ProjectionDenominator) and the distortion
// (internal::Distort) with Camera::Project, so only the chain rule of camera/camera_model.h is
// checked by it. Test code only: the library has no use for it.
#ifndef SPLINECAL_TESTS_TESTING_PROJECT_T_H_
#define SPLINECAL_TESTS_TESTING_PROJECT_T_H_

#include <Eigen/Core>

#include "splinecal/camera/camera_model.h"
#include "splinecal/camera/distortion.h"
#include "splinecal/camera/projection.h"

namespace splinecal {
namespace testing {

// uv of p_c for the model (projection, distortion) with intrinsics pointing at kNumIntrinsics
// entries in the layout of camera/camera_model.h. False outside the valid region.
template <typename T>
bool ProjectT(ProjectionModel projection,
              DistortionModel distortion,
              const T* intrinsics,
              const Eigen::Matrix<T, 3, 1>& p_c,
              Eigen::Matrix<T, 2, 1>* uv) {
  T den;
  if (!internal::ProjectionDenominator(
          projection, intrinsics + kProjectionParamsIndex, p_c, &den)) {
    return false;
  }
  const Eigen::Matrix<T, 2, 1> md = internal::Distort(
      distortion, intrinsics + kDistortionCoeffsIndex, p_c.x() / den, p_c.y() / den);
  (*uv)(0) = intrinsics[0] * md(0) + intrinsics[2];
  (*uv)(1) = intrinsics[1] * md(1) + intrinsics[3];
  return true;
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_TESTING_PROJECT_T_H_

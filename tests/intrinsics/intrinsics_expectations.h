// The accuracy check the simulated intrinsics tests share: every estimated intrinsic within k
// of its reported standard deviations of the truth.
#ifndef SPLINECAL_TESTS_INTRINSICS_INTRINSICS_EXPECTATIONS_H_
#define SPLINECAL_TESTS_INTRINSICS_INTRINSICS_EXPECTATIONS_H_

#include <gtest/gtest.h>

#include <cmath>

#include "splinecal/intrinsics/calibrate_intrinsics.h"
#include "splinecal/intrinsics/intrinsics_observability.h"

namespace splinecal {
namespace testing {

// Every active intrinsic of `result` within `k` of its reported std of the truth.
inline void ExpectWithinStd(const IntrinsicsCameraResult& result, const Camera& truth, double k) {
  const IntrinsicsVector estimate = result.camera.intrinsics();
  const IntrinsicsVector expected = truth.intrinsics();
  for (int i : result.active) {
    SCOPED_TRACE(IntrinsicName(truth, i));
    ASSERT_TRUE(std::isfinite(result.intrinsics_std(i)));
    EXPECT_LT(std::abs(estimate(i) - expected(i)), k * result.intrinsics_std(i))
        << "estimate " << estimate(i) << " truth " << expected(i) << " std "
        << result.intrinsics_std(i);
  }
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_INTRINSICS_INTRINSICS_EXPECTATIONS_H_

// The two trajectory models (spline/trajectory_model.h) as a GoogleTest parameter. A suite that
// runs on both:
//
//   class Suite : public ::testing::TestWithParam<TrajectoryModel> {};
//   INSTANTIATE_TEST_SUITE_P(Models, Suite, testing::BothTrajectoryModels(),
//                            testing::TrajectoryModelTestName);
//
// names its instances .../se3 and .../split, and gtest prints the parameter by name.
#ifndef SPLINECAL_TESTS_TESTING_TRAJECTORY_MODELS_H_
#define SPLINECAL_TESTS_TESTING_TRAJECTORY_MODELS_H_

#include <gtest/gtest.h>

#include <ostream>
#include <string>

#include "splinecal/spline/trajectory_model.h"

namespace splinecal {

// gtest's printer for the parameter (found by argument-dependent lookup).
inline void PrintTo(TrajectoryModel model, std::ostream* out) { *out << TrajectoryModelName(model); }

namespace testing {

inline auto BothTrajectoryModels() {
  return ::testing::Values(TrajectoryModel::kSE3, TrajectoryModel::kSplitSO3R3);
}

inline std::string TrajectoryModelTestName(const ::testing::TestParamInfo<TrajectoryModel>& info) {
  return TrajectoryModelName(info.param);
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_TESTING_TRAJECTORY_MODELS_H_

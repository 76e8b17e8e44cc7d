// Shared by the considered-intrinsics tests (consider_covariance_test.cc,
// calibrate_consider_slow_test.cc): the 8 s global-shutter scenario with EuRoC's radtan camera,
// a diagonal covariance of its intrinsics, and calibrate run with them considered and held.
#ifndef SPLINECAL_TESTS_CALIB_CONSIDER_TEST_HELPERS_H_
#define SPLINECAL_TESTS_CALIB_CONSIDER_TEST_HELPERS_H_

#include <Eigen/Core>

#include "calib/calibrate_test_checks.h"
#include "calib/calibrate_test_scenario.h"
#include "splinecal/calib/calibrate.h"

namespace splinecal {
namespace testing {

inline CalibrationScenario ConsiderScenario() {
  ScenarioOptions o;
  o.duration_s = 8.0;
  o.line_delay_s = 0.0;
  return MakeCalibrationScenario(o);
}

// pinhole-radtan's fu fv pu pv, k1 k2 p1 p2 (Kalibr's order), independent, with these stds.
inline CameraCovariance DiagonalRadtanCovariance(const Eigen::Matrix<double, 8, 1>& std) {
  CameraCovariance covariance;
  covariance.intrinsics = {0, 1, 2, 3, 6, 7, 8, 9};
  covariance.matrix = std.cwiseAbs2().asDiagonal();
  return covariance;
}

struct ConsideredAndHeld {
  CalibrationResult consider;
  CalibrationResult held;
};

// `options` with the covariance given, the intrinsics considered, then held.
inline ConsideredAndHeld CalibrateConsideredAndHeld(const CalibrationScenario& s,
                                                    const CameraCovariance& covariance,
                                                    CalibrateOptions options) {
  options.camchain_covariances = {covariance};
  ConsideredAndHeld r;
  options.intrinsics = ParameterMode::kConsider;
  r.consider = Calibrate(s.imu, s.observations, s.start, &s.target, options);
  options.intrinsics = ParameterMode::kHeld;
  r.held = Calibrate(s.imu, s.observations, s.start, &s.target, options);
  return r;
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_CALIB_CONSIDER_TEST_HELPERS_H_

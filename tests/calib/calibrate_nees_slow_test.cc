// Monte-Carlo consistency of calibrate's reported standard deviations (label "slow"): the
// normalised estimation error squared (NEES) of T_cam_imu's rotation (3) and translation (3), the
// time offset (1) and the line delay (1) over 120 seeds, on data made from a CLOSED-FORM
// trajectory (ClosedFormCalibrationTrajectory, calib/closed_form_simulation.h) that the
// estimator's spline only approximates, as on real data.
//
// CalibrationResult reports standard deviations only (CameraEstimate: rotation per axis in the
// right tangent of T_cam_imu, IMU frame; translation per axis, camera frame; time offset; line
// delay), not their correlations: the NEES here is the DIAGONAL one,
//
//     NEES = sum_i (e_i / std_i)^2,
//     e = [Log(R_true^T R_est) (3); t_est - t_true (3); offset_est - offset_true;
//          delay_est - delay_true].
//
// Its mean is still the dimension when the stds are honest, but for a group of correlated
// components (rotation, translation, all 8) the sum over seeds is not exactly chi-square: its
// variance exceeds 2 x dof by the correlations, so the chi-square interval is narrower than the
// true one for those groups. The 1-D groups (time offset, line delay) are exact. Each group's sum
// over the seeds, and the sum of all eight, must lie in the two-sided 95% interval of
// chi-square with seeds x dof degrees of freedom (Wilson-Hilferty, testing/chi_square.h).
// 120 seeds, not 20: over 20 a 1-D group whose variance is 1.5 times too large still passes 81%
// of the time, over 120 13% (docs/reliability.md, "Power of the NEES bands"). 1.3 CPU-s a seed.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "calib/calibrate_test_checks.h"
#include "calib/calibrate_test_scenario.h"
#include "splinecal/calib/calibrate.h"
#include "testing/chi_square.h"
#include "testing/tool_allocator.h"

namespace splinecal {
namespace {

TEST(CalibrateMonteCarlo, DiagonalNeesOnAClosedFormTrajectoryIsInsideItsInterval) {
  constexpr int kSeeds = 120;
  // NeesGroup::first: index in the 8-vector of normalised errors.
  std::vector<testing::NeesGroup> groups = {{"rotation", 0, 3},
                                            {"translation", 3, 3},
                                            {"time offset", 6, 1},
                                            {"line delay", 7, 1},
                                            {"all", 0, 8}};
  for (int seed = 1; seed <= kSeeds; ++seed) {
    testing::ScenarioOptions o;
    o.closed_form = true;
    o.duration_s = 8.0;
    o.seed = static_cast<uint64_t>(seed);
    const testing::CalibrationScenario s = testing::MakeCalibrationScenario(o);
    CalibrateOptions options = testing::FastOptions();
    options.rolling_shutter = true;
    options.keep_residuals = false;
    const CalibrationResult r = Calibrate(s.imu, s.observations, s.start, &s.target, options);
    ASSERT_TRUE(r.covariance_ok) << "seed " << seed;
    const testing::Errors e = testing::ErrorsOf(r.cameras[0].calibration, s.truth[0]);
    const CameraEstimate& c = r.cameras[0];
    Eigen::Matrix<double, 8, 1> z;  // errors over their stds
    z.head<3>() = e.rotation_deg.cwiseQuotient(c.rotation_std_deg);
    z.segment<3>(3) = e.translation_m.cwiseQuotient(c.translation_std_m);
    z[6] = e.time_offset_s / c.time_offset_std_s;
    z[7] = e.line_delay_s / c.line_delay_std_s;
    std::printf("seed %2d (%d frames, %d corners, %.1f s):",
                seed,
                s.camera_result.num_frames_with_target,
                s.camera_result.num_target_observations,
                r.solve.solve_time_s);
    for (testing::NeesGroup& group : groups) {
      const double nees = z.segment(group.first, group.dof).squaredNorm();
      group.sum += nees;
      std::printf(" %s %.2f", group.name, nees);
    }
    std::printf("\n");
    testing::Print("  ", r, e);
    std::fflush(stdout);
  }
  testing::ExpectNeesSumsInsideInterval95(groups, kSeeds);
}

}  // namespace
}  // namespace splinecal

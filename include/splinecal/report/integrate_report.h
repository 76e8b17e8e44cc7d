// `splinecal integrate` as a library call: the start and end the command integrates between,
// the dead reckoning of each method from the ground-truth state at the start (imu/integrate.h),
// its drift against the ground truth, and the files the command writes (result.yaml,
// trajectory_<method>.csv, trajectory.svg). The command line and the Python module both call
// these. See docs/integrate.md.
#ifndef SPLINECAL_REPORT_INTEGRATE_REPORT_H_
#define SPLINECAL_REPORT_INTEGRATE_REPORT_H_

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "splinecal/imu/imu_sample.h"
#include "splinecal/imu/integrate.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/output_dir.h"

namespace splinecal {

// The stretch integrate covers: from ground-truth row start_row to end_ns.
struct IntegrationSpan {
  size_t start_row = 0;
  int64_t end_ns = 0;
};

// The first ground-truth row at or after the IMU's first sample + start_s, and start_row's time
// + duration_s (duration_s = 0: the end of the IMU or ground-truth data, whichever is first).
// start_s and duration_s are already checked (>= 0, at most 1e9 s). Throws splinecal::Error
// naming truth_path when the start is outside the data, imu_path when the duration reaches past
// its end (worded with the command's flags, --start and --duration).
IntegrationSpan ChooseIntegrationSpan(const std::vector<ImuSample>& imu,
                                      const std::vector<GroundTruthState>& truth,
                                      double start_s,
                                      double duration_s,
                                      const std::string& imu_path,
                                      const std::string& truth_path);

struct IntegrationRun {
  struct Method {
    IntegrationMethod method;
    DriftMetrics drift;
  };
  NavState start;               // the ground-truth state integrated from
  std::vector<Method> methods;  // in the order asked for
  std::vector<OutputFile> files;  // result.yaml, trajectory_<method>.csv, trajectory.svg
};

// Integrates `imu` over `span` with each method from the ground-truth state and biases of its
// start row, gravity g_w = (0, 0, -gravity_m_s2), and compares with `truth`.
IntegrationRun RunIntegration(const std::vector<ImuSample>& imu,
                              const std::vector<GroundTruthState>& truth,
                              const IntegrationSpan& span,
                              const std::vector<IntegrationMethod>& methods,
                              double gravity_m_s2);

}  // namespace splinecal

#endif  // SPLINECAL_REPORT_INTEGRATE_REPORT_H_

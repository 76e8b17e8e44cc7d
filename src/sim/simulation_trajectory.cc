#include "splinecal/sim/simulation_trajectory.h"

#include <string>

#include "splinecal/sim/simulate_camera.h"
#include "splinecal/sim/simulate_imu.h"
#include "splinecal/sim/trajectories.h"
#include "splinecal/spline/knot_layout.h"
#include "splinecal/string_printf.h"
#include "splinecal/units.h"

namespace splinecal {

SimulationSpline FitSimulationTrajectory(const SimulationTrajectory& trajectory,
                                         int64_t start_ns,
                                         int64_t end_ns,
                                         int64_t knot_spacing_ns,
                                         const PoseFitOptions& options) {
  auto progress = [&options](const std::string& line) {
    if (options.progress) options.progress(line);
  };
  const std::string knots_s = std::to_string(NanosecondsToSeconds(knot_spacing_ns));
  const std::string duration_s = std::to_string(NanosecondsToSeconds(end_ns - start_ns));
  SimulationSpline out;
  if (!trajectory.recorded_poses.empty()) {
    out.source = trajectory.recorded_source;
    progress("simulate: fitting " + knots_s + " s knots to " +
             std::to_string(trajectory.recorded_poses.size()) + " poses of " + out.source);
    out.fit = FitControlPoses(
        trajectory.recorded_poses, KnotLayoutCovering(start_ns, end_ns, knot_spacing_ns), options);
  } else if (trajectory.name == "calibration") {
    out.source = "calibration";
    progress("simulate: fitting the calibration trajectory (" + duration_s + " s, knots every " +
             knots_s + " s)");
    out.fit = FitCalibrationTrajectory(trajectory.target_centre_w,
                                       trajectory.T_cam_imu,
                                       start_ns,
                                       end_ns,
                                       knot_spacing_ns,
                                       trajectory.seed);
  } else {
    const AnalyticTrajectory analytic = MakeTrajectory(trajectory.name, trajectory.seed);
    out.source = analytic.name();
    progress("simulate: fitting the " + out.source + " trajectory (" + duration_s +
             " s, knots every " + knots_s + " s)");
    out.fit = FitAnalyticTrajectory(analytic, start_ns, end_ns, knot_spacing_ns, 0, options);
  }
  progress(StringPrintf(
      "simulate: spline fit position RMS %.3g m, rotation RMS %.3g deg (%d control poses)",
      out.fit.position_rms_m,
      out.fit.rotation_rms_deg,
      out.fit.layout.num_control_poses));
  return out;
}

}  // namespace splinecal

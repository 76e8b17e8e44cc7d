// `splinecal evaluate`: reads a spline.csv and evaluates it - pose, body angular velocity, world
// velocity and acceleration, and the IMU reading it predicts - at evenly spaced times (printed)
// and optionally at a fixed rate over the whole valid range (written to evaluation.csv).
#include <gflags/gflags.h>

#include <cstdio>

#include "splinecal/cli/command.h"
#include "splinecal/cli/commands.h"
#include "splinecal/cli/common_flags.h"
#include "splinecal/cli/console_text.h"
#include "splinecal/error.h"
#include "splinecal/io/output_dir.h"
#include "splinecal/io/spline_csv.h"
#include "splinecal/report/evaluate_report.h"
#include "splinecal/spline/trajectory_model.h"
#include "splinecal/units.h"

DEFINE_string(spline, "", "Control poses, spline.csv [path]");
DEFINE_int32(samples, 5, "Evenly spaced times to print, ends included [count]");
DEFINE_double(every,
              0.0,
              "Also write evaluation.csv with a row every this many seconds [s]; 0: no");

namespace splinecal {
namespace cli {

namespace {

// What evaluate reads and checks before evaluating anything (Command::read_inputs).
struct EvaluateInputs {
  SE3Splined spline;
  EvaluateOptions options;
};

EvaluateInputs ReadEvaluateInputs() {
  EvaluateInputs in{ReadSplineCsv(RequiredFlag("spline", FLAGS_spline)), EvaluateOptions{}};
  in.options.samples = FLAGS_samples;
  in.options.every_s = FLAGS_every;
  in.options.gravity_m_s2 = PositiveFlag("gravity", FLAGS_gravity);
  in.options.gyro_bias = Vector3Flag("gyro-bias", FLAGS_gyro_bias);
  in.options.accel_bias = Vector3Flag("accel-bias", FLAGS_accel_bias);
  CheckEvaluateOptions(in.spline, in.options);
  RequiredFlag("out", FLAGS_out);
  return in;
}

int RunEvaluate() {
  const EvaluateInputs in = ReadEvaluateInputs();
  const SE3Splined& spline = in.spline;
  OutputDir output(FLAGS_out);

  std::printf("spline: %d control poses, dt = %.6g s, %s, valid %.6f s to %.6f s after t0\n",
              spline.num_control_poses(),
              spline.dt(),
              TrajectoryModelName(spline.model()),
              spline.start_time(),
              spline.end_time());
  std::printf("%10s  %29s  %26s  %26s  %26s\n",
              "t - t_1 [s]",
              "p_w_s [m]",
              "w_s [rad/s]",
              "gyro [rad/s]",
              "accel [m/s^2]");
  const EvaluateRun run = EvaluateSplineFiles(spline, FLAGS_spline, in.options);
  for (const SplineEvaluation& e : run.samples) {
    std::printf("%10.4f  %s  %s  %s  %s\n",
                NanosecondsToSeconds(e.t_ns - spline.start_time_ns()),
                BracketedVector(e.T_w_s.translation(), "%8.4f").c_str(),
                BracketedVector(e.w_s, "%7.4f").c_str(),
                BracketedVector(e.gyro, "%7.4f").c_str(),
                BracketedVector(e.accel, "%7.3f").c_str());
  }
  output.WriteFiles(run.files);
  output.Commit();
  return 0;
}

}  // namespace

Command EvaluateCommand() {
  return {"evaluate",
          "evaluate a spline.csv: pose, rates, IMU prediction",
          "splinecal evaluate --spline FILE --out DIR [--samples N] [--every S]\n"
          "    [--gravity M_S2] [--gyro-bias X,Y,Z] [--accel-bias X,Y,Z]",
          "Reads the control poses of a spline (spline.csv) and evaluates the spline, in the\n"
          "trajectory model the file names (se3 or split), at N evenly spaced times of its valid\n"
          "range [t_1, t_{n-2}]: pose T_w_s, body angular velocity, world velocity and\n"
          "acceleration, and the IMU reading it predicts for the given biases and gravity.\n"
          "Prints a table; writes samples.csv, result.yaml and, with --every, evaluation.csv.",
          {{"spline", ""},
           {"out", ""},
           {"samples", ""},
           {"every", ""},
           {"gravity", ""},
           {"gyro_bias", "Gyro bias b_g added to the prediction, x,y,z [rad/s]"},
           {"accel_bias", "Accelerometer bias b_a added to the prediction, x,y,z [m/s^2]"}},
          &RunEvaluate,
          [] { ReadEvaluateInputs(); }};
}

}  // namespace cli
}  // namespace splinecal

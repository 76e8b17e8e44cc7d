// `splinecal evaluate`: reads a spline.csv and evaluates it - pose, body angular velocity, world
// velocity and acceleration, and the IMU reading it predicts - at evenly spaced times (printed)
// and optionally at a fixed rate over the whole valid range (written to evaluation.csv).
#include <gflags/gflags.h>

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "splinecal/cli/command.h"
#include "splinecal/cli/commands.h"
#include "splinecal/cli/common_flags.h"
#include "splinecal/error.h"
#include "splinecal/imu/imu_model.h"
#include "splinecal/io/output_dir.h"
#include "splinecal/io/spline_csv.h"
#include "splinecal/io/yaml_writer.h"
#include "splinecal/spline/trajectory_model.h"
#include "splinecal/string_printf.h"
#include "splinecal/units.h"

DEFINE_string(spline, "", "Control poses, spline.csv [path]");
DEFINE_int32(samples, 5, "Evenly spaced times to print, ends included [count]");
DEFINE_double(every,
              0.0,
              "Also write evaluation.csv with a row every this many seconds [s]; 0: no");

namespace splinecal {
namespace cli {

namespace {

struct Evaluation {
  int64_t t_ns;
  SE3d T_w_s;
  Eigen::Vector3d w_s, v_w, a_w, gyro, accel;
};

Evaluation EvaluateAt(const SE3Splined& spline,
                      int64_t t_ns,
                      const Eigen::Vector3d& g_w,
                      const Eigen::Vector3d& b_g,
                      const Eigen::Vector3d& b_a) {
  Evaluation e;
  e.t_ns = t_ns;
  const Segment<double> segment = spline.SegmentAtNs(t_ns);
  spline.Evaluate(segment, &e.T_w_s, &e.w_s, nullptr, &e.v_w, &e.a_w);
  PredictImu(spline, segment, g_w, b_g, b_a, &e.gyro, &e.accel);
  return e;
}

std::string CsvRow(const Evaluation& e) {
  const Eigen::Quaterniond& q = e.T_w_s.so3().quaternion();
  const Eigen::Vector3d& p = e.T_w_s.translation();
  std::string row = std::to_string(e.t_ns);
  for (double v : {p.x(), p.y(), p.z(), q.w(), q.x(), q.y(), q.z()}) row += "," + FormatDouble(v);
  for (const Eigen::Vector3d* vec : {&e.w_s, &e.v_w, &e.a_w, &e.gyro, &e.accel}) {
    for (int i = 0; i < 3; ++i) row += "," + FormatDouble((*vec)[i]);
  }
  return row + "\n";
}

// What evaluate reads and checks before evaluating anything (Command::read_inputs).
struct EvaluateInputs {
  SE3Splined spline;
  double every_s = 0.0;
  Eigen::Vector3d g_w = Eigen::Vector3d::Zero();
  Eigen::Vector3d b_g = Eigen::Vector3d::Zero();
  Eigen::Vector3d b_a = Eigen::Vector3d::Zero();
};

EvaluateInputs ReadEvaluateInputs() {
  EvaluateInputs in{ReadSplineCsv(RequiredFlag("spline", FLAGS_spline))};
  if (FLAGS_samples < 2 || FLAGS_samples > 100000) {
    throw Error("--samples: expected 2 to 100000, got " + std::to_string(FLAGS_samples));
  }
  in.every_s = NonNegativeFlag("every", FLAGS_every);
  in.g_w = GravityWorld(PositiveFlag("gravity", FLAGS_gravity));
  in.b_g = Vector3Flag("gyro-bias", FLAGS_gyro_bias);
  in.b_a = Vector3Flag("accel-bias", FLAGS_accel_bias);
  const double span_s = NanosecondsToSeconds(in.spline.end_time_ns() - in.spline.start_time_ns());
  constexpr double kMaxRows = 1e8;  // refuse before allocating an absurd table
  if (in.every_s > 0.0 && span_s / in.every_s > kMaxRows) {
    throw Error("--every " + FormatDouble(in.every_s) + " s would write more than 1e8 rows");
  }
  RequiredFlag("out", FLAGS_out);
  return in;
}

int RunEvaluate() {
  const EvaluateInputs in = ReadEvaluateInputs();
  const SE3Splined& spline = in.spline;
  const double every_s = in.every_s;
  const Eigen::Vector3d& g_w = in.g_w;
  const Eigen::Vector3d& b_g = in.b_g;
  const Eigen::Vector3d& b_a = in.b_a;
  const int64_t start_ns = spline.start_time_ns();
  const int64_t end_ns = spline.end_time_ns();
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
  const std::string header =
      "#t_ns,px,py,pz,qw,qx,qy,qz,wx,wy,wz,vx,vy,vz,ax,ay,az,gyro_x,gyro_y,gyro_z,accel_x,"
      "accel_y,accel_z\n";
  std::string samples_csv = header;
  for (int k = 0; k < FLAGS_samples; ++k) {
    const int64_t t_ns =
        start_ns + static_cast<int64_t>(std::llround(static_cast<double>(end_ns - start_ns) * k /
                                                     (FLAGS_samples - 1)));
    const Evaluation e = EvaluateAt(spline, t_ns, g_w, b_g, b_a);
    samples_csv += CsvRow(e);
    const Eigen::Vector3d& p = e.T_w_s.translation();
    std::printf(
        "%10.4f  [%8.4f %8.4f %8.4f]  [%7.4f %7.4f %7.4f]  [%7.4f %7.4f %7.4f]  "
        "[%7.3f %7.3f %7.3f]\n",
        NanosecondsToSeconds(t_ns - start_ns),
        p.x(),
        p.y(),
        p.z(),
        e.w_s.x(),
        e.w_s.y(),
        e.w_s.z(),
        e.gyro.x(),
        e.gyro.y(),
        e.gyro.z(),
        e.accel.x(),
        e.accel.y(),
        e.accel.z());
  }
  output.WriteFile("samples.csv", samples_csv);
  int64_t rows = 0;
  if (every_s > 0.0) {
    // A step longer than the range gives the first row alone (and keeps llround in range).
    const int64_t span_ns = end_ns - start_ns;
    const int64_t step_ns = every_s * 1e9 > static_cast<double>(span_ns)
                                ? span_ns + 1
                                : std::max<int64_t>(1, std::llround(every_s * 1e9));
    std::string csv = header;
    for (; rows <= span_ns / step_ns; ++rows) {
      csv += CsvRow(EvaluateAt(spline, start_ns + rows * step_ns, g_w, b_g, b_a));
    }
    output.WriteFile("evaluation.csv", csv);
  }
  YamlWriter yaml;
  yaml.Scalar("spline", FLAGS_spline);
  yaml.Scalar("num_control_poses", spline.num_control_poses());
  yaml.Scalar("trajectory", std::string(TrajectoryModelName(spline.model())));
  yaml.Scalar("knot_spacing_s", spline.dt());
  yaml.Scalar("start_time_ns", start_ns);
  yaml.Scalar("end_time_ns", end_ns);
  yaml.Vector("gravity_w", g_w);
  yaml.Vector("gyro_bias", b_g);
  yaml.Vector("accel_bias", b_a);
  yaml.Scalar("evaluation_rows", rows);
  output.WriteFile("result.yaml", yaml.str());
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

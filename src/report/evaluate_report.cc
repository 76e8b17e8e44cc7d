#include "splinecal/report/evaluate_report.h"

#include <algorithm>
#include <cmath>

#include "splinecal/error.h"
#include "splinecal/imu/imu_model.h"
#include "splinecal/io/yaml_writer.h"
#include "splinecal/spline/trajectory_model.h"
#include "splinecal/string_printf.h"
#include "splinecal/units.h"

namespace splinecal {

namespace {

SplineEvaluation EvaluateAt(const SE3Splined& spline,
                            int64_t t_ns,
                            const Eigen::Vector3d& g_w,
                            const Eigen::Vector3d& b_g,
                            const Eigen::Vector3d& b_a) {
  SplineEvaluation e;
  e.t_ns = t_ns;
  const Segment<double> segment = spline.SegmentAtNs(t_ns);
  spline.Evaluate(segment, &e.T_w_s, &e.w_s, nullptr, &e.v_w, &e.a_w);
  PredictImu(spline, segment, g_w, b_g, b_a, &e.gyro, &e.accel);
  return e;
}

std::string CsvRow(const SplineEvaluation& e) {
  const Eigen::Quaterniond& q = e.T_w_s.so3().quaternion();
  const Eigen::Vector3d& p = e.T_w_s.translation();
  std::string row = std::to_string(e.t_ns);
  for (double v : {p.x(), p.y(), p.z(), q.w(), q.x(), q.y(), q.z()}) row += "," + FormatDouble(v);
  for (const Eigen::Vector3d* vec : {&e.w_s, &e.v_w, &e.a_w, &e.gyro, &e.accel}) {
    for (int i = 0; i < 3; ++i) row += "," + FormatDouble((*vec)[i]);
  }
  return row + "\n";
}

}  // namespace

void CheckEvaluateOptions(const SE3Splined& spline, const EvaluateOptions& options) {
  if (options.samples < 2 || options.samples > 100000) {
    throw Error("--samples: expected 2 to 100000, got " + std::to_string(options.samples));
  }
  if (!std::isfinite(options.every_s) || options.every_s < 0.0) {
    throw Error("--every: must be zero or positive, got " + std::to_string(options.every_s));
  }
  const double span_s = NanosecondsToSeconds(spline.end_time_ns() - spline.start_time_ns());
  constexpr double kMaxRows = 1e8;  // refuse before allocating an absurd table
  if (options.every_s > 0.0 && span_s / options.every_s > kMaxRows) {
    throw Error("--every " + FormatDouble(options.every_s) + " s would write more than 1e8 rows");
  }
}

EvaluateRun EvaluateSplineFiles(const SE3Splined& spline,
                                const std::string& spline_path,
                                const EvaluateOptions& options) {
  CheckEvaluateOptions(spline, options);
  const Eigen::Vector3d g_w = GravityWorld(options.gravity_m_s2);
  const Eigen::Vector3d& b_g = options.gyro_bias;
  const Eigen::Vector3d& b_a = options.accel_bias;
  const int64_t start_ns = spline.start_time_ns();
  const int64_t end_ns = spline.end_time_ns();
  EvaluateRun run;
  const std::string header =
      "#t_ns,px,py,pz,qw,qx,qy,qz,wx,wy,wz,vx,vy,vz,ax,ay,az,gyro_x,gyro_y,gyro_z,accel_x,"
      "accel_y,accel_z\n";
  std::string samples_csv = header;
  for (int k = 0; k < options.samples; ++k) {
    const int64_t t_ns =
        start_ns + static_cast<int64_t>(std::llround(static_cast<double>(end_ns - start_ns) * k /
                                                     (options.samples - 1)));
    run.samples.push_back(EvaluateAt(spline, t_ns, g_w, b_g, b_a));
    samples_csv += CsvRow(run.samples.back());
  }
  run.files.push_back({"samples.csv", samples_csv});
  int64_t& rows = run.evaluation_rows;
  if (options.every_s > 0.0) {
    // A step longer than the range gives the first row alone (and keeps llround in range).
    const int64_t span_ns = end_ns - start_ns;
    const int64_t step_ns = options.every_s * 1e9 > static_cast<double>(span_ns)
                                ? span_ns + 1
                                : std::max<int64_t>(1, std::llround(options.every_s * 1e9));
    std::string csv = header;
    for (; rows <= span_ns / step_ns; ++rows) {
      csv += CsvRow(EvaluateAt(spline, start_ns + rows * step_ns, g_w, b_g, b_a));
    }
    run.files.push_back({"evaluation.csv", csv});
  }
  YamlWriter yaml;
  yaml.Scalar("spline", spline_path);
  yaml.Scalar("num_control_poses", spline.num_control_poses());
  yaml.Scalar("trajectory", std::string(TrajectoryModelName(spline.model())));
  yaml.Scalar("knot_spacing_s", spline.dt());
  yaml.Scalar("start_time_ns", start_ns);
  yaml.Scalar("end_time_ns", end_ns);
  yaml.Vector("gravity_w", g_w);
  yaml.Vector("gyro_bias", b_g);
  yaml.Vector("accel_bias", b_a);
  yaml.Scalar("evaluation_rows", rows);
  run.files.push_back({"result.yaml", yaml.str()});
  return run;
}

}  // namespace splinecal

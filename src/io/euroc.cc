#include "splinecal/io/euroc.h"

#include <algorithm>
#include <cmath>

#include "row_checks.h"
#include "splinecal/error.h"
#include "splinecal/imu/imu_rate.h"
#include "splinecal/io/imu_units.h"
#include "splinecal/io/text_file.h"
#include "splinecal/string_printf.h"

namespace splinecal {

std::vector<ImuSample> ReadEurocImu(const std::string& path, const ImuReadOptions& options) {
  static const char* const kNames[] = {"timestamp", "gyro x", "gyro y", "gyro z",
                                       "accel x",   "accel y", "accel z"};
  TextFileReader reader(path);
  reader.set_yaml_hint(options.yaml_hint);
  std::vector<ImuSample> samples;
  internal::TimestampChecker timestamps(&reader);
  internal::ForEachDataRow(&reader, [&](const std::vector<std::string_view>& fields) {
    internal::CheckColumnCount(reader, fields, 7, "EuRoC IMU (t_ns, gyro xyz, accel xyz)");
    ImuSample sample;
    sample.t_ns = ParseTimestampNs(fields[0], reader, kNames[0]);
    for (int i = 0; i < 3; ++i) {
      sample.gyro[i] = options.gyro_scale * ParseBoundedDouble(fields[1 + i], reader, kNames[1 + i],
                                                               kMaxAngularRate, "rad/s");
      sample.accel[i] = options.accel_scale * ParseBoundedDouble(fields[4 + i], reader,
                                                                 kNames[4 + i], kMaxAcceleration,
                                                                 "m/s^2");
    }
    timestamps.Add(sample.t_ns, fields[0]);
    samples.push_back(sample);
  });
  if (samples.size() < 2) {
    throw Error(path, 0, "needs at least 2 IMU samples, found " + std::to_string(samples.size()));
  }
  timestamps.CheckGaps(options.max_gap_periods);
  if (options.check_accel_units) CheckAccelNotInG(samples, path);
  CheckImuRate(ImuRateHz(samples), path);  // after the checks that name a line
  return samples;
}

void CheckAccelNotInG(const std::vector<ImuSample>& samples, const std::string& source) {
  if (samples.empty()) return;
  std::vector<double> norms(samples.size());
  for (size_t i = 0; i < samples.size(); ++i) norms[i] = samples[i].accel.norm();
  std::nth_element(norms.begin(), norms.begin() + norms.size() / 2, norms.end());
  const double median = norms[norms.size() / 2];
  if (median > 0.5 && median < 1.5) {
    throw Error(source,
                0,
                StringPrintf("accelerometer magnitude is about %.2f: the data looks like units "
                             "of g, expected m/s^2 (pass --accel-unit g)",
                             median));
  }
}

void WriteEurocImu(const std::vector<ImuSample>& samples, std::ostream* out) {
  *out << "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
          "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n";
  for (const ImuSample& s : samples) {
    *out << internal::CsvRow(s.t_ns, {s.gyro, s.accel});
  }
}

std::vector<GroundTruthState> ReadEurocGroundTruth(const std::string& path) {
  static const char* const kNames[] = {
      "timestamp", "p x", "p y", "p z", "q w", "q x", "q y", "q z", "v x",
      "v y", "v z", "gyro bias x", "gyro bias y", "gyro bias z", "accel bias x",
      "accel bias y", "accel bias z"};
  TextFileReader reader(path);
  std::vector<GroundTruthState> states;
  internal::TimestampChecker timestamps(&reader);
  internal::ForEachDataRow(&reader, [&](const std::vector<std::string_view>& fields) {
    internal::CheckColumnCount(reader, fields, 17,
                               "EuRoC ground truth (t_ns, p xyz, q wxyz, v xyz, bg xyz, ba xyz)");
    double v[17];
    GroundTruthState state;
    state.t_ns = ParseTimestampNs(fields[0], reader, kNames[0]);
    for (int i = 1; i < 17; ++i) {
      // Positions, quaternion (checked for unit norm below), velocities, biases.
      const double limit = i < 4 ? kMaxPosition : i < 8 ? 2.0 : i < 11 ? kMaxVelocity
                                                        : i < 14 ? kMaxAngularRate : kMaxAcceleration;
      const char* unit = i < 4 ? "m" : i < 8 ? "" : i < 11 ? "m/s" : i < 14 ? "rad/s" : "m/s^2";
      v[i] = ParseBoundedDouble(fields[i], reader, kNames[i], limit, unit);
    }
    state.p_w_s = Eigen::Vector3d(v[1], v[2], v[3]);
    state.q_w_s = internal::CheckedUnitQuaternion(reader, fields[4], v[4], v[5], v[6], v[7]);
    state.v_w = Eigen::Vector3d(v[8], v[9], v[10]);
    state.gyro_bias = Eigen::Vector3d(v[11], v[12], v[13]);
    state.accel_bias = Eigen::Vector3d(v[14], v[15], v[16]);
    timestamps.Add(state.t_ns, fields[0]);
    states.push_back(state);
  });
  if (states.size() < 2) {
    throw Error(path, 0, "needs at least 2 ground-truth rows, found " + std::to_string(states.size()));
  }
  return states;
}

void WriteEurocGroundTruth(const std::vector<GroundTruthState>& states, std::ostream* out) {
  *out << "#timestamp [ns],p_RS_R_x [m],p_RS_R_y [m],p_RS_R_z [m],q_RS_w [],q_RS_x [],q_RS_y [],"
          "q_RS_z [],v_RS_R_x [m s^-1],v_RS_R_y [m s^-1],v_RS_R_z [m s^-1],"
          "b_w_RS_S_x [rad s^-1],b_w_RS_S_y [rad s^-1],b_w_RS_S_z [rad s^-1],"
          "b_a_RS_S_x [m s^-2],b_a_RS_S_y [m s^-2],b_a_RS_S_z [m s^-2]\n";
  for (const GroundTruthState& s : states) {
    const Eigen::Vector4d q_wxyz(s.q_w_s.w(), s.q_w_s.x(), s.q_w_s.y(), s.q_w_s.z());
    *out << internal::CsvRow(s.t_ns, {s.p_w_s, q_wxyz, s.v_w, s.gyro_bias, s.accel_bias});
  }
}

}  // namespace splinecal

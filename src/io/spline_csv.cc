#include "splinecal/io/spline_csv.h"

#include <cstdlib>
#include <string>
#include <string_view>

#include "row_checks.h"
#include "splinecal/error.h"
#include "splinecal/io/text_file.h"
#include "splinecal/spline/trajectory_model.h"

namespace splinecal {

namespace {

constexpr std::string_view kTrajectoryKey = "trajectory:";

// True for a "# trajectory: <model>" comment line (spaces around both parts allowed); *value is
// then <model>.
bool IsTrajectoryComment(std::string_view comment, std::string_view* value) {
  comment = TrimLine(comment.substr(1));  // without the '#'
  if (comment.substr(0, kTrajectoryKey.size()) != kTrajectoryKey) return false;
  *value = TrimLine(comment.substr(kTrajectoryKey.size()));
  return true;
}

}  // namespace

SE3Splined ReadSplineCsv(const std::string& path) {
  static const char* const kNames[] = {"t_ns", "px", "py", "pz", "qw", "qx", "qy", "qz"};
  // A spacing written from a non-integer number of nanoseconds may round by one.
  constexpr int64_t kSpacingToleranceNs = 1;
  TextFileReader reader(path);
  // Files without the key (written before it existed) are the coupled SE(3) spline.
  TrajectoryModel model = TrajectoryModel::kSE3;
  bool model_given = false;
  reader.set_comment_visitor([&](std::string_view comment) {
    std::string_view value;
    if (!IsTrajectoryComment(comment, &value)) return;
    if (model_given) reader.Fail("the trajectory model is given twice");
    if (!ParseTrajectoryModel(value, &model)) {
      reader.Fail("trajectory: expected se3 or split, got '" + std::string(value) + "'");
    }
    model_given = true;
  });
  std::vector<std::string_view> fields;
  std::vector<SE3d> poses;
  int64_t t0_ns = 0;
  int64_t previous_ns = 0;
  int64_t dt_ns = 0;
  int64_t grid_offset_ns = 0;  // t_ns - (t0 + i*dt) of the last row
  while (reader.NextLine()) {
    SplitFields(reader.line(), &fields);
    if (internal::IsHeaderRow(reader, fields)) continue;
    internal::CheckColumnCount(reader, fields, 8, "spline.csv: t_ns,px,py,pz,qw,qx,qy,qz");
    const int64_t t_ns = ParseTimestampNs(fields[0], reader, kNames[0]);
    double v[8];
    for (int i = 1; i < 8; ++i) {
      v[i] = ParseBoundedDouble(fields[i], reader, kNames[i], i < 4 ? kMaxPosition : 2.0,
                                i < 4 ? "m" : "(quaternion)");
    }
    const Eigen::Quaterniond q =
        internal::CheckedUnitQuaternion(reader, fields[4], v[4], v[5], v[6], v[7]);
    if (poses.empty()) {
      t0_ns = t_ns;
    } else if (poses.size() == 1) {
      dt_ns = t_ns - previous_ns;
      if (dt_ns <= 0) reader.Fail("knot times must increase", fields[0]);
    } else {
      // The offset from the grid t0 + i*dt, updated step by step: t0 + i*dt itself may lie
      // beyond int64 when a row breaks off the grid, differences of two stamps never do.
      const int64_t step_ns = t_ns - previous_ns;
      if (step_ns > 0) grid_offset_ns += step_ns - dt_ns;
      if (step_ns <= 0 || std::llabs(grid_offset_ns) > kSpacingToleranceNs) {
        reader.Fail("knot spacing is not uniform: " + std::to_string(step_ns) +
                        " ns after the previous knot, expected t0 + i*dt with dt = " +
                        std::to_string(dt_ns) + " ns",
                    fields[0]);
      }
    }
    previous_ns = t_ns;
    poses.emplace_back(SO3d(q), Eigen::Vector3d(v[1], v[2], v[3]));
  }
  if (poses.size() < 4) {
    throw Error(path, 0, "a spline needs at least 4 control poses, found " +
                             std::to_string(poses.size()));
  }
  return SE3Splined(std::move(poses), t0_ns, dt_ns, model);
}

void WriteSplineCsv(const SE3Splined& spline, std::ostream* out) {
  *out << "# trajectory: " << TrajectoryModelName(spline.model()) << "\n";
  *out << "#t_ns,px,py,pz,qw,qx,qy,qz\n";
  for (int i = 0; i < spline.num_control_poses(); ++i) {
    const SE3d& T = spline.control_pose(i);
    const Eigen::Quaterniond& q = T.so3().quaternion();
    const Eigen::Vector3d& p = T.translation();
    const Eigen::Vector4d q_wxyz(q.w(), q.x(), q.y(), q.z());
    *out << internal::CsvRow(spline.knot_time_ns(i), {p, q_wxyz});
  }
}

}  // namespace splinecal

#include "splinecal/io/poses.h"

#include <cinttypes>

#include "row_checks.h"
#include "splinecal/error.h"
#include "splinecal/io/text_file.h"
#include "splinecal/string_printf.h"

namespace splinecal {
namespace {

enum class PoseFormat { kTum, kEurocGroundTruth };

StampedPose ParseRow(const TextFileReader& reader,
                     const std::vector<std::string_view>& fields,
                     PoseFormat format) {
  static const char* const kTumNames[] = {"time", "tx", "ty", "tz", "qx", "qy", "qz", "qw"};
  static const char* const kEurocNames[] = {"timestamp", "p x", "p y", "p z",
                                            "q w",       "q x", "q y", "q z"};
  const bool tum = format == PoseFormat::kTum;
  const char* const* names = tum ? kTumNames : kEurocNames;
  StampedPose pose;
  if (tum) {
    internal::CheckColumnCount(reader, fields, 8, "TUM: t_s tx ty tz qx qy qz qw");
    pose.t_ns = ParseSecondsToNs(fields[0], reader, names[0]);
  } else {
    if (fields.size() < 8) {
      reader.Fail("expected at least 8 columns (EuRoC ground truth: t_ns, p xyz, q wxyz, ...), "
                  "found " + std::to_string(fields.size()));
    }
    pose.t_ns = ParseTimestampNs(fields[0], reader, names[0]);
  }
  // Both: the position, then the quaternion in the file's order (TUM x y z w, EuRoC w x y z).
  double v[8];
  for (int i = 1; i < 8; ++i) {
    v[i] = ParseBoundedDouble(fields[i], reader, names[i], i < 4 ? kMaxPosition : 2.0,
                              i < 4 ? "m" : "(quaternion)");
  }
  pose.p = Eigen::Vector3d(v[1], v[2], v[3]);
  pose.q = tum ? internal::CheckedUnitQuaternion(reader, fields[4], v[7], v[4], v[5], v[6])
               : internal::CheckedUnitQuaternion(reader, fields[4], v[4], v[5], v[6], v[7]);
  return pose;
}

std::vector<StampedPose> Read(const std::string& path, const PoseFormat* forced_format) {
  TextFileReader reader(path);
  std::vector<StampedPose> poses;
  internal::TimestampChecker timestamps(&reader);
  bool have_format = forced_format != nullptr;
  PoseFormat format = have_format ? *forced_format : PoseFormat::kTum;
  // EuRoC ground truth may carry 8 columns (t, p, q) or more (v, biases); every row as the first.
  size_t first_row_columns = 0;
  internal::ForEachDataRow(&reader, [&](const std::vector<std::string_view>& fields) {
    if (!have_format) {
      format = reader.line().find(',') != std::string_view::npos ? PoseFormat::kEurocGroundTruth
                                                                  : PoseFormat::kTum;
      have_format = true;
    }
    if (!poses.empty() && fields.size() != first_row_columns) {
      reader.Fail("expected " + std::to_string(first_row_columns) +
                  " columns like the first row, found " + std::to_string(fields.size()));
    }
    const StampedPose pose = ParseRow(reader, fields, format);
    if (poses.empty()) first_row_columns = fields.size();
    timestamps.Add(pose.t_ns, fields[0]);
    poses.push_back(pose);
  });
  if (poses.size() < 2) {
    throw Error(path, 0, "needs at least 2 poses, found " + std::to_string(poses.size()));
  }
  return poses;
}

}  // namespace

std::vector<StampedPose> ReadTumTrajectory(const std::string& path) {
  const PoseFormat format = PoseFormat::kTum;
  return Read(path, &format);
}

std::vector<StampedPose> ReadPoses(const std::string& path) { return Read(path, nullptr); }

void WriteTumTrajectory(const std::vector<StampedPose>& poses, std::ostream* out) {
  *out << "# t_s tx ty tz qx qy qz qw\n";
  for (const StampedPose& pose : poses) {
    // Seconds printed from the integer nanoseconds, digit-exact.
    const int64_t t = pose.t_ns;
    const char* sign = t < 0 ? "-" : "";
    const int64_t magnitude = t < 0 ? -t : t;
    *out << StringPrintf("%s%" PRId64 ".%09" PRId64 " %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n",
                         sign,
                         magnitude / 1'000'000'000,
                         magnitude % 1'000'000'000,
                         pose.p.x(),
                         pose.p.y(),
                         pose.p.z(),
                         pose.q.x(),
                         pose.q.y(),
                         pose.q.z(),
                         pose.q.w());
  }
}

}  // namespace splinecal

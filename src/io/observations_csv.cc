#include "splinecal/io/observations_csv.h"

#include <algorithm>
#include <numeric>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include "row_checks.h"
#include "splinecal/error.h"
#include "splinecal/io/text_file.h"
#include "splinecal/string_printf.h"

namespace splinecal {

namespace {

// Pixels beyond this magnitude [px] are refused: no sensor is that large, so the column holds
// something else (a timestamp, a corrupt number).
constexpr double kMaxPixel = 1e6;
// Camera indices above this are refused as implausible (camN keys of a camchain).
constexpr int64_t kMaxCameraId = 1000;

}  // namespace

std::vector<Observation> ReadObservationsCsv(const std::string& path) {
  TextFileReader reader(path);
  std::vector<std::string_view> fields;
  std::vector<Observation> observations;
  std::vector<int64_t> lines;
  while (reader.NextLine()) {
    SplitFields(reader.line(), &fields);
    if (reader.data_lines() == 1 && internal::IsHeaderRow(reader, fields)) continue;
    internal::CheckColumnCount(reader, fields, 5, "t_ns,cam_id,point_id,u,v");
    Observation o;
    o.t_ns = ParseTimestampNs(fields[0], reader, "t_ns");
    const int64_t cam = ParseInt64(fields[1], reader, "cam_id");
    if (cam < 0 || cam > kMaxCameraId) {
      reader.Fail("cam_id must be an integer in [0, " + std::to_string(kMaxCameraId) + "]",
                  fields[1]);
    }
    o.cam_id = static_cast<int>(cam);
    o.point_id = ParseInt64(fields[2], reader, "point_id");
    if (o.point_id < 0) reader.Fail("point_id must be >= 0", fields[2]);
    o.uv.x() = ParseBoundedDouble(fields[3], reader, "u", kMaxPixel, "px");
    o.uv.y() = ParseBoundedDouble(fields[4], reader, "v", kMaxPixel, "px");
    observations.push_back(o);
    lines.push_back(reader.line_number());
  }
  if (observations.empty())
    throw Error(path, 0, "no observations (expected t_ns,cam_id,point_id,u,v rows)");
  // Sort by (t, cam, point), keeping line numbers, then refuse duplicates naming both lines.
  std::vector<size_t> order(observations.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    const Observation& x = observations[a];
    const Observation& y = observations[b];
    return std::tie(x.t_ns, x.cam_id, x.point_id) < std::tie(y.t_ns, y.cam_id, y.point_id);
  });
  std::vector<Observation> sorted;
  sorted.reserve(observations.size());
  for (size_t k = 0; k < order.size(); ++k) {
    const Observation& o = observations[order[k]];
    if (k > 0) {
      const Observation& prev = observations[order[k - 1]];
      if (prev.t_ns == o.t_ns && prev.cam_id == o.cam_id && prev.point_id == o.point_id) {
        const int64_t first = std::min(lines[order[k - 1]], lines[order[k]]);
        const int64_t second = std::max(lines[order[k - 1]], lines[order[k]]);
        throw Error(path,
                    second,
                    "point " + std::to_string(o.point_id) + " of camera " +
                        std::to_string(o.cam_id) + " appears twice in frame " +
                        std::to_string(o.t_ns) + " (also on line " + std::to_string(first) + ")");
      }
    }
    sorted.push_back(o);
  }
  return sorted;
}

void WriteObservationsCsv(const std::vector<Observation>& observations, std::ostream* out) {
  *out << "#t_ns,cam_id,point_id,u,v\n";
  for (const Observation& o : observations) {
    *out << o.t_ns << ',' << o.cam_id << ',' << o.point_id << ',' << FormatDouble(o.uv.x()) << ','
         << FormatDouble(o.uv.y()) << '\n';
  }
}

}  // namespace splinecal

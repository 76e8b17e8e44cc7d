// observations.csv: one detected point per row (camera/observations.h), read with the one input
// layer (io/text_file.h: CRLF, blank lines, '#' comments, spaces after commas):
//
//   #t_ns,cam_id,point_id,u,v
//   1403715273262142976,0,17,412.25,233.5
//
// t_ns: frame timestamp, camera clock [ns] (int64, never through a double); cam_id: camN index
// (>= 0); point_id: target corner or landmark id (int64 >= 0); u, v: pixel [px].
#ifndef SPLINECAL_IO_OBSERVATIONS_CSV_H_
#define SPLINECAL_IO_OBSERVATIONS_CSV_H_

#include <ostream>
#include <string>
#include <vector>

#include "splinecal/camera/observations.h"

namespace splinecal {

// Reads observations.csv; the result is sorted by (t_ns, cam_id, point_id). Throws
// splinecal::Error (file:line:column) for a wrong column count, a non-integer time, camera or
// point id, a negative id, a non-finite or implausible pixel (|u|, |v| > 1e6), the same point
// twice in one frame (naming both lines), and for a file without any observation.
std::vector<Observation> ReadObservationsCsv(const std::string& path);

// Writes the header and one row per observation (pixels with 17 significant digits).
void WriteObservationsCsv(const std::vector<Observation>& observations, std::ostream* out);

}  // namespace splinecal

#endif  // SPLINECAL_IO_OBSERVATIONS_CSV_H_

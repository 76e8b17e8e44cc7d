// spline.csv: the control poses of a spline, one per row (docs/conventions.md, "File formats").
//
//   # trajectory: se3
//   #t_ns,px,py,pz,qw,qx,qy,qz
//   row i = control pose T_i (T_w_s) at knot time t_i = t0 + i*dt, uniform spacing.
//
// The file alone reproduces the spline: t0 is the first row's time, dt the spacing, and the
// comment line "# trajectory: se3|split" the model that interpolates the control poses
// (spline/trajectory_model.h). A file without that line (written before it existed) is se3.
#ifndef SPLINECAL_IO_SPLINE_CSV_H_
#define SPLINECAL_IO_SPLINE_CSV_H_

#include <ostream>
#include <string>

#include "splinecal/spline/se3_spline.h"

namespace splinecal {

// Reads a spline.csv. Throws Error (file:line) on fewer than 4 rows, a spacing that is not
// uniform (to 1 ns) or not positive, non-unit quaternions, a trajectory model other than se3 or
// split (or given twice) and the reader's usual problems.
SE3Splined ReadSplineCsv(const std::string& path);

// Writes the trajectory model and the control poses with 17 significant digits (they read back
// bit-exactly).
void WriteSplineCsv(const SE3Splined& spline, std::ostream* out);

}  // namespace splinecal

#endif  // SPLINECAL_IO_SPLINE_CSV_H_

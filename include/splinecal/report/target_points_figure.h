// The free target's figure in `splinecal intrinsics`' report.html (intrinsics/target_deformation.h,
// kind "points"): where the data put each target point against the file's layout.
//
//   left   the target's plane [m]: every point of the file, and each free point's offset in the
//          plane as an arrow magnified by a round factor (in the title), so that the longest is
//          about a twentieth of the target's width. A print scaled unevenly shows as a smooth
//          field; a detector bias tied to the tags as a pattern repeated tag by tag.
//   right  each free point's offset along the target's normal [mm] against its x [m], with its
//          std as an error bar.
// The report shows it for a run with every point free, and for a run with the file's layout
// whose test of the points warns (their one-step displacements instead).
#ifndef SPLINECAL_REPORT_TARGET_POINTS_FIGURE_H_
#define SPLINECAL_REPORT_TARGET_POINTS_FIGURE_H_

#include "splinecal/intrinsics/calibrate_intrinsics.h"
#include "splinecal/plot/svg_plot.h"

namespace splinecal {

// d: a result with every point free (d.shape.per_point()); its refined target and offsets.
plot::Figure TargetPointsFigure(const TargetDeformationResult& d);

// The same figure from the test of the file's layout (intrinsics/target_points_check.h): each
// tested point's one-step displacement delta_p and its std, the poses and intrinsics held.
plot::Figure TargetPointsFigure(const TargetPointsCheck& check);

}  // namespace splinecal

#endif  // SPLINECAL_REPORT_TARGET_POINTS_FIGURE_H_

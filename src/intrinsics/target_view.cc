#include "splinecal/intrinsics/target_view.h"

namespace splinecal {

std::vector<TargetView> MakeTargetViews(const std::vector<Observation>& observations,
                                        const CalibrationTarget& target,
                                        int64_t* unknown_ids) {
  *unknown_ids = 0;
  std::vector<TargetView> views;
  for (const ObservationFrame& frame : GroupIntoFrames(observations)) {
    TargetView view;
    view.t_ns = frame.t_ns;
    view.cam_id = frame.cam_id;
    for (const Observation& o : frame.observations) {
      const Eigen::Vector3d* p_t = target.Find(o.point_id);
      if (p_t == nullptr) {
        ++*unknown_ids;
        continue;
      }
      view.point_ids.push_back(o.point_id);
      view.corners.push_back({*p_t, o.uv});
    }
    views.push_back(std::move(view));
  }
  return views;
}

}  // namespace splinecal

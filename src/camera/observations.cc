#include "splinecal/camera/observations.h"

#include <algorithm>
#include <tuple>
#include <utility>

namespace splinecal {

void SortObservations(std::vector<Observation>* observations) {
  std::stable_sort(
      observations->begin(), observations->end(), [](const Observation& a, const Observation& b) {
        return std::tie(a.t_ns, a.cam_id, a.point_id) < std::tie(b.t_ns, b.cam_id, b.point_id);
      });
}

std::vector<ObservationFrame> GroupIntoFrames(std::vector<Observation> observations) {
  SortObservations(&observations);
  std::vector<ObservationFrame> frames;
  for (Observation& o : observations) {
    if (frames.empty() || frames.back().t_ns != o.t_ns || frames.back().cam_id != o.cam_id) {
      ObservationFrame& frame = frames.emplace_back();
      frame.t_ns = o.t_ns;
      frame.cam_id = o.cam_id;
    }
    frames.back().observations.push_back(std::move(o));
  }
  return frames;
}

}  // namespace splinecal

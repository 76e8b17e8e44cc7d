// Camera observations: one detected point per row of observations.csv
// (`#t_ns,cam_id,point_id,u,v`, io/observations_csv.h): the frame's timestamp in the CAMERA clock
// [ns] (row 0's exposure time for a rolling shutter, docs/conventions.md "Time"), the camera index
// (camN of the camchain), the point id (a target corner id, camera/target.h, or a natural
// landmark's id) and the pixel (u right, v down, pixel centres at integers).
#ifndef SPLINECAL_CAMERA_OBSERVATIONS_H_
#define SPLINECAL_CAMERA_OBSERVATIONS_H_

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace splinecal {

struct Observation {
  int64_t t_ns = 0;  // frame timestamp, camera clock [ns]
  int cam_id = 0;
  int64_t point_id = 0;
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();  // [px]
};

// The observations of one image: same camera, same timestamp.
struct ObservationFrame {
  int64_t t_ns = 0;
  int cam_id = 0;
  std::vector<Observation> observations;
};

// Groups observations into frames, ordered by (t_ns, cam_id); within a frame by point_id.
std::vector<ObservationFrame> GroupIntoFrames(std::vector<Observation> observations);

// Orders by (t_ns, cam_id, point_id): the order of observations.csv.
void SortObservations(std::vector<Observation>* observations);

}  // namespace splinecal

#endif  // SPLINECAL_CAMERA_OBSERVATIONS_H_

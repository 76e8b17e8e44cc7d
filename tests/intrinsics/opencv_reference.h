// OpenCV's single-camera calibration as the outside reference of the exact least-squares tests
// (intrinsics_exact_least_squares_slow_test.cc, intrinsics_opencv_chessboard_test.cc):
// cv::calibrateCamera (pinhole-radtan, k3 fixed: CALIB_FIX_K3, steps solved by LU:
// CALIB_USE_LU) or cv::fisheye::calibrate (pinhole-equi, CALIB_FIX_SKEW), both run to
// TermCriteria(COUNT + EPS, 1000, 1e-15), on the corners of some frames of one camera, and the
// sum of squared pixel errors of either solution evaluated the same way: in double, on the same
// corners.
#ifndef SPLINECAL_TESTS_INTRINSICS_OPENCV_REFERENCE_H_
#define SPLINECAL_TESTS_INTRINSICS_OPENCV_REFERENCE_H_

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <map>
#include <opencv2/calib3d.hpp>
#include <vector>

#include "splinecal/camera/camera_model.h"
#include "splinecal/camera/observations.h"
#include "splinecal/camera/reprojection_sample.h"
#include "splinecal/camera/target.h"

namespace splinecal {
namespace testing {

// Rounds every pixel to float. OpenCV's calibrateCamera converts its inputs to float
// (collectCalibrationData); giving both solvers the same rounded corners makes their sums of
// squares comparable to the last digit.
inline std::vector<Observation> RoundedToFloat(std::vector<Observation> observations) {
  for (Observation& o : observations) {
    o.uv = Eigen::Vector2d(static_cast<float>(o.uv.x()), static_cast<float>(o.uv.y()));
  }
  return observations;
}

// Every `step`-th frame (in time) of camera cam_id, renumbered as camera 0.
inline std::vector<Observation> EveryNthFrame(const std::vector<Observation>& observations,
                                              int cam_id,
                                              int step) {
  std::map<int64_t, int> frame_index;
  for (const Observation& o : observations) {
    if (o.cam_id == cam_id) frame_index.emplace(o.t_ns, 0);
  }
  int index = 0;
  for (auto& [t, i] : frame_index) i = index++;
  std::vector<Observation> kept;
  for (const Observation& o : observations) {
    if (o.cam_id != cam_id || frame_index.at(o.t_ns) % step != 0) continue;
    kept.push_back(o);
    kept.back().cam_id = 0;
  }
  return kept;
}

struct OpenCvCalibration {
  Camera camera;
  double sum_sq_px2 = 0.0;  // over every corner, projectPoints in double
  int corners = 0;
  int views = 0;
};

// OpenCV's calibration of camera 0 of `observations` with `distortion` (kRadTan or
// kEquidistant): frames with at least min_corners corners, every corner of them.
inline OpenCvCalibration CalibrateWithOpenCv(const std::vector<Observation>& observations,
                                             const CalibrationTarget& target,
                                             DistortionModel distortion,
                                             int width,
                                             int height,
                                             int min_corners) {
  std::map<int64_t, std::pair<std::vector<cv::Point3d>, std::vector<cv::Point2d>>> frames;
  for (const Observation& o : observations) {
    if (o.cam_id != 0 || target.Find(o.point_id) == nullptr) continue;
    const Eigen::Vector3d& p = *target.Find(o.point_id);
    frames[o.t_ns].first.emplace_back(p.x(), p.y(), p.z());
    frames[o.t_ns].second.emplace_back(o.uv.x(), o.uv.y());
  }
  std::vector<std::vector<cv::Point3d>> object_points;
  std::vector<std::vector<cv::Point2d>> image_points;
  std::vector<std::vector<cv::Point3f>> object_points_f;
  std::vector<std::vector<cv::Point2f>> image_points_f;
  for (const auto& [t, frame] : frames) {
    if (static_cast<int>(frame.first.size()) < min_corners) continue;
    object_points.push_back(frame.first);
    image_points.push_back(frame.second);
    object_points_f.emplace_back(frame.first.begin(), frame.first.end());
    image_points_f.emplace_back(frame.second.begin(), frame.second.end());
  }
  const cv::TermCriteria criteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 1000, 1e-15);
  cv::Mat K, d;
  std::vector<cv::Mat> rvecs, tvecs;
  OpenCvCalibration out;
  out.camera.distortion = distortion;
  out.camera.width = width;
  out.camera.height = height;
  if (distortion == DistortionModel::kEquidistant) {
    cv::fisheye::calibrate(object_points,
                           image_points,
                           cv::Size(width, height),
                           K,
                           d,
                           rvecs,
                           tvecs,
                           cv::fisheye::CALIB_RECOMPUTE_EXTRINSIC | cv::fisheye::CALIB_FIX_SKEW,
                           criteria);
  } else {
    cv::calibrateCamera(object_points_f,
                        image_points_f,
                        cv::Size(width, height),
                        K,
                        d,
                        rvecs,
                        tvecs,
                        // LU in place of OpenCV's default SVD for each Levenberg-Marquardt
                        // step: the damped normal equations (about 1,070 unknowns on 177 views)
                        // are positive definite, so LU solves them exactly as SVD does; only the
                        // factorisation's cost changes (SVD was 85% of the test's CPU,
                        // docs/reliability.md, "test time before / after").
                        cv::CALIB_FIX_K3 | cv::CALIB_USE_LU,
                        criteria);
  }
  IntrinsicsVector x = IntrinsicsVector::Zero();
  x(0) = K.at<double>(0, 0);
  x(1) = K.at<double>(1, 1);
  x(2) = K.at<double>(0, 2);
  x(3) = K.at<double>(1, 2);
  const int num_coeffs = distortion == DistortionModel::kEquidistant ? 4 : 5;
  for (int j = 0; j < num_coeffs; ++j) x(kDistortionCoeffsIndex + j) = d.at<double>(j);
  out.camera.set_intrinsics(x);
  for (size_t v = 0; v < object_points.size(); ++v) {
    std::vector<cv::Point2d> projected;
    if (distortion == DistortionModel::kEquidistant) {
      cv::fisheye::projectPoints(object_points[v], projected, rvecs[v], tvecs[v], K, d);
    } else {
      cv::projectPoints(object_points[v], rvecs[v], tvecs[v], K, d, projected);
    }
    for (size_t i = 0; i < projected.size(); ++i) {
      const cv::Point2d e = projected[i] - image_points[v][i];
      out.sum_sq_px2 += e.dot(e);
    }
    out.corners += static_cast<int>(projected.size());
  }
  out.views = static_cast<int>(object_points.size());
  return out;
}

inline double SumOfSquares(const std::vector<ReprojectionSample>& residuals) {
  double sum = 0.0;
  for (const ReprojectionSample& s : residuals) sum += s.error.squaredNorm();
  return sum;
}

// The largest distance [px] between the pixels two cameras of the same model give to the same
// ray, over a grid of rays through the image (every 8th pixel of camera a): the difference of
// two calibrations in pixels, whatever parameters trade against each other.
inline double LargestPixelDifference(const Camera& a, const Camera& b) {
  double largest = 0.0;
  for (int v = 0; v < a.height; v += 8) {
    for (int u = 0; u < a.width; u += 8) {
      Eigen::Vector3d ray;
      Eigen::Vector2d uv_b;
      if (!a.Unproject(Eigen::Vector2d(u, v), &ray) || !b.Project(ray, &uv_b)) continue;
      largest = std::max(largest, (uv_b - Eigen::Vector2d(u, v)).norm());
    }
  }
  return largest;
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_INTRINSICS_OPENCV_REFERENCE_H_

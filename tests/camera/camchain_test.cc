#include "splinecal/camera/camchain.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "splinecal/error.h"

namespace splinecal {
namespace {

std::vector<Observation> Observations(const std::vector<int>& cam_ids) {
  std::vector<Observation> observations;
  for (size_t k = 0; k < cam_ids.size(); ++k) {
    Observation o;
    o.t_ns = 1'000 + static_cast<int64_t>(k);
    o.cam_id = cam_ids[k];
    observations.push_back(o);
  }
  return observations;
}

TEST(FindObservationWithoutCamera, FirstUnknownOrNegativeCamera) {
  const Camchain two(2);
  const std::vector<Observation> fine = Observations({0, 1, 1, 0});
  EXPECT_EQ(FindObservationWithoutCamera(fine, two), nullptr);
  const std::vector<Observation> beyond = Observations({0, 2, 3});
  EXPECT_EQ(FindObservationWithoutCamera(beyond, two), &beyond[1]);
  const std::vector<Observation> negative = Observations({1, -1});
  EXPECT_EQ(FindObservationWithoutCamera(negative, two), &negative[1]);
  EXPECT_EQ(FindObservationWithoutCamera({}, Camchain()), nullptr);
}

TEST(CheckCameraIds, AcceptsEveryKnownCamera) {
  EXPECT_NO_THROW(CheckCameraIds(Observations({0, 1}), Camchain(2), "obs.csv", "camchain.yaml"));
}

TEST(CheckCameraIds, OneLineNamingBothFilesTheCameraAndTheFrame) {
  try {
    CheckCameraIds(Observations({0, 0, 1}), Camchain(1), "obs.csv", "camchain.yaml");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.path(), "obs.csv");
    EXPECT_EQ(e.message(),
              "cam_id 1 (frame t_ns 1002) has no camera in camchain.yaml, which describes 1 "
              "camera(s): wrong camchain or cam_id column");
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
  }
}

}  // namespace
}  // namespace splinecal

#include "splinecal/detect/detect_folders.h"

#include <utility>

#include "detect_frames.h"
#include "splinecal/detect/image_file.h"
#include "splinecal/error.h"

namespace splinecal {
namespace {

// The frames of the folders, camera by camera, each decoded from its file by the worker.
class FolderFrames : public internal::FrameSource {
 public:
  explicit FolderFrames(const std::vector<ImageFolder>& folders) : folders_(folders) {}

  bool Take(internal::FrameJob* job) override {
    while (cam_ < folders_.size() && index_ >= folders_[cam_].frames.size()) {
      ++cam_;
      index_ = 0;
    }
    if (cam_ >= folders_.size()) return false;
    job->cam = static_cast<int>(cam_);
    job->index = static_cast<int64_t>(index_);
    job->frame = folders_[cam_].frames[index_++];
    return true;
  }

  GrayImage Decode(const internal::FrameJob& job) const override {
    return ReadGrayImage(job.frame.path);
  }

 private:
  const std::vector<ImageFolder>& folders_;
  size_t cam_ = 0;
  size_t index_ = 0;
};

// The sizes of the folder's first readable frames (at most 5), found before the workers start so
// that each frame is checked as soon as it is decoded and no overlay is drawn for a frame then
// dropped.
std::vector<std::pair<int, int>> FirstSizes(const ImageFolder& folder) {
  std::vector<std::pair<int, int>> sizes;
  for (size_t i = 0; i < folder.frames.size() && sizes.size() < 5; ++i) {
    try {
      const GrayImage image = ReadGrayImage(folder.frames[i].path);
      sizes.emplace_back(image.width, image.height);
    } catch (const Error&) {
      // The workers read it again and report the problem with the frame.
    }
  }
  return sizes;
}

}  // namespace

DetectFoldersResult DetectFolders(const std::vector<ImageFolder>& folders,
                                  const CalibrationTarget& target,
                                  const DetectFoldersOptions& options) {
  std::vector<CameraDetectionSummary> cameras;
  std::vector<std::string> warnings;
  for (size_t cam = 0; cam < folders.size(); ++cam) {
    CameraDetectionSummary summary;
    summary.cam_id = static_cast<int>(cam);
    summary.dir = folders[cam].dir;
    summary.images_listed = static_cast<int64_t>(folders[cam].frames.size());
    internal::ChooseResolution(FirstSizes(folders[cam]), &summary);
    cameras.push_back(summary);
    for (const std::string& warning : folders[cam].warnings) warnings.push_back(warning);
  }
  FolderFrames frames(folders);
  return internal::DetectFrames(&frames, std::move(cameras), std::move(warnings), target,
                                options);
}

}  // namespace splinecal

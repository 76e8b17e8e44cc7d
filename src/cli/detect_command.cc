// `splinecal detect`: AprilGrid or checkerboard corners in camera image folders, written as the
// observations.csv that `calibrate` reads (detect/detect_folders.h, docs/detect.md).
#include <gflags/gflags.h>
#include <unistd.h>

#include <cstdio>
#include <string>
#include <vector>

#include "splinecal/cli/command.h"
#include "splinecal/cli/commands.h"
#include "splinecal/cli/common_flags.h"
#include "splinecal/detect/detect_bag.h"
#include "splinecal/detect/detect_folders.h"
#include "splinecal/report/detect_report.h"
#include "splinecal/error.h"
#include "splinecal/io/bag_messages.h"
#include "splinecal/io/image_folder.h"
#include "splinecal/io/output_dir.h"
#include "splinecal/io/target_yaml.h"
#include "splinecal/string_printf.h"

DEFINE_string(images,
              "",
              "Image folders, comma separated; the i-th is camera i: an EuRoC/ASL camera folder "
              "(data.csv and data/) or a folder of <t_ns>.png / <t_ns>.jpg [paths]");
DEFINE_string(effort,
              "default",
              "aprilgrid: how hard to look for tags, recall against time: default (when tags "
              "of the grid in view are missing, the tags their found neighbours predict, kept "
              "when their code reads right, and searches of the frame upsampled 2x: 98% of the "
              "corners of 15-20 px tags, 100% from 20 px in docs/detect.md's test), thorough "
              "(the upsampled searches in every frame), fast (the first search only: 14% of "
              "15-20 px tags, 78% of 20-25 px ones)");
DEFINE_string(image_topics,
              "",
              "With --bag: the image topics (sensor_msgs/Image or CompressedImage), comma "
              "separated; the i-th is camera i");
DEFINE_bool(draw, false, "Also write one overlay PNG per frame with corners under overlays/camN/");

namespace splinecal {
namespace cli {
namespace {

struct DetectInputs {
  std::vector<ImageFolder> folders;  // --images
  BagImageSource bag;                // --bag: paths, topics, clock
  CalibrationTarget target;
  int threads = 1;
  DetectEffort effort = DetectEffort::kDefault;
};

DetectInputs ReadDetectInputs() {
  if (FLAGS_images.empty() == FLAGS_bag.empty()) {
    throw Error("give the frames as --images DIR[,DIR...] or as --bag FILE --image-topics "
                "T0[,T1...]: exactly one");
  }
  if (FLAGS_bag.empty() && !FLAGS_image_topics.empty()) {
    throw Error("--image-topics names the topics of --bag; --images takes folders");
  }
  RequiredFlag("target", FLAGS_target);
  RequiredFlag("out", FLAGS_out);
  DetectInputs in;
  in.threads = ThreadsFlag();
  try {
    in.effort = ParseDetectEffort(FLAGS_effort);
  } catch (const Error& e) {
    throw Error(std::string("--effort: ") + e.what());
  }
  in.target = ReadTargetYaml(FLAGS_target);
  if (in.target.type != "aprilgrid" && in.target.type != "checkerboard") {
    throw Error(FLAGS_target, 0,
                "detect finds aprilgrid and checkerboard targets, not '" + in.target.type + "'");
  }
  if (!FLAGS_bag.empty()) {
    in.bag.paths = ListFlag("bag", FLAGS_bag);
    in.bag.topics = ListFlag("image-topics", RequiredFlag("image-topics", FLAGS_image_topics));
    in.bag.time = ParseBagTime(FLAGS_bag_time);
    return in;
  }
  // Split at every comma (getline would drop a trailing empty name): cam_id i is the i-th.
  size_t begin = 0;
  while (true) {
    const size_t comma = FLAGS_images.find(',', begin);
    const std::string dir = FLAGS_images.substr(begin, comma - begin);
    if (dir.empty()) throw Error("--images: empty folder name in '" + FLAGS_images + "'");
    in.folders.push_back(ListImageFolder(dir));
    if (comma == std::string::npos) break;
    begin = comma + 1;
  }
  return in;
}

// "detect: [=======>      ] 1234/2880 frames, 85.3 frames/s, 19 s left": redrawn in place on a
// terminal, a line per tenth of the work otherwise (a log file stays short).
class ProgressBar {
 public:
  void Update(const DetectProgress& p) {
    if (Quiet()) return;
    const double fraction = p.frames_total > 0 ? double(p.frames_done) / p.frames_total : 1.0;
    const double rate = p.elapsed_s > 0 ? p.frames_done / p.elapsed_s : 0.0;
    const double left = rate > 0 ? (p.frames_total - p.frames_done) / rate : 0.0;
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(fraction * kWidth);
    const std::string bar = std::string(filled, '=') + (filled < kWidth ? ">" : "") +
                            std::string(std::max(0, kWidth - filled - 1), ' ');
    const std::string line =
        StringPrintf("detect: [%s] %lld/%lld frames, %.1f frames/s, %.0f s left", bar.c_str(),
                     static_cast<long long>(p.frames_done),
                     static_cast<long long>(p.frames_total), rate, left);
    const bool finished = p.frames_done == p.frames_total;
    if (terminal_) {
      std::fprintf(stderr, "\r%s%s", line.c_str(), finished ? "\n" : "");
    } else if (finished || static_cast<int>(fraction * 10) > tenths_) {
      tenths_ = static_cast<int>(fraction * 10);
      std::fprintf(stderr, "%s\n", line.c_str());
    }
  }

 private:
  bool terminal_ = isatty(fileno(stderr)) != 0;
  int tenths_ = 0;
};

int RunDetect() {
  DetectInputs in = ReadDetectInputs();
  OutputDir output(FLAGS_out);
  if (!in.folders.empty()) {  // a bag's frames are counted as it is opened, by DetectBag
    int64_t frames = 0;
    for (const ImageFolder& folder : in.folders) frames += folder.frames.size();
    Progress(StringPrintf("detect: %lld frames of %zu camera%s, %s target",
                          static_cast<long long>(frames), in.folders.size(),
                          in.folders.size() == 1 ? "" : "s", in.target.type.c_str()));
  }

  DetectFoldersOptions options;
  options.threads = in.threads;
  options.detector.effort = in.effort;
  ProgressBar bar;
  options.progress = [&bar](const DetectProgress& p) { bar.Update(p); };
  if (FLAGS_draw) options.on_detection = OverlayWriter(&output);
  const DetectFoldersResult result = in.folders.empty()
                                         ? DetectBag(in.bag, in.target, options)
                                         : DetectFolders(in.folders, in.target, options);
  for (const std::string& warning : result.warnings) Progress("detect: warning: " + warning);

  output.WriteFiles(DetectOutputFiles(result, in.target, FLAGS_target, FLAGS_effort));
  output.Commit();
  if (!Quiet()) std::fputs(DetectSummaryText(result).c_str(), stderr);
  return 0;
}

}  // namespace

Command DetectCommand() {
  Command command;
  command.name = "detect";
  command.summary = "AprilGrid or checkerboard corners in image folders (observations.csv)";
  command.usage =
      "splinecal detect (--images DIR[,DIR...] | --bag FILE --image-topics T0[,T1...]\n"
      "    [--bag-time header|receive]) --target FILE [--effort fast|default|thorough]\n"
      "    [--threads N] [--draw] --out DIR";
  command.description =
      "Finds the calibration target of --target (a Kalibr aprilgrid of tag family 36h11 with a "
      "2-bit black border, or a checkerboard) in every image of every folder; the i-th folder is "
      "camera i. Corners are refined to sub-pixel precision and get the target's point ids; a "
      "partly seen aprilgrid gives the corners seen, a tag whose id or place does not fit the "
      "grid is dropped. Writes observations.csv (#t_ns,cam_id,point_id,u,v, what calibrate "
      "reads), result.yaml (per camera: resolution, images read, images with the target, "
      "corners, detection time) and with --draw one overlay per frame under overlays/camN/. A "
      "frame that cannot be read is a warning; no readable frame at all, or no frame with the "
      "target, is an error. With --bag, the frames are the messages of --image-topics (topic i "
      "is camera i; sensor_msgs/Image or CompressedImage, made grey as bag extract does), "
      "streamed from the recording, each stamped with its header stamp (--bag-time receive: "
      "the recording time). See docs/detect.md.";
  command.flags = {{"images", ""},
                   {"bag",
                    "The frames from a recording instead of --images: a ROS 1 bag (several: one "
                    "split recording), an MCAP file, or a rosbag2 folder, metadata.yaml or .db3 "
                    "files [paths, comma-separated]"},
                   {"image_topics", ""},
                   {"bag_time", ""},
                   {"target", "Calibration target: Kalibr aprilgrid or checkerboard YAML [path]"},
                   {"out", ""},
                   {"effort", ""},
                   {"threads", "", "2"},
                   {"draw", ""},
                   {"quiet", ""}};
  command.run = &RunDetect;
  command.read_inputs = [] {
    const DetectInputs in = ReadDetectInputs();
    if (in.folders.empty()) CheckBagImageSource(in.bag);
  };
  return command;
}

}  // namespace cli
}  // namespace splinecal

// splinecal.detect: the target corners in grayscale images (detect/target_detector.h), the
// per-image step of `splinecal detect` (whose result.yaml summarises folders of images). Images
// come as pixels the caller decoded, or as files that splinecal's own decoder reads
// (detect/image_file.h), so that a file gives the same corners here as in the command line.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "bindings.h"
#include "command_outputs.h"
#include "estimate_arguments.h"
#include "interruptible.h"
#include "numpy_io.h"
#include "splinecal/detect/detect_bag.h"
#include "splinecal/detect/detect_folders.h"
#include "splinecal/report/detect_report.h"
#include "splinecal/detect/image_file.h"
#include "splinecal/error.h"
#include "splinecal/detect/target_detector.h"
#include "splinecal/io/image_folder.h"
#include "splinecal/io/target_yaml.h"

namespace splinecal {
namespace python {

namespace {

py::dict DetectionDict(const TargetDetection& detection) {
  const auto n = static_cast<py::ssize_t>(detection.corners.size());
  py::array_t<int64_t> point_id(n);
  py::array_t<double> uv({n, py::ssize_t{2}});
  for (py::ssize_t i = 0; i < n; ++i) {
    point_id.mutable_data()[i] = detection.corners[i].point_id;
    uv.mutable_data()[2 * i] = detection.corners[i].uv.x();
    uv.mutable_data()[2 * i + 1] = detection.corners[i].uv.y();
  }
  py::dict dict;
  dict["point_id"] = point_id;
  dict["uv"] = uv;
  dict["tags_found"] = detection.tags_found;
  dict["tags_rejected"] = detection.tags_rejected;
  dict["corners_rejected"] = detection.corners_rejected;
  return dict;
}

// Pixels the caller decoded: a uint8 array (h, w), any memory layout.
py::dict DetectArray(py::handle image_object, TargetDetector* detector) {
  py::array any = py::array::ensure(image_object);
  if (!any) {
    PyErr_Clear();
    throw py::value_error(
        "image: expected a uint8 array (h, w), an image file, a folder or a list of files");
  }
  if (any.dtype().kind() != 'u' || any.itemsize() != 1) {
    throw py::value_error("image: expected dtype uint8 (8-bit grayscale), got dtype " +
                          py::str(any.dtype()).cast<std::string>());
  }
  if (any.ndim() != 2 || any.shape(0) < 1 || any.shape(1) < 1) {
    throw py::value_error("image: expected shape (h, w), got " + std::to_string(any.ndim()) +
                          " dimensions");
  }
  const auto image = py::array_t<uint8_t, py::array::c_style>::ensure(any);
  GrayImageView view;
  view.height = static_cast<int>(image.shape(0));
  view.width = static_cast<int>(image.shape(1));
  view.stride = view.width;
  view.data = image.data();
  return DetectionDict(RunWithoutGil([&] { return detector->Detect(view); }));
}

// One file, decoded as `splinecal detect` decodes it; splinecal.Error naming it when it cannot.
py::dict DetectFile(const std::string& path, TargetDetector* detector) {
  py::dict dict = DetectionDict(RunWithoutGil([&] {
    const GrayImage image = ReadGrayImage(path);
    return detector->Detect(image.view());
  }));
  dict["path"] = path;
  return dict;
}

// The paths of a list or tuple `object` (every item checked before any is used; a ValueError
// naming `name`[i] for an item that is not a path); nullopt when `object` is no list or tuple.
std::optional<std::vector<std::string>> PathList(py::handle object, const std::string& name,
                                                 const std::string& what) {
  if (!py::isinstance<py::list>(object) && !py::isinstance<py::tuple>(object)) return std::nullopt;
  std::vector<std::string> paths;
  for (py::handle item : object) {
    const std::optional<std::string> path = AsPath(item);
    if (!path) {
      throw py::value_error(name + "[" + std::to_string(paths.size()) +
                            "]: expected a path (str or os.PathLike) in a list of " + what);
    }
    paths.push_back(*path);
  }
  return paths;
}

// Each line as a Python warning (UserWarning), where the command line prints
// "detect: warning: LINE" to stderr.
void Warn(const std::vector<std::string>& lines) {
  for (const std::string& line : lines) {
    if (PyErr_WarnEx(PyExc_UserWarning, line.c_str(), 1) != 0) throw py::error_already_set();
  }
}

// A camera folder as `splinecal detect --images` reads it: every frame searched, one dict per
// frame in time order (with t_ns and path); frames that cannot be used are warnings, as in the
// command line.
py::list DetectFolder(const std::string& dir, const CalibrationTarget& board,
                      const DetectorOptions& detector, int threads) {
  DetectFoldersOptions options;
  options.threads = threads;
  options.detector = detector;
  std::mutex mutex;
  std::map<int64_t, std::pair<std::string, TargetDetection>> frames;
  options.on_detection = [&](int, const ImageFrame& frame, const GrayImage&,
                             const TargetDetection& detection) {
    std::lock_guard<std::mutex> lock(mutex);
    frames[frame.t_ns] = {frame.path, detection};
  };
  const DetectFoldersResult result =
      RunWithoutGil([&] { return DetectFolders({ListImageFolder(dir)}, board, options); });
  Warn(result.warnings);
  py::list list;
  for (const auto& [t_ns, frame] : frames) {
    py::dict dict = DetectionDict(frame.second);
    dict["path"] = frame.first;
    dict["t_ns"] = t_ns;
    list.append(dict);
  }
  return list;
}

// The whole command (`splinecal detect --images ...`): result.yaml as a dict with the
// observations, and with out= the command's files, written by the same function.
// With a bag source (bag=, as --bag), the frames are the messages of its image topics instead.
py::dict DetectCommand(py::handle images, const std::optional<BagImageSource>& bag,
                       const std::string& target_path, const CalibrationTarget& board,
                       const std::string& effort, const DetectorOptions& detector, int threads,
                       bool draw, py::handle out) {
  // A str (or path) is split at commas as the command line splits --images; a list holds one
  // folder per camera.
  std::vector<std::string> dirs;
  if (bag.has_value()) {
    // no folders
  } else if (const std::optional<std::string> list = AsPath(images)) {
    size_t begin = 0;
    while (true) {
      const size_t comma = list->find(',', begin);
      dirs.push_back(list->substr(begin, comma - begin));
      if (comma == std::string::npos) break;
      begin = comma + 1;
    }
  } else if (std::optional<std::vector<std::string>> list = PathList(images, "images", "folders")) {
    dirs = *list;
  } else {
    throw py::type_error("images: expected camera folders, a list or a comma-separated str");
  }
  std::vector<ImageFolder> folders;
  for (const std::string& dir : dirs) {
    if (dir.empty()) throw py::value_error("images: an empty folder name");
    folders.push_back(ListImageFolder(dir));
  }
  std::unique_ptr<OutputDir> dir = OutputArgument(out);
  if (draw && dir == nullptr) {
    throw py::value_error("draw: the overlays are files under out/overlays/; give out= too");
  }
  DetectFoldersOptions options;
  options.threads = threads;
  options.detector = detector;
  if (draw) options.on_detection = OverlayWriter(dir.get());
  const DetectFoldersResult result = RunWithoutGil([&] {
    return bag.has_value() ? DetectBag(*bag, board, options)
                           : DetectFolders(folders, board, options);
  });
  Warn(result.warnings);
  py::dict dict = FinishOutputs(dir.get(), DetectOutputFiles(result, board, target_path, effort));
  dict["observations"] = ObservationsDict(result.observations);
  return dict;
}

py::object Detect(py::handle images_argument, py::handle target, const std::string& effort,
                  py::handle images, py::handle out, int threads, bool draw, py::handle bag,
                  py::handle image_topics, const std::string& bag_time) {
  const std::string target_path = PathArgument(target, "target");
  const CalibrationTarget board = ReadTargetYaml(target_path);
  DetectorOptions options;
  try {
    options.effort = ParseDetectEffort(effort);
  } catch (const Error& e) {
    throw py::value_error(std::string("effort: ") + e.what());
  }
  if (threads < 1 || threads > 256) {
    throw py::value_error("threads: expected 1 to 256, got " + std::to_string(threads));
  }
  if (!bag.is_none()) {
    if (!images.is_none() || !images_argument.is_none()) {
      throw py::type_error("detect: give the frames as bag= with image_topics= (as --bag), or "
                           "as image or images=, not both");
    }
    BagImageSource source;
    source.paths = BagPaths(bag);
    if (const std::optional<std::string> topics = AsPath(image_topics)) {
      source.topics = SplitCommaList(*topics, "image_topics", "topic");
    } else if (std::optional<std::vector<std::string>> list =
                   PathList(image_topics, "image_topics", "topics")) {
      source.topics = *list;
    }
    if (source.topics.empty()) {
      throw py::value_error("image_topics: the bag's image topics (a list, or a str with "
                            "commas, as --image-topics; the i-th is camera i)");
    }
    source.time = ParseBagTime(bag_time);
    return DetectCommand(py::none(), source, target_path, board, effort, options, threads, draw,
                         out);
  }
  if (!image_topics.is_none()) {
    throw py::type_error("image_topics: the topics of bag=; give bag= too");
  }
  if (!images.is_none()) {
    if (!images_argument.is_none()) {
      throw py::type_error("detect: give either image (pixels, a file, files or a folder) or "
                           "images= (camera folders, as --images), not both");
    }
    return DetectCommand(images, std::nullopt, target_path, board, effort, options, threads, draw,
                         out);
  }
  if (!out.is_none() || draw) {
    throw py::type_error(std::string(draw ? "draw" : "out") +
                         ": writes the command's files, for images= (camera folders, as "
                         "--images); detect(image, ...) returns its corners only");
  }
  if (images_argument.is_none()) {
    throw py::type_error("detect: missing image (pixels, a file, files or a folder) or images=");
  }
  TargetDetector detector(board, options);
  if (const std::optional<std::string> path = AsPath(images_argument)) {
    if (std::filesystem::is_directory(*path)) return DetectFolder(*path, board, options, threads);
    // One file: nothing else to return when it cannot be read (the command line, given only
    // this frame, stops with "none of cam0's 1 images could be read").
    return DetectFile(*path, &detector);
  }
  if (const std::optional<std::vector<std::string>> list =
          PathList(images_argument, "image", "files")) {
    const std::vector<std::string>& paths = *list;
    // A file that cannot be read is a warning and is left out (its dict would have no corners
    // to give), as the command line skips such a frame; none readable is an error, as there.
    py::list frames;
    std::string first_problem;
    for (const std::string& path : paths) {
      try {
        frames.append(DetectFile(path, &detector));
      } catch (const Error& e) {
        if (first_problem.empty()) first_problem = e.what();
        Warn({std::string(e.what()) + ", frame skipped"});
      }
    }
    if (frames.empty() && !paths.empty()) {
      throw Error("image: none of the " + std::to_string(paths.size()) +
                  " files could be read (first problem: " + first_problem + ")");
    }
    return std::move(frames);
  }
  return DetectArray(images_argument, &detector);
}

}  // namespace

void BindDetect(py::module_& m) {
  m.def("detect",
        &Detect,
        py::arg("image") = py::none(),
        py::arg("target") = py::none(),
        py::kw_only(),
        py::arg("effort") = "default",
        py::arg("images") = py::none(),
        py::arg("out") = py::none(),
        py::arg("threads") = 2,
        py::arg("draw") = false,
        py::arg("bag") = py::none(),
        py::arg("image_topics") = py::none(),
        py::arg("bag_time") = "header",
        R"(Target corners in grayscale images; target: a Kalibr target YAML path.

image: a uint8 array (h, w) of pixels already decoded, or the path of a PNG/JPEG file, or a
list of such paths, or a camera folder as `splinecal detect --images` reads it (EuRoC data.csv
and data/, or <t_ns>.png files). Files are decoded by splinecal's own decoder, as the command
line does, so the same file gives the same corners in both.
images: instead of image, the command itself: camera folders (a list, or a str with commas,
as --images; the i-th is camera i), searched on `threads` workers; returns result.yaml's dict
with "observations" (t_ns, cam_id, point_id, uv arrays). out: a folder to write the command's
files to (observations.csv, result.yaml, and with draw=True overlays/camN/<t_ns>.png), whole or
not at all. A target found in no frame raises splinecal.Error, as the command exits 2.
effort: "default" (recall first), "thorough" (the upsampled searches in every frame) or
"fast" (one search, misses most tags under 25 px), as `splinecal detect --effort`.
threads: frames searched at once (images= and a folder).
bag: instead of images=, a recording (a path or a list: a ROS 1 bag, split bags, an MCAP file,
a rosbag2 folder), its image_topics (a list, or a str with commas; the i-th is camera i) as
`splinecal detect --bag --image-topics`, streamed; bag_time "header" (the header stamps) or
"receive" (the recording time). Returns and writes what images= does.

Returns, for an array or a file, a dict: point_id (k,) and uv (k, 2) [px] (pixel centres at
integers, docs/conventions.md), tags_found, tags_rejected, corners_rejected (and path for a
file); for a list of files, a list of such dicts in its order; for a folder, a list in time
order whose dicts also hold t_ns. A frame that cannot be used (unreadable, another size) is a
UserWarning naming it and is left out, where the command line warns and skips it; a single file
that cannot be read raises splinecal.Error naming it.)");
}

}  // namespace python
}  // namespace splinecal

// splinecal.bag_info and splinecal.bag_extract: `splinecal bag info` and `splinecal bag extract`
// (docs/bags.md) with their flags as keywords. bag_extract runs the command's own function
// (detect/bag_extract.h), streamed into out/.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <climits>
#include <memory>
#include <string>
#include <vector>

#include "bindings.h"
#include "command_outputs.h"
#include "estimate_arguments.h"
#include "interruptible.h"
#include "numpy_io.h"
#include "splinecal/detect/bag_extract.h"
#include "splinecal/error.h"
#include "splinecal/io/bag_messages.h"
#include "splinecal/io/bag_reader.h"
#include "splinecal/io/output_dir.h"
#include "yaml_to_python.h"

namespace splinecal {
namespace python {

namespace py = pybind11;

namespace {

// What `bag info` prints, as a dict: per topic its type, count, rate and longest gap in recording
// time, and whether splinecal reads it.
py::dict BagInfo(py::handle bags) {
  const std::vector<std::string> paths = BagPaths(bags);
  const std::unique_ptr<BagReader> bag = OpenBag(paths);
  py::dict dict;
  dict["paths"] = paths;
  dict["format"] = bag->format();
  dict["size_bytes"] = bag->file_bytes();
  int64_t messages = 0;
  int64_t start = INT64_MAX;
  int64_t end = INT64_MIN;
  py::dict topics;
  for (const BagTopic& topic : bag->topics()) {
    messages += topic.message_count;
    py::dict entry;
    entry["type"] = topic.type;
    entry["messages"] = topic.message_count;
    entry["read_by_splinecal"] = KindOfType(topic.type) != BagMessageKind::kOther;
    if (topic.message_count > 0) {
      entry["first_t_ns"] = topic.first_time_ns;
      entry["last_t_ns"] = topic.last_time_ns;
      start = std::min(start, topic.first_time_ns);
      end = std::max(end, topic.last_time_ns);
    }
    if (topic.message_count > 1 && topic.last_time_ns > topic.first_time_ns) {
      entry["rate_hz"] = (topic.message_count - 1) * 1e9 /
                         static_cast<double>(topic.last_time_ns - topic.first_time_ns);
      entry["max_gap_s"] = topic.max_gap_ns * 1e-9;
    }
    topics[py::str(topic.name)] = entry;
  }
  dict["messages"] = messages;
  if (messages > 0) {
    dict["start_t_ns"] = start;
    dict["end_t_ns"] = end;
  }
  dict["topics"] = topics;
  dict["warnings"] = bag->warnings();
  return dict;
}

py::dict BagExtract(py::handle bags, py::handle out, py::handle topics,
                    const std::string& bag_time) {
  const std::vector<std::string> paths = BagPaths(bags);
  std::string name;
  for (const std::string& path : paths) name += (name.empty() ? "" : ",") + path;
  BagExtractOptions options;
  const std::string list = topics.is_none() ? "" : CommaListArgument(topics, "topics");
  if (!list.empty()) options.topics = SplitCommaList(list, "topics", "topic");
  options.time = ParseBagTime(bag_time);
  const std::unique_ptr<BagReader> bag = OpenBag(paths);
  ChooseExtractedTopics(*bag, options, name);  // a bad topic before the folder is made
  OutputDir output(PathArgument(out, "out"));
  const std::vector<ExtractedTopic> extracted =
      RunWithoutGil([&] { return ExtractBag(bag.get(), options, name, &output); });
  const std::string yaml = BagExtractResultYaml(*bag, paths, bag_time, extracted);
  output.WriteFile("result.yaml", yaml);
  output.Commit();
  return YamlTextToDict(yaml);
}

}  // namespace

void BindBag(py::module_& m) {
  m.def("bag_info",
        &BagInfo,
        py::arg("bags"),
        R"(What `splinecal bag info` lists, as a dict. bags: a ROS 1 bag, a list of them (one split
recording), an MCAP file, or a rosbag2 folder, metadata.yaml or .db3 files. Returns format,
size_bytes, messages, start_t_ns, end_t_ns (recording time), warnings (an unindexed bag read by a
linear scan), and topics {name: {type, messages, first_t_ns, last_t_ns, rate_hz, max_gap_s,
read_by_splinecal}}.)");
  m.def("bag_extract",
        &BagExtract,
        py::arg("bags"),
        py::arg("out"),
        py::kw_only(),
        py::arg("topics") = py::none(),
        py::arg("bag_time") = "header",
        R"(`splinecal bag extract`: the recording's IMU and image topics written into the folder
out as EuRoC/ASL folders (imu0/data.csv, cam0/data.csv + cam0/data/<t_ns>.png, 8-bit grey),
streamed, whole or not at all. topics: a list or a str with commas (in this order; None: every
sensor_msgs/Imu, Image and CompressedImage topic, by name); bag_time: "header" (the header
stamps) or "receive" (the recording time). Returns result.yaml's content: which topic became
which folder, with its count and time range.)");
}

}  // namespace python
}  // namespace splinecal

// OpenBag: tells the formats apart by their first bytes (io/bag_reader.h).
#include "splinecal/io/bag_reader.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "bag_formats.h"
#include "splinecal/error.h"
#include "splinecal/io/yaml_document.h"

namespace splinecal {
namespace {

enum class Format { kRos1, kMcap, kSqlite, kMetadata };

bool IsDirectory(const std::string& path) {
  struct stat info;
  return ::stat(path.c_str(), &info) == 0 && S_ISDIR(info.st_mode);
}

bool EndsWith(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

Format Detect(const std::string& path) {
  if (IsDirectory(path) || EndsWith(path, "metadata.yaml")) return Format::kMetadata;
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) throw Error(path, 0, std::string("cannot open: ") + std::strerror(errno));
  char head[16] = {};
  const size_t got = std::fread(head, 1, sizeof(head), file);
  std::fclose(file);
  const std::string_view bytes(head, got);
  if (bytes.substr(0, 13) == "#ROSBAG V2.0\n") return Format::kRos1;
  if (bytes.substr(0, 8) == std::string_view("\x89MCAP0\r\n", 8)) return Format::kMcap;
  if (bytes.substr(0, 16) == std::string_view("SQLite format 3\0", 16)) return Format::kSqlite;
  if (bytes.substr(0, 9) == "#ROSBAG V") {
    throw Error(path, 0, "a ROS 1 bag of another version than 2.0 (re-record or 'rosbag fix')");
  }
  throw Error(path, 0, "not a ROS 1 bag, MCAP file or rosbag2 sqlite3 database");
}

// The files a rosbag2 metadata.yaml lists, as paths, and its storage.
std::vector<std::string> Rosbag2Files(const std::string& path, std::string* storage) {
  const size_t slash = path.rfind('/');
  const std::string folder =
      IsDirectory(path) ? path : (slash == std::string::npos ? "" : path.substr(0, slash));
  const std::string metadata = IsDirectory(path) ? path + "/metadata.yaml" : path;
  const YamlDocument yaml(metadata);
  *storage = yaml.String("rosbag2_bagfile_information/storage_identifier");
  std::vector<std::string> files;
  for (const std::string& relative : yaml.Strings("rosbag2_bagfile_information/relative_file_paths")) {
    files.push_back(folder.empty() ? relative : folder + "/" + relative);
  }
  if (files.empty()) throw Error(metadata, 0, "lists no files (relative_file_paths)");
  return files;
}

}  // namespace

std::unique_ptr<BagReader> OpenBag(const std::vector<std::string>& paths) {
  if (paths.empty()) throw Error("no bag file given");
  const Format format = Detect(paths[0]);
  for (const std::string& path : paths) {
    if (Detect(path) != format) {
      throw Error(path, 0, "is another format than " + paths[0] + ": give one recording");
    }
  }
  switch (format) {
    case Format::kRos1:
      return internal::OpenRos1Bags(paths);
    case Format::kMcap:
      if (paths.size() > 1) throw Error(paths[1], 0, "one MCAP file at a time");
      return internal::OpenMcap(paths[0]);
    case Format::kSqlite:
      return internal::OpenRosbag2Sqlite(paths);
    case Format::kMetadata: {
      if (paths.size() > 1) throw Error(paths[1], 0, "one rosbag2 folder at a time");
      std::string storage;
      const std::vector<std::string> files = Rosbag2Files(paths[0], &storage);
      if (storage == "sqlite3") return internal::OpenRosbag2Sqlite(files);
      if (storage == "mcap" && files.size() == 1) {
        struct stat info;
        if (::stat(files[0].c_str(), &info) != 0) {
          throw Error(files[0], 0, "missing MCAP file of the recording");
        }
        return internal::OpenMcap(files[0]);
      }
      throw Error(paths[0], 0, "storage '" + storage + "' with " +
                                   std::to_string(files.size()) +
                                   " files: splinecal reads sqlite3, and mcap as one file");
    }
  }
  return nullptr;
}

}  // namespace splinecal

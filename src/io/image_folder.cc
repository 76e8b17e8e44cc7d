#include "splinecal/io/image_folder.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <system_error>

#include "splinecal/error.h"
#include "splinecal/io/text_file.h"

namespace splinecal {
namespace {

namespace fs = std::filesystem;

bool HasImageExtension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg";
}

bool IsRegularFile(const fs::path& path) {
  std::error_code error;
  return fs::is_regular_file(path, error);
}

// EuRoC/ASL: `#timestamp [ns],filename`, the file under DIR/data/.
void ReadEurocFrames(const fs::path& dir, ImageFolder* folder) {
  const fs::path csv = dir / "data.csv";
  TextFileReader reader(csv.string());
  std::vector<std::string_view> fields;
  while (reader.NextLine()) {
    SplitFields(reader.line(), &fields);
    if (fields.size() != 2) {
      reader.Fail("expected 2 columns (timestamp [ns], filename), got " +
                  std::to_string(fields.size()));
    }
    ImageFrame frame;
    frame.t_ns = ParseTimestampNs(fields[0], reader, "timestamp [ns]");
    if (fields[1].empty()) reader.Fail("empty filename", fields[1]);
    frame.path = (dir / "data" / std::string(fields[1])).string();
    frame.origin = csv.string() + ":" + std::to_string(reader.line_number());
    if (!IsRegularFile(frame.path)) {
      std::error_code error;
      folder->warnings.push_back(frame.origin + ": image " + frame.path +
                                 (fs::exists(frame.path, error) ? " is not a regular file"
                                                                : " is missing"));
      continue;
    }
    folder->frames.push_back(std::move(frame));
  }
}

// A plain folder: every <t_ns>.png/.jpg; other image names are listed as warnings, other files
// (a README, a data.csv of another layout) are ignored.
void ReadPlainFrames(const fs::path& dir, ImageFolder* folder) {
  std::error_code error;
  fs::directory_iterator it(dir, error);
  if (error) throw Error(dir.string(), 0, "cannot list the folder: " + error.message());
  // Incremented with an error code: a failing readdir is a clear error, not an exception.
  for (; it != fs::directory_iterator(); it.increment(error)) {
    if (error) throw Error(dir.string(), 0, "cannot list the folder: " + error.message());
    const fs::directory_entry& entry = *it;
    if (!HasImageExtension(entry.path())) continue;
    if (!entry.is_regular_file(error)) {
      folder->warnings.push_back(entry.path().string() +
                                 ": not a regular file (a folder or a broken link), skipped");
      continue;
    }
    ImageFrame frame;
    frame.path = entry.path().string();
    frame.origin = frame.path;
    const std::string stem = entry.path().stem().string();
    if (!TryParseInt64(stem, &frame.t_ns) || frame.t_ns < 0 || frame.t_ns > kMaxTimestampNs) {
      folder->warnings.push_back(frame.path +
                                 ": the name is not a timestamp [ns] (<t_ns>.png), skipped");
      continue;
    }
    folder->frames.push_back(std::move(frame));
  }
}

}  // namespace

ImageFolder ListImageFolder(const std::string& dir) {
  ImageFolder folder;
  folder.dir = dir;
  std::error_code error;
  if (!fs::is_directory(dir, error)) {
    if (error && error != std::errc::no_such_file_or_directory) {
      throw Error(dir, 0, "cannot open the folder: " + error.message());  // e.g. no permission
    }
    throw Error(dir, 0, fs::exists(dir, error) ? "not a folder" : "no such folder");
  }
  folder.euroc = IsRegularFile(fs::path(dir) / "data.csv");
  if (folder.euroc) {
    ReadEurocFrames(dir, &folder);
  } else {
    ReadPlainFrames(dir, &folder);
  }
  std::sort(folder.frames.begin(), folder.frames.end(),
            [](const ImageFrame& a, const ImageFrame& b) { return a.t_ns < b.t_ns; });
  for (size_t i = 1; i < folder.frames.size(); ++i) {
    if (folder.frames[i].t_ns == folder.frames[i - 1].t_ns) {
      throw Error(folder.frames[i].origin + ": timestamp " + std::to_string(folder.frames[i].t_ns) +
                  " also names " + folder.frames[i - 1].origin);
    }
  }
  if (folder.frames.empty()) {
    throw Error(folder.euroc ? (fs::path(dir) / "data.csv").string() : dir, 0,
                folder.euroc ? "no image of data.csv exists under data/"
                             : "no images named <t_ns>.png or <t_ns>.jpg");
  }
  return folder;
}

}  // namespace splinecal

// The frames of one camera's image folder, in time order: what `splinecal detect` reads
// (docs/detect.md). Two layouts are accepted:
//
//   EuRoC/ASL camera folder   DIR/data.csv with `#timestamp [ns],filename` rows, the images in
//                             DIR/data/ (read with the one input layer, io/text_file.h)
//   plain folder              DIR/<t_ns>.png or DIR/<t_ns>.jpg (also .jpeg, any letter case)
//
// Only names are listed here; decoding the pixels is detect/'s job.
#ifndef SPLINECAL_IO_IMAGE_FOLDER_H_
#define SPLINECAL_IO_IMAGE_FOLDER_H_

#include <cstdint>
#include <string>
#include <vector>

namespace splinecal {

struct ImageFrame {
  int64_t t_ns = 0;    // the frame's timestamp, camera clock [ns]
  std::string path;    // the image file
  std::string origin;  // where the frame was named, for messages: "DIR/data.csv:12" or the path
};

struct ImageFolder {
  std::string dir;
  bool euroc = false;  // true: DIR/data.csv named the frames
  std::vector<ImageFrame> frames;
  // Rows or files that name no usable frame (a data.csv row whose image is missing, a file whose
  // name is not a timestamp): "origin: problem", one per entry. Lists them; the caller decides.
  std::vector<std::string> warnings;
};

// Lists the frames of `dir`, sorted by t_ns. Throws splinecal::Error naming the file and line for
// a folder that is missing or unreadable, a malformed data.csv row (column count, timestamp), the
// same timestamp twice, and for a folder with no frame at all.
ImageFolder ListImageFolder(const std::string& dir);

}  // namespace splinecal

#endif  // SPLINECAL_IO_IMAGE_FOLDER_H_

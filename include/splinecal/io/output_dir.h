// The one way splinecal writes results: whole or not at all (docs/conventions.md, "Command
// line").
//
// Files are staged in a hidden folder inside the output directory (same file system, so rename
// is atomic) and moved into place by Commit(). A run that fails before Commit() - bad input, a
// solver that diverged, an exception - leaves the previous results untouched and no new partial
// files: the destructor removes the staging folder.
#ifndef SPLINECAL_IO_OUTPUT_DIR_H_
#define SPLINECAL_IO_OUTPUT_DIR_H_

#include <string>
#include <vector>

namespace splinecal {

// One file of a command's results: its path relative to the output folder, and its contents.
// The report functions return a command's files as a list (report/command_outputs.h), so that
// the command line and the Python module write the same files.
struct OutputFile {
  std::string path;
  std::string contents;
};

// The contents of `path` in `files`; throws std::logic_error when it is not there (a bug).
const std::string& OutputFileContents(const std::vector<OutputFile>& files,
                                      const std::string& path);

class OutputDir {
 public:
  // Creates `dir` (and its parents) if missing; throws Error when it cannot (a file in the way,
  // no permission). Every failure here happens before any work is done.
  explicit OutputDir(const std::string& dir);
  ~OutputDir();
  OutputDir(const OutputDir&) = delete;
  OutputDir& operator=(const OutputDir&) = delete;

  const std::string& dir() const { return dir_; }

  // Stages `contents` as dir/relative_path (subfolders such as "mav0/imu0" are created).
  void WriteFile(const std::string& relative_path, const std::string& contents);
  // Stages every file of `files` (WriteFile).
  void WriteFiles(const std::vector<OutputFile>& files);
  // The staged path of relative_path (its folder created), for code that writes a file itself.
  std::string StagedPath(const std::string& relative_path);

  // Moves every staged file into place. Files are renamed one by one, each atomically.
  void Commit();

 private:
  std::string dir_;
  std::string staging_;
  std::vector<std::string> staged_;
  bool committed_ = false;
};

}  // namespace splinecal

#endif  // SPLINECAL_IO_OUTPUT_DIR_H_

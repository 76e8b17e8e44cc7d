#include "splinecal/io/output_dir.h"

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "splinecal/error.h"

namespace splinecal {
namespace fs = std::filesystem;

namespace {

void CheckRelativePath(const std::string& dir, const std::string& relative_path) {
  const fs::path path(relative_path);
  if (relative_path.empty() || path.is_absolute()) {
    throw Error(dir, 0, "output name '" + relative_path + "' must be a relative path");
  }
  for (const auto& part : path) {
    if (part == "..") throw Error(dir, 0, "output name '" + relative_path + "' leaves the folder");
  }
}

}  // namespace

const std::string& OutputFileContents(const std::vector<OutputFile>& files,
                                      const std::string& path) {
  for (const OutputFile& file : files) {
    if (file.path == path) return file.contents;
  }
  throw std::logic_error("no output file " + path);
}

OutputDir::OutputDir(const std::string& dir) : dir_(dir) {
  if (dir.empty()) throw Error("--out is required: the folder for the results");
  std::error_code error;
  if (fs::exists(dir, error) && !fs::is_directory(dir, error)) {
    throw Error(dir, 0, "output path exists and is not a directory");
  }
  fs::create_directories(dir, error);
  if (error) throw Error(dir, 0, "cannot create output directory: " + error.message());
  static std::atomic<int> counter{0};
  staging_ = (fs::path(dir) / (".splinecal-staging-" + std::to_string(::getpid()) + "-" +
                               std::to_string(counter++)))
                 .string();
  fs::create_directory(staging_, error);
  if (error) throw Error(dir, 0, "cannot write in output directory: " + error.message());
}

OutputDir::~OutputDir() {
  std::error_code ignored;
  fs::remove_all(staging_, ignored);
}

std::string OutputDir::StagedPath(const std::string& relative_path) {
  CheckRelativePath(dir_, relative_path);
  const fs::path staged = fs::path(staging_) / relative_path;
  std::error_code error;
  fs::create_directories(staged.parent_path(), error);
  if (error) throw Error(staged.string(), 0, "cannot create folder: " + error.message());
  staged_.push_back(relative_path);
  return staged.string();
}

void OutputDir::WriteFile(const std::string& relative_path, const std::string& contents) {
  const std::string path = StagedPath(relative_path);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
  out.close();
  if (!out) throw Error(path, 0, "cannot write (disk full or no permission?)");
}

void OutputDir::WriteFiles(const std::vector<OutputFile>& files) {
  for (const OutputFile& file : files) WriteFile(file.path, file.contents);
}

void OutputDir::Commit() {
  if (committed_) return;
  for (const std::string& relative_path : staged_) {
    const fs::path target = fs::path(dir_) / relative_path;
    std::error_code error;
    fs::create_directories(target.parent_path(), error);
    if (!error) fs::rename(fs::path(staging_) / relative_path, target, error);
    if (error) throw Error(target.string(), 0, "cannot move result into place: " + error.message());
  }
  committed_ = true;
  std::error_code ignored;
  fs::remove_all(staging_, ignored);
}

}  // namespace splinecal

#include "splinecal/io/parallel_euroc_imu.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string_view>
#include <thread>

#include "splinecal/io/text_file.h"

namespace splinecal {
namespace internal {
namespace {

// A read-only memory map of a whole file (empty when mapping fails).
class MappedFile {
 public:
  explicit MappedFile(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY);
    if (fd < 0) return;
    struct stat info;
    if (::fstat(fd, &info) == 0 && S_ISREG(info.st_mode) && info.st_size > 0) {
      void* data =
          ::mmap(nullptr, static_cast<size_t>(info.st_size), PROT_READ, MAP_PRIVATE, fd, 0);
      if (data != MAP_FAILED) {
        data_ = static_cast<const char*>(data);
        size_ = static_cast<size_t>(info.st_size);
        ::madvise(data, size_, MADV_SEQUENTIAL);
      }
    }
    ::close(fd);
  }
  ~MappedFile() {
    if (data_ != nullptr) ::munmap(const_cast<char*>(data_), size_);
  }
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  std::string_view text() const { return std::string_view(data_, size_); }

 private:
  const char* data_ = nullptr;
  size_t size_ = 0;
};

// What one thread found in its share of the file.
struct ChunkScan {
  int64_t rows = 0;
  int64_t first_t_ns = 0;
  int64_t last_t_ns = 0;
  int64_t largest_step_ns = 0;
  bool ok = true;
};

// Calls visit(DataLineContent(line)) for each data line of `chunk` (whole lines); stops and
// returns false as soon as visit does.
template <typename Visit>
bool ForEachDataLine(std::string_view chunk, Visit&& visit) {
  while (!chunk.empty()) {
    const size_t newline = chunk.find('\n');
    const std::string_view content = DataLineContent(chunk.substr(0, newline));
    if (!content.empty() && !visit(content)) return false;
    if (newline == std::string_view::npos) break;
    chunk.remove_prefix(newline + 1);
  }
  return true;
}

bool IsBlank(char c) { return c == ' ' || c == '\t'; }

// A row "t,gx,gy,gz,ax,ay,az" (blanks allowed around the commas): a row that SplitFields cuts into
// seven fields at its commas and that TryParseInt64 and TryParseFiniteDouble accept, read in one
// pass (the caller's finite limits refuse what TryParseFiniteDouble would refuse: inf, nan).
// False for anything else, whitespace-separated columns included: the TextFileReader path then
// reads or refuses it.
bool ParseRow(std::string_view line, int64_t* t_ns, double* values) {
  const char* p = line.data();
  const char* const end = p + line.size();
  p = ParseNumberPrefix(p, end, t_ns);
  for (int a = 0; a < 6 && p != nullptr; ++a) {
    while (p != end && IsBlank(*p)) ++p;
    if (p == end || *p != ',') return false;
    ++p;
    while (p != end && IsBlank(*p)) ++p;
    p = ParseNumberPrefix(p, end, &values[a]);
  }
  return p == end;
}

// Runs body(0) .. body(threads - 1) at once, body(0) on the calling thread.
template <typename Body>
void RunOnThreads(int threads, Body&& body) {
  std::vector<std::thread> pool;
  for (int i = 1; i < threads; ++i) pool.emplace_back(body, i);
  body(0);
  for (std::thread& thread : pool) thread.join();
}

}  // namespace

std::optional<EurocImuColumns> ReadEurocImuParallel(const std::string& path,
                                                    double gyro_scale,
                                                    double accel_scale) {
  const MappedFile file(path);
  const std::string_view text = file.text();
  if (text.empty()) return std::nullopt;
  const int threads = static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, 16u));
  // Shares of the file that begin just after a newline.
  std::vector<std::string_view> chunks(threads);
  size_t begin = 0;
  for (int i = 0; i < threads; ++i) {
    size_t end = text.size();
    if (i + 1 < threads) {
      const size_t newline = text.find('\n', std::max(begin, text.size() / threads * (i + 1)));
      end = newline == std::string_view::npos ? text.size() : newline + 1;
    }
    chunks[i] = text.substr(begin, end - begin);
    begin = end;
  }
  // Pass 1: data rows per share, so that every thread writes straight into the final arrays.
  std::vector<ChunkScan> scans(threads);
  RunOnThreads(threads, [&](int chunk) {
    int64_t rows = 0;
    ForEachDataLine(chunks[chunk], [&](std::string_view) {
      ++rows;
      return true;
    });
    scans[chunk].rows = rows;
  });
  std::vector<int64_t> offsets(threads + 1, 0);
  for (int i = 0; i < threads; ++i) offsets[i + 1] = offsets[i] + scans[i].rows;
  const int64_t rows = offsets[threads];
  if (rows < 2) return std::nullopt;
  EurocImuColumns columns;
  for (std::vector<double>& values : columns.values) values.resize(rows);
  double scales[6];
  // Limits in the file's unit, as the TextFileReader path checks them; kept finite (a tiny scale
  // would make them inf) so that they also refuse inf and nan.
  double limits[6];
  for (int a = 0; a < 6; ++a) {
    scales[a] = a < 3 ? gyro_scale : accel_scale;
    limits[a] = std::min((a < 3 ? kMaxAngularRate : kMaxAcceleration) / scales[a],
                         std::numeric_limits<double>::max());
  }
  // Pass 2: parse.
  RunOnThreads(threads, [&](int chunk) {
    // Counted in a local copy: the threads' entries of `scans` share cache lines, and writing
    // them on every row would have the cores fight over those lines.
    ChunkScan scan;
    int64_t row = offsets[chunk];
    scan.ok = ForEachDataLine(chunks[chunk], [&](std::string_view line) {
      int64_t t_ns = 0;
      double values[6];
      if (!ParseRow(line, &t_ns, values) || t_ns > kMaxTimestampNs || t_ns < -kMaxTimestampNs) {
        return false;
      }
      if (scan.rows > 0) {
        if (t_ns <= scan.last_t_ns) return false;
        scan.largest_step_ns = std::max(scan.largest_step_ns, t_ns - scan.last_t_ns);
      } else {
        scan.first_t_ns = t_ns;
      }
      scan.last_t_ns = t_ns;
      for (int a = 0; a < 6; ++a) {
        if (!(std::abs(values[a]) <= limits[a])) return false;
        columns.values[a][row] = scales[a] * values[a];
      }
      ++scan.rows;
      ++row;
      return true;
    });
    scans[chunk] = scan;
  });
  bool started = false;
  for (const ChunkScan& scan : scans) {
    if (!scan.ok) return std::nullopt;
    if (scan.rows == 0) continue;
    if (started) {
      if (scan.first_t_ns <= columns.last_t_ns) return std::nullopt;
      columns.largest_step_ns =
          std::max(columns.largest_step_ns, scan.first_t_ns - columns.last_t_ns);
    } else {
      columns.first_t_ns = scan.first_t_ns;
      started = true;
    }
    columns.largest_step_ns = std::max(columns.largest_step_ns, scan.largest_step_ns);
    columns.last_t_ns = scan.last_t_ns;
  }
  return columns;
}

}  // namespace internal
}  // namespace splinecal

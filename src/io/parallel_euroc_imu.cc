#include "splinecal/io/parallel_euroc_imu.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <string_view>
#include <thread>

#include "splinecal/io/number_parser.h"
#include "splinecal/io/detail/number_parser_avx2.h"
#include "splinecal/io/text_file.h"
#include "splinecal/run_tasks.h"

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

// What one share of the file holds.
struct Chunk {
  std::string_view text;  // whole lines
  int64_t row_bound = 0;  // line ends counted: at least its data rows
  int64_t first_row = 0;  // where its rows go in the columns
  int64_t rows = 0;
  int64_t first_t_ns = 0;
  int64_t last_t_ns = 0;
  int64_t largest_step_ns = 0;
  bool ok = true;
};

// Number of '\n' in `text`, 16 bytes per step (GCC/Clang vector extension: SSE2 on x86-64; 4x
// faster than std::count, which widens every comparison to 64 bits).
int64_t CountNewlines(std::string_view text) {
  typedef unsigned char Bytes __attribute__((vector_size(16)));
  Bytes newline;
  for (int i = 0; i < 16; ++i) newline[i] = '\n';
  int64_t count = 0;
  const char* p = text.data();
  const char* const end = p + text.size();
  while (end - p >= 16) {
    // Per-byte counters, emptied before they can wrap (255 steps).
    Bytes counters = {};
    const char* const stop = p + std::min<ptrdiff_t>((end - p) / 16, 255) * 16;
    for (; p != stop; p += 16) {
      Bytes bytes;
      std::memcpy(&bytes, p, 16);
      counters -= reinterpret_cast<Bytes>(bytes == newline);  // a match is -1
    }
    for (int i = 0; i < 16; ++i) count += counters[i];
  }
  for (; p != end; ++p) count += *p == '\n';
  return count;
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

// A row is looked for within this many bytes: a EuRoC row of 17-digit numbers is about 140.
constexpr int kRowWindow = 192;

// Always inlined: the templates below are compiled once per instruction set, inside the function
// that names it (ParseChunkSse2, ParseChunkAvx2).
#if defined(__GNUC__)
#define SPLINECAL_INLINE __attribute__((always_inline)) inline
#else
#define SPLINECAL_INLINE inline
#endif

// How fields are read on processors without AVX2: SSE2 (io/number_parser.h).
struct Sse2Fields {
  // One bit per byte of the 64 bytes at p: ',' or '\n'.
  static SPLINECAL_INLINE uint64_t Separators(const char* p) {
    uint64_t bits = 0;
#if defined(__SSE2__)
    const __m128i comma = _mm_set1_epi8(',');
    const __m128i newline = _mm_set1_epi8('\n');
    for (int v = 0; v < 4; ++v) {
      const __m128i bytes = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p + 16 * v));
      const __m128i found =
          _mm_or_si128(_mm_cmpeq_epi8(bytes, comma), _mm_cmpeq_epi8(bytes, newline));
      bits |= uint64_t{static_cast<uint16_t>(_mm_movemask_epi8(found))} << (16 * v);
    }
#else
    for (int i = 0; i < 64; ++i) bits |= uint64_t{p[i] == ',' || p[i] == '\n'} << i;
#endif
    return bits;
  }
  // The six readings [begins[a], ends[a]); false when one is no number.
  static SPLINECAL_INLINE bool Readings(const char* const* begins,
                                        const char* const* ends,
                                        double* values) {
    for (int a = 0; a < 6; ++a) {
      if (!ParseDecimalField(begins[a], ends[a], &values[a]) &&
          ParseNumberPrefix(begins[a], ends[a], &values[a]) != ends[a]) {
        return false;
      }
    }
    return true;
  }
};

#if defined(SPLINECAL_HAS_AVX2_PARSER)
// The same with AVX2 (io/detail/number_parser_avx2.h): the six fields' digits first, then the six
// roundings in two groups of four.
struct Avx2Fields {
  SPLINECAL_AVX2_TARGET static inline uint64_t Separators(const char* p) {
    const __m256i comma = _mm256_set1_epi8(',');
    const __m256i newline = _mm256_set1_epi8('\n');
    uint64_t bits = 0;
    for (int v = 0; v < 2; ++v) {
      const __m256i bytes = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p + 32 * v));
      const __m256i found =
          _mm256_or_si256(_mm256_cmpeq_epi8(bytes, comma), _mm256_cmpeq_epi8(bytes, newline));
      bits |= uint64_t{static_cast<uint32_t>(_mm256_movemask_epi8(found))} << (32 * v);
    }
    return bits;
  }
  SPLINECAL_AVX2_TARGET static inline bool Readings(const char* const* begins,
                                                    const char* const* ends,
                                                    double* values) {
    DecimalDigits digits[8];
    bool read[6];
    for (int a = 0; a < 6; ++a) read[a] = ReadDecimalFieldAvx2(begins[a], ends[a], &digits[a]);
    double rounded[8];
    const int open =
        RoundDecimals4(digits, rounded) | (RoundDecimals4(digits + 4, rounded + 4) << 4);
    for (int a = 0; a < 6; ++a) {
      if (read[a] && ((open >> a) & 1) == 0) {
        values[a] = rounded[a];
      } else if (!(read[a] && DecimalToDouble(digits[a].w,
                                              -static_cast<int>(digits[a].fraction_digits),
                                              digits[a].negative != 0,
                                              &values[a])) &&
                 ParseNumberPrefix(begins[a], ends[a], &values[a]) != ends[a]) {
        return false;
      }
    }
    return true;
  }
};
#endif

// The first 7 ',' or '\n' in the kRowWindow bytes at p (all readable), in order; returns how many
// were found (at most 7).
template <typename Fields>
SPLINECAL_INLINE int FindSeparators(const char* p, const char* separators[7]) {
  uint64_t words[kRowWindow / 64];
  for (int w = 0; w < kRowWindow / 64; ++w) words[w] = Fields::Separators(p + 64 * w);
  int count = 0;
  for (int w = 0; w < kRowWindow / 64 && count < 7; ++w) {
    for (uint64_t bits = words[w]; bits != 0 && count < 7; bits &= bits - 1) {
      separators[count++] = p + 64 * w + __builtin_ctzll(bits);
    }
  }
  return count;
}

// The common spelling of a row, "t,gx,gy,gz,ax,ay,az" then '\n' or "\r\n", read without a
// search for the line end: the field ends are found first (FindSeparators), then every field is
// read on its own (Fields, or ParseNumberPrefix for what that leaves). Returns the start of the
// next line, or nullptr for anything else, the first and last rows of the text included (then
// ParseRow on the trimmed line decides; for the rows accepted here both read the same numbers).
template <typename Fields>
SPLINECAL_INLINE const char* ParseCommonRow(
    const char* p, const char* end, std::string_view text, int64_t* t_ns, double* values) {
  // Fields are read right-aligned, from up to kFieldWindow + 1 bytes before their end.
  if (p - text.data() <= kFieldWindow || text.data() + text.size() - p < kRowWindow) {
    return nullptr;
  }
  const char* separators[7];
  if (FindSeparators<Fields>(p, separators) < 7 || *separators[6] != '\n' || separators[6] >= end) {
    return nullptr;
  }
  for (int k = 0; k < 6; ++k) {
    if (*separators[k] != ',') return nullptr;
  }
  if (!ParseInt64Field(p, separators[0], t_ns) &&
      ParseNumberPrefix(p, separators[0], t_ns) != separators[0]) {
    return nullptr;
  }
  const char* begins[6];
  const char* ends[6];
  for (int a = 0; a < 6; ++a) {
    begins[a] = separators[a] + 1;
    ends[a] = separators[a + 1];
  }
  if (ends[5][-1] == '\r') --ends[5];
  return Fields::Readings(begins, ends, values) ? separators[6] + 1 : nullptr;
}

// Readings within the plausibility limits, multiplied by their scales.
struct Scaling {
  double scales[6];
  double limits[6];  // in the file's unit
};

// Parses `chunk` into columns rows chunk->first_row onwards; stops at the first row that the
// TextFileReader path must judge (chunk->ok = false).
template <typename Fields>
SPLINECAL_INLINE void ParseChunk(std::string_view text,
                                 const Scaling& scaling,
                                 EurocImuColumns* columns,
                                 Chunk* chunk) {
  const char* p = chunk->text.data();
  const char* const end = p + chunk->text.size();
  int64_t row = chunk->first_row;
  // Counted in locals: chunks next to each other share cache lines, and writing them on every row
  // would have the cores fight over those lines.
  int64_t rows = 0;
  int64_t first_t_ns = 0;
  int64_t last_t_ns = 0;
  int64_t largest_step_ns = 0;
  while (p != end) {
    int64_t t_ns = 0;
    double values[6];
    const char* next = ParseCommonRow<Fields>(p, end, text, &t_ns, values);
    if (next == nullptr) {
      const char* const newline = static_cast<const char*>(std::memchr(p, '\n', end - p));
      const char* const line_end = newline != nullptr ? newline : end;
      next = newline != nullptr ? newline + 1 : end;
      const std::string_view content = DataLineContent(std::string_view(p, line_end - p));
      if (content.empty()) {
        p = next;
        continue;
      }
      if (!ParseRow(content, &t_ns, values)) {
        chunk->ok = false;
        return;
      }
    }
    if (t_ns > kMaxTimestampNs || t_ns < -kMaxTimestampNs || (rows > 0 && t_ns <= last_t_ns)) {
      chunk->ok = false;
      return;
    }
    if (rows > 0) {
      largest_step_ns = std::max(largest_step_ns, t_ns - last_t_ns);
    } else {
      first_t_ns = t_ns;
    }
    last_t_ns = t_ns;
    for (int a = 0; a < 6; ++a) {
      if (!(std::abs(values[a]) <= scaling.limits[a])) {
        chunk->ok = false;
        return;
      }
      columns->values[a][row] = scaling.scales[a] * values[a];
    }
    ++rows;
    ++row;
    p = next;
  }
  chunk->rows = rows;
  chunk->first_t_ns = first_t_ns;
  chunk->last_t_ns = last_t_ns;
  chunk->largest_step_ns = largest_step_ns;
}

void ParseChunkSse2(std::string_view text,
                    const Scaling& scaling,
                    EurocImuColumns* columns,
                    Chunk* chunk) {
  ParseChunk<Sse2Fields>(text, scaling, columns, chunk);
}

#if defined(SPLINECAL_HAS_AVX2_PARSER)
SPLINECAL_AVX2_TARGET void ParseChunkAvx2(std::string_view text,
                                          const Scaling& scaling,
                                          EurocImuColumns* columns,
                                          Chunk* chunk) {
  ParseChunk<Avx2Fields>(text, scaling, columns, chunk);
}
#endif

// Maps the pages of [data, data + bytes) for writing in one call (Linux 5.14 and later; elsewhere
// the first writes fault them in one page at a time): 480 MB of columns for 10^7 rows took 0.07 s
// less system time than 120 000 page faults. Transparent huge pages were tried and dropped: 0.15 s
// less on most runs, but up to 0.6 s more on others (2 MB pages this VM's host had to back
// first).
void Prefault(const void* data, size_t bytes) {
#if defined(MADV_POPULATE_WRITE)
  constexpr uintptr_t kPage = 4096;
  const uintptr_t begin = (reinterpret_cast<uintptr_t>(data) + kPage - 1) & ~(kPage - 1);
  const uintptr_t end = (reinterpret_cast<uintptr_t>(data) + bytes) & ~(kPage - 1);
  if (end > begin) ::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_POPULATE_WRITE);
#endif
}

// Shares of `text` of about `bytes` that end just after a newline (the last at the end). Many
// more than threads (8 MB: 170 for 1.4 GB): a thread that the scheduler holds back, the machine
// being busy with other work, then delays the others by one share, not by half the file.
std::vector<Chunk> SplitIntoChunks(std::string_view text, size_t bytes) {
  std::vector<Chunk> chunks;
  size_t begin = 0;
  while (begin < text.size()) {
    size_t end = text.size();
    if (text.size() - begin > bytes) {
      const size_t newline = text.find('\n', begin + bytes);
      if (newline != std::string_view::npos) end = newline + 1;
    }
    Chunk chunk;
    chunk.text = text.substr(begin, end - begin);
    chunks.push_back(chunk);
    begin = end;
  }
  return chunks;
}

// Closes the gaps that lines without data (comments, blank lines) left between chunks.
int64_t CloseGaps(const std::vector<Chunk>& chunks, EurocImuColumns* columns) {
  int64_t rows = 0;
  for (const Chunk& chunk : chunks) {
    if (chunk.first_row != rows && chunk.rows > 0) {
      for (std::vector<double>& values : columns->values) {
        std::memmove(values.data() + rows,
                     values.data() + chunk.first_row,
                     static_cast<size_t>(chunk.rows) * sizeof(double));
      }
    }
    rows += chunk.rows;
  }
  return rows;
}

}  // namespace

std::optional<EurocImuColumns> ReadEurocImuParallel(const std::string& path,
                                                    double gyro_scale,
                                                    double accel_scale,
                                                    const ParallelReadOptions& options) {
  const MappedFile file(path);
  std::string_view text = file.text();
  if (text.empty()) return std::nullopt;
  // Leading lines without data (the '#' header) are skipped here, so that no chunk has a gap.
  while (!text.empty()) {
    const size_t newline = text.find('\n');
    if (!DataLineContent(text.substr(0, newline)).empty()) break;
    text.remove_prefix(newline == std::string_view::npos ? text.size() : newline + 1);
  }
  const int threads = static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, 16u));
  std::vector<Chunk> chunks =
      SplitIntoChunks(text, static_cast<size_t>(std::max<int64_t>(options.share_bytes, 1)));
  const int64_t num_chunks = static_cast<int64_t>(chunks.size());
  // Pass 1: an upper bound of each chunk's rows (its newlines, plus an unterminated last line),
  // so that every chunk is parsed straight into the final arrays.
  RunTasks(threads, num_chunks, [&](int64_t i) {
    const std::string_view chunk = chunks[i].text;
    chunks[i].row_bound = CountNewlines(chunk) + (chunk.back() != '\n' ? 1 : 0);
  });
  int64_t bound = 0;
  for (Chunk& chunk : chunks) {
    chunk.first_row = bound;
    bound += chunk.row_bound;
  }
  if (bound < 2) return std::nullopt;
  EurocImuColumns columns;
  // Zeroing 6 x 8 bytes per row on both threads, the pages mapped in one call per axis.
  RunTasks(threads, 6, [&](int64_t a) {
    columns.values[a].reserve(bound);
    Prefault(columns.values[a].data(), bound * sizeof(double));
    columns.values[a].resize(bound);
  });
  Scaling scaling;
  // Limits in the file's unit, as the TextFileReader path checks them; kept finite (a tiny scale
  // would make them inf) so that they also refuse inf and nan.
  for (int a = 0; a < 6; ++a) {
    scaling.scales[a] = a < 3 ? gyro_scale : accel_scale;
    scaling.limits[a] = std::min((a < 3 ? kMaxAngularRate : kMaxAcceleration) / scaling.scales[a],
                                 std::numeric_limits<double>::max());
  }
  // Pass 2: parse.
  auto parse = &ParseChunkSse2;
#if defined(SPLINECAL_HAS_AVX2_PARSER)
  if (options.avx2 && CpuHasAvx2Parser()) parse = &ParseChunkAvx2;
#endif
  RunTasks(
      threads, num_chunks, [&](int64_t i) { parse(file.text(), scaling, &columns, &chunks[i]); });
  bool started = false;
  for (const Chunk& chunk : chunks) {
    if (!chunk.ok) return std::nullopt;
    if (chunk.rows == 0) continue;
    if (started) {
      if (chunk.first_t_ns <= columns.last_t_ns) return std::nullopt;
      columns.largest_step_ns =
          std::max(columns.largest_step_ns, chunk.first_t_ns - columns.last_t_ns);
    } else {
      columns.first_t_ns = chunk.first_t_ns;
      started = true;
    }
    columns.largest_step_ns = std::max(columns.largest_step_ns, chunk.largest_step_ns);
    columns.last_t_ns = chunk.last_t_ns;
  }
  const int64_t rows = CloseGaps(chunks, &columns);
  if (rows < 2) return std::nullopt;
  for (std::vector<double>& values : columns.values) values.resize(rows);
  return columns;
}

}  // namespace internal
}  // namespace splinecal

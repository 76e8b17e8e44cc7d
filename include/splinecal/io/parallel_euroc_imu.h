// The fast path for long EuRoC imu0/data.csv files (internal to io/; used by
// io/static_recording.h). Allan recordings last hours: at 200-1000 Hz that is 10^6-10^7 rows, up
// to 1.5 GB of text. The file is memory-mapped and split at line ends into shares of a few MB,
// which the hardware threads take one after the other (so that one thread held back by a busy
// machine does not hold the others back for long); every share is parsed straight into the final
// arrays (a first pass counts each share's line ends).
//
// A row in the common spelling ("t,gx,gy,gz,ax,ay,az" and a line end) is read field by field once
// its commas are found (io/number_parser.h, or io/detail/number_parser_avx2.h where the processor has
// AVX2); any other line goes through the TextFileReader path's primitives (io/text_file.h:
// DataLineContent, the number parser ParseNumberPrefix), with the plausibility limits
// kMaxAngularRate and kMaxAcceleration for both. Nothing here reports an error: anything unusual
// (a header row without '#', a wrong column count, a bad or implausible value, timestamps that do
// not increase, fewer than 2 rows) returns nullopt, and the caller reads the file again with
// TextFileReader, which names the line and column. Both paths give the same numbers, bit for bit.
#ifndef SPLINECAL_IO_PARALLEL_EUROC_IMU_H_
#define SPLINECAL_IO_PARALLEL_EUROC_IMU_H_

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace splinecal {
namespace internal {

struct EurocImuColumns {
  // gyro xyz [rad/s], accel xyz [m/s^2], multiplied by the scales on input.
  std::array<std::vector<double>, 6> values;
  int64_t first_t_ns = 0;
  int64_t last_t_ns = 0;
  int64_t largest_step_ns = 0;  // the longest time between consecutive rows
};

// How the file is read (tests choose; the defaults are for use).
struct ParallelReadOptions {
  int64_t share_bytes = int64_t{8} << 20;  // the size of the shares (tests make many small ones)
  bool avx2 = true;  // the AVX2 field reader where the processor has it (io/detail/number_parser_avx2.h)
};

// Readings are multiplied by gyro_scale / accel_scale (both positive) and must stay within the
// plausibility limits after scaling. nullopt also when the file cannot be mapped.
std::optional<EurocImuColumns> ReadEurocImuParallel(const std::string& path,
                                                    double gyro_scale,
                                                    double accel_scale,
                                                    const ParallelReadOptions& options = {});

}  // namespace internal
}  // namespace splinecal

#endif  // SPLINECAL_IO_PARALLEL_EUROC_IMU_H_

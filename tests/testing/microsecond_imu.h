// A copy of a real EuRoC IMU file with its timestamps in microseconds (each divided by 1000):
// the unit mistake the IMU-rate gate must catch (imu/imu_rate.h).
#ifndef SPLINECAL_TESTS_TESTING_MICROSECOND_IMU_H_
#define SPLINECAL_TESTS_TESTING_MICROSECOND_IMU_H_

#include <fstream>
#include <sstream>
#include <string>

#include "testing/temp_dir.h"

namespace splinecal {
namespace testing {

// Writes `name` into dir: `source` with every data row's first field divided by 1000.
inline std::string WriteMicrosecondImu(const TempDir& dir,
                                       const std::string& source,
                                       const std::string& name = "imu_us.csv") {
  std::ifstream in(source);
  std::ostringstream out;
  std::string line;
  while (std::getline(in, line)) {
    const size_t comma = line.find(',');
    if (line.empty() || line[0] == '#' || comma == std::string::npos) {
      out << line << "\n";
      continue;
    }
    out << std::stoll(line.substr(0, comma)) / 1000 << line.substr(comma) << "\n";
  }
  return dir.Write(name, out.str());
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_TESTING_MICROSECOND_IMU_H_

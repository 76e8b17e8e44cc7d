// How the commands' console summaries (fit, align, evaluate) show a 3-vector: "[x y z]", one
// printf conversion for the three entries, so a line's format says once how its vector is shown.
#ifndef SPLINECAL_CLI_CONSOLE_TEXT_H_
#define SPLINECAL_CLI_CONSOLE_TEXT_H_

#include <Eigen/Core>
#include <string>

namespace splinecal {
namespace cli {

// "[x y z]": each entry of v printed with `conversion`, one printf conversion of a double
// ("%.6f", "%8.4f", "%.2g"), separated by single spaces.
std::string BracketedVector(const Eigen::Vector3d& v, const char* conversion);

}  // namespace cli
}  // namespace splinecal

#endif  // SPLINECAL_CLI_CONSOLE_TEXT_H_

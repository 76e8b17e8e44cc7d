#include "splinecal/cli/console_text.h"

#include "splinecal/string_printf.h"

namespace splinecal {
namespace cli {

std::string BracketedVector(const Eigen::Vector3d& v, const char* conversion) {
  std::string text = "[";
  for (int i = 0; i < 3; ++i) {
    if (i > 0) text += ' ';
    text += StringPrintf(conversion, v[i]);
  }
  return text + "]";
}

}  // namespace cli
}  // namespace splinecal

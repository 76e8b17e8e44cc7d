// One factory per subcommand, each in src/cli/<name>_command.cc.
#ifndef SPLINECAL_CLI_COMMANDS_H_
#define SPLINECAL_CLI_COMMANDS_H_

#include "splinecal/cli/command.h"

namespace splinecal {
namespace cli {

Command EvaluateCommand();
Command SimulateCommand();
Command IntegrateCommand();
Command CorrectCommand();
Command AllanCommand();
Command AlignCommand();
Command FitCommand();
Command CalibrateCommand();
Command DetectCommand();
Command IntrinsicsCommand();
Command BagInfoCommand();
Command BagExtractCommand();
Command ExportCommand();

}  // namespace cli
}  // namespace splinecal

#endif  // SPLINECAL_CLI_COMMANDS_H_

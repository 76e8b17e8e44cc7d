// The list of subcommands, in the order `splinecal help` shows them.
#include "splinecal/cli/command.h"
#include "splinecal/cli/commands.h"

namespace splinecal {
namespace cli {

const std::vector<Command>& AllCommands() {
  static const std::vector<Command> commands = {
      SimulateCommand(),
      IntegrateCommand(),
      CorrectCommand(),
      AllanCommand(),
      EvaluateCommand(),
      AlignCommand(),
      FitCommand(),
      DetectCommand(),
      IntrinsicsCommand(),
      CalibrateCommand(),
      BagInfoCommand(),
      BagExtractCommand(),
      ExportCommand(),
  };
  return commands;
}

}  // namespace cli
}  // namespace splinecal

// The command-line front end: one binary, `splinecal`, with subcommands (docs/conventions.md,
// "Command line").
//
// Every subcommand is a Command: a name, a one-line summary, a usage line, the flags it accepts
// and a function that runs it once those flags are set. Flags are gflags flags (DEFINE_* in the
// command's own file, or in common_flags.cc when several commands share one); the front end
// parses argv itself so that every bad flag or value exits 2 with one clear line instead of
// gflags' exit 1, and so that `splinecal SUB --help` lists only SUB's flags.
//
// Flag spelling: `--imu-rate 200`, `--imu-rate=200` and `--imu_rate=200` are the same flag
// (dashes become underscores); booleans take `--flag`, `--noflag`, `--flag=true|false`.
//
// A flag means the same in every command that takes it (its unit, and what 0 or an empty value
// means); only its default may differ per command (FlagDoc::default_value). `--quiet` is taken
// by every command and is not repeated in the usage lines.
#ifndef SPLINECAL_CLI_COMMAND_H_
#define SPLINECAL_CLI_COMMAND_H_

#include <string>
#include <utility>
#include <vector>

namespace splinecal {
namespace cli {

struct FlagDoc {
  // Implicit, so that a command lists its flags as {"name", "help"} or {"name", "help", "0.05"}.
  FlagDoc(std::string name, std::string help = "", std::string default_value = "")
      : name(std::move(name)), help(std::move(help)), default_value(std::move(default_value)) {}

  // The gflags name, with underscores (`imu_rate`); shown with dashes unless it is a Kalibr key.
  std::string name;
  // Help text for this command; empty means the flag's gflags description. Give the unit.
  std::string help;
  // This command's default, when it differs from the DEFINE_* default (e.g. --knot-spacing:
  // 0.05 s in calibrate, 0 = from the data in fit). ParseFlags sets it before parsing and
  // --help shows it.
  std::string default_value;
};

struct Command {
  std::string name;
  std::string summary;         // one line, for `splinecal help`
  std::string usage;           // every flag of `flags` but --quiet, e.g. "splinecal fit ..."
  std::string description;     // a paragraph for `splinecal SUB --help`
  std::vector<FlagDoc> flags;  // every flag the command accepts
  // Runs the command after its flags were set. Throws splinecal::Error for bad input (the front
  // end prints it on one line and exits 2). Returns the exit code.
  int (*run)();
  // The input stage run() begins with: reads every file the flags name and checks them and the
  // flags, up to the point where the heavy work (a solve, a simulation) would start. Writes
  // nothing. Throws splinecal::Error exactly as run() would; the fuzz targets (tests/fuzz/) call
  // it on every input, since a whole run per input would be far too slow.
  void (*read_inputs)();
  // The string flag that collects arguments without a leading '-' (comma-joined), for commands
  // that take files as `splinecal bag info A.bag B.bag`; empty: such arguments are refused.
  std::string positional_flag = "";
};

// Every command, in the order `splinecal help` lists them (src/cli/commands.cc). A name of two
// words ("bag info") is a command group: `splinecal bag info ...` runs it.
const std::vector<Command>& AllCommands();

// The whole front end: dispatch, flag parsing, error reporting. Returns the process exit code.
int Main(int argc, char** argv);

// Sets the gflags values of `args` (the arguments after the command name), accepting only the
// command's flags, after setting each of them to the command's default (FlagDoc::default_value,
// else its DEFINE_* default) with gflags' SET_FLAGS_DEFAULT: a flag the arguments do not set
// still reads as not given (CommandLineFlagInfo::is_default). Returns false and fills `error`
// on the first problem; sets `help` when --help was asked for.
bool ParseFlags(const Command& command,
                const std::vector<std::string>& args,
                bool* help,
                std::string* error);

// Progress for long work goes to stderr through this, and nowhere when --quiet is set.
void Progress(const std::string& line);
bool Quiet();

}  // namespace cli
}  // namespace splinecal

#endif  // SPLINECAL_CLI_COMMAND_H_

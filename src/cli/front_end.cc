// splinecal's command-line front end: dispatch, flag parsing, help and the one error report.
#include <gflags/gflags.h>
#include <glog/logging.h>

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <new>
#include <set>
#include <string>
#include <vector>

#include "splinecal/cli/command.h"
#include "splinecal/cli/common_flags.h"
#include "splinecal/error.h"
#include "splinecal/memory_reuse.h"
#include "splinecal/string_printf.h"

#ifndef SPLINECAL_VERSION
#define SPLINECAL_VERSION "unknown"
#endif

namespace splinecal {
namespace cli {
namespace {

constexpr int kExitBadInput = 2;

// Kalibr's noise keys keep their underscores on the command line, as Kalibr spells them.
std::string DisplayName(const std::string& name) {
  if (name.rfind("gyroscope_", 0) == 0 || name.rfind("accelerometer_", 0) == 0) return name;
  std::string display = name;
  for (char& c : display) {
    if (c == '_') c = '-';
  }
  return display;
}

std::string FlagName(std::string text) {
  for (char& c : text) {
    if (c == '-') c = '_';
  }
  return text;
}

const Command* FindCommand(const std::string& name) {
  for (const Command& command : AllCommands()) {
    if (command.name == name) return &command;
  }
  return nullptr;
}

// The DEFINE_* default of every flag, read once before any command set its own defaults.
const std::map<std::string, std::string>& DefinedDefaults() {
  static const std::map<std::string, std::string>* const defaults = [] {
    auto* map = new std::map<std::string, std::string>;
    std::vector<gflags::CommandLineFlagInfo> flags;
    gflags::GetAllFlags(&flags);
    for (const gflags::CommandLineFlagInfo& info : flags) (*map)[info.name] = info.default_value;
    return map;
  }();
  return *defaults;
}

// The flag's default in this command.
std::string CommandDefault(const FlagDoc& flag) {
  if (!flag.default_value.empty()) return flag.default_value;
  const auto found = DefinedDefaults().find(flag.name);
  return found == DefinedDefaults().end() ? "" : found->second;
}

std::vector<FlagDoc> AcceptedFlags(const Command& command) {
  std::vector<FlagDoc> flags = command.flags;
  bool has_quiet = false;
  for (const FlagDoc& flag : flags) has_quiet = has_quiet || flag.name == "quiet";
  if (!has_quiet) flags.push_back({"quiet", ""});
  return flags;
}

void PrintGeneralHelp(std::FILE* out) {
  std::fprintf(out,
               "splinecal %s: continuous-time spline calibration of visual-inertial rigs\n\n"
               "usage: splinecal COMMAND [--flag value ...]\n\ncommands:\n",
               SPLINECAL_VERSION);
  for (const Command& command : AllCommands()) {
    std::fprintf(out, "  %-10s %s\n", command.name.c_str(), command.summary.c_str());
  }
  std::fprintf(out, "  %-10s %s\n", "help", "this list; 'splinecal help COMMAND' for a command");
  std::fprintf(out, "  %-10s %s\n", "version", "print the version");
  std::fprintf(out, "\nEvery command takes --quiet (no progress on stderr).\n");
  std::fprintf(out, "Bad input exits with code 2 and one line naming the file and line.\n");
}

void PrintCommandHelp(const Command& command, std::FILE* out) {
  std::fprintf(out,
               "usage: %s\n\n%s\n\n%s\n\nflags:\n",
               command.usage.c_str(),
               command.summary.c_str(),
               command.description.c_str());
  for (const FlagDoc& flag : AcceptedFlags(command)) {
    gflags::CommandLineFlagInfo info;
    if (!gflags::GetCommandLineFlagInfo(flag.name.c_str(), &info)) continue;
    const std::string& help = flag.help.empty() ? info.description : flag.help;
    const std::string default_value = CommandDefault(flag);
    std::string default_text;
    if (info.type == "string") {
      default_text = default_value.empty() ? "" : " (default: " + default_value + ")";
    } else if (info.type == "double") {
      // gflags prints 17 digits (9.8100000000000005); show the value as typed.
      default_text = StringPrintf(" (default: %.10g)", std::strtod(default_value.c_str(), nullptr));
    } else {
      default_text = " (default: " + default_value + ")";
    }
    std::fprintf(out,
                 "  --%s\n      %s%s\n",
                 DisplayName(flag.name).c_str(),
                 help.c_str(),
                 default_text.c_str());
  }
}

}  // namespace

bool ParseFlags(const Command& command,
                const std::vector<std::string>& args,
                bool* help,
                std::string* error) {
  std::set<std::string> accepted;
  for (const FlagDoc& flag : AcceptedFlags(command)) {
    accepted.insert(flag.name);
    // The command's default, as gflags' default: the flag still reads as not given.
    const std::string set = gflags::SetCommandLineOptionWithMode(
        flag.name.c_str(), CommandDefault(flag).c_str(), gflags::SET_FLAGS_DEFAULT);
    CHECK(!set.empty()) << "bad default '" << CommandDefault(flag) << "' of --" << flag.name;
  }
  std::string positional;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (arg == "--help" || arg == "-h" || arg == "-help") {
      *help = true;
      return true;
    }
    if (!command.positional_flag.empty() && !arg.empty() && arg[0] != '-') {
      positional += (positional.empty() ? "" : ",") + arg;
      continue;
    }
    if (arg.size() < 2 || arg[0] != '-') {
      *error = "unexpected argument '" + arg + "' (flags are written --name value)";
      return false;
    }
    const std::string body = arg.substr(arg[1] == '-' ? 2 : 1);
    const size_t equals = body.find('=');
    std::string name = FlagName(body.substr(0, equals));
    const bool has_value = equals != std::string::npos;
    std::string value = has_value ? body.substr(equals + 1) : "";
    gflags::CommandLineFlagInfo info;
    bool known = accepted.count(name) > 0 && gflags::GetCommandLineFlagInfo(name.c_str(), &info);
    if (!known && name.rfind("no", 0) == 0 && !has_value && accepted.count(name.substr(2)) > 0 &&
        gflags::GetCommandLineFlagInfo(name.substr(2).c_str(), &info) && info.type == "bool") {
      name = name.substr(2);
      value = "false";
      known = true;
    } else if (known && info.type == "bool" && !has_value) {
      value = "true";
    } else if (known && !has_value) {
      if (i + 1 >= args.size()) {
        *error = "flag --" + DisplayName(name) + " needs a value";
        return false;
      }
      value = args[++i];
    }
    if (!known) {
      *error = "unknown flag '" + arg + "' (see 'splinecal " + command.name + " --help')";
      return false;
    }
    if (gflags::SetCommandLineOption(name.c_str(), value.c_str()).empty()) {
      *error = "flag --" + DisplayName(name) + ": '" + value + "' is not a valid " + info.type;
      return false;
    }
  }
  if (!positional.empty()) {
    gflags::CommandLineFlagInfo info;
    gflags::GetCommandLineFlagInfo(command.positional_flag.c_str(), &info);
    if (!info.is_default) positional = info.current_value + "," + positional;
    gflags::SetCommandLineOption(command.positional_flag.c_str(), positional.c_str());
  }
  return true;
}

bool Quiet() { return FLAGS_quiet; }

void Progress(const std::string& line) {
  if (!FLAGS_quiet) std::fprintf(stderr, "%s\n", line.c_str());
}

int Main(int argc, char** argv) {
  KeepFreedMemoryForReuse();  // splinecal/memory_reuse.h: each page faulted once
  FLAGS_logtostderr = true;
  google::InitGoogleLogging(argc > 0 ? argv[0] : "splinecal");
  std::vector<std::string> args(argv + (argc > 0 ? 1 : 0), argv + argc);
  // A command group ("bag info"): its two words are the command's name.
  if (args.size() >= 2 && FindCommand(args[0]) == nullptr &&
      FindCommand(args[0] + " " + args[1]) != nullptr) {
    args[1] = args[0] + " " + args[1];
    args.erase(args.begin());
  }
  if (args.size() >= 3 && (args[0] == "help" || args[0] == "--help" || args[0] == "-h") &&
      FindCommand(args[1] + " " + args[2]) != nullptr) {
    args[2] = args[1] + " " + args[2];
    args.erase(args.begin() + 1);
  }
  if (args.empty()) {
    PrintGeneralHelp(stderr);
    return kExitBadInput;
  }
  const std::string& name = args[0];
  if (name == "help" || name == "--help" || name == "-h") {
    if (args.size() < 2) {
      PrintGeneralHelp(stdout);
      return 0;
    }
    const Command* command = FindCommand(args[1]);
    if (command == nullptr) {
      std::fprintf(
          stderr, "splinecal: unknown command '%s' (see 'splinecal help')\n", args[1].c_str());
      return kExitBadInput;
    }
    PrintCommandHelp(*command, stdout);
    return 0;
  }
  if (name == "version" || name == "--version") {
    std::printf("splinecal %s\n", SPLINECAL_VERSION);
    return 0;
  }
  const Command* command = FindCommand(name);
  if (command == nullptr) {
    std::fprintf(stderr, "splinecal: unknown command '%s' (see 'splinecal help')\n", name.c_str());
    return kExitBadInput;
  }
  bool help = false;
  std::string error;
  if (!ParseFlags(
          *command, std::vector<std::string>(args.begin() + 1, args.end()), &help, &error)) {
    std::fprintf(stderr, "splinecal %s: %s\n", name.c_str(), error.c_str());
    return kExitBadInput;
  }
  if (help) {
    PrintCommandHelp(*command, stdout);
    return 0;
  }
  try {
    return command->run();
  } catch (const Error& e) {
    std::fprintf(stderr, "splinecal %s: %s\n", name.c_str(), e.what());
    return kExitBadInput;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "splinecal %s: out of memory (input too large?)\n", name.c_str());
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "splinecal %s: internal error: %s\n", name.c_str(), e.what());
    return 1;
  }
}

}  // namespace cli
}  // namespace splinecal

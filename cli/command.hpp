#pragma once
/// Subcommand registry of the `ablmg` program. Each cmd_*.cpp registers itself:
///
///   static int runStats(const std::vector<std::string>& args);
///   ABLMG_COMMAND("stats", "quality report of a mesh", runStats)
///
/// `args` excludes the program and subcommand names. A command returns the exit code; it
/// may throw ablmg::Error, which main() turns into one stderr line and exit code 1.
#include <string>
#include <vector>

namespace ablmg::cli {

using CommandFn = int (*)(const std::vector<std::string>& args);
struct Command {
  const char* name;
  const char* summary;
  CommandFn run;
};
bool registerCommand(const Command& c);
const std::vector<Command>& commands();

}  // namespace ablmg::cli

#define ABLMG_CONCAT2(a, b) a##b
#define ABLMG_CONCAT(a, b) ABLMG_CONCAT2(a, b)
#define ABLMG_COMMAND(name, summary, fn) \
  static const bool ABLMG_CONCAT(ablmg_registered_, __LINE__) = ::ablmg::cli::registerCommand({name, summary, fn});

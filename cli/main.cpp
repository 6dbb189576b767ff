// ablmg: command-line front end. Parses the subcommand, runs it, and turns any ablmg::Error
// (or other exception) into one line on stderr and exit code 1. Libraries never print.
#include "cli/command.hpp"
#include "core/error.hpp"

#include <algorithm>
#include <cstring>
#include <exception>
#include <iostream>

namespace ablmg::cli {

static std::vector<Command>& registry() {
  static std::vector<Command> r;
  return r;
}
bool registerCommand(const Command& c) {
  registry().push_back(c);
  return true;
}
const std::vector<Command>& commands() {
  auto& r = registry();
  std::sort(r.begin(), r.end(), [](const Command& a, const Command& b) { return std::strcmp(a.name, b.name) < 0; });
  return r;
}

} // namespace ablmg::cli

static void usage(std::ostream& os) {
  os << "usage: ablmg <command> [options]   (ablmg <command> --help for details)\n\ncommands:\n";
  for (const auto& c : ablmg::cli::commands()) os << "  " << c.name << std::string(10 - std::min<size_t>(9, std::strlen(c.name)), ' ') << c.summary << "\n";
}

int main(int argc, char** argv) {
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
    usage(argc < 2 ? std::cerr : std::cout);
    return argc < 2 ? 2 : 0;
  }
  const std::string name = argv[1];
  for (const auto& c : ablmg::cli::commands()) {
    if (name != c.name) continue;
    try {
      return c.run(std::vector<std::string>(argv + 2, argv + argc));
    } catch (const ablmg::Error& e) {
      std::cerr << "ablmg " << name << ": error: " << e.what() << "\n";
      return 1;
    } catch (const std::bad_alloc&) {
      std::cerr << "ablmg " << name << ": error: out of memory\n";
      return 1;
    } catch (const std::exception& e) {
      std::cerr << "ablmg " << name << ": error: " << e.what() << "\n";
      return 1;
    }
  }
  std::cerr << "ablmg: unknown command '" << name << "'\n";
  usage(std::cerr);
  return 2;
}

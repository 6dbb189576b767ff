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

/// Output size (triangles) from which a command runs itself again under glibc's huge-page heap.
inline constexpr double kHugePageHeapTriangles = 2e5;

/// For a command about to build a mesh of ≈ expectedTriangles (≥ kHugePageHeapTriangles):
/// runs the program again, same arguments, with
/// GLIBC_TUNABLES=glibc.malloc.hugetlb=1:glibc.malloc.mmap_threshold=4194304 (every heap
/// growth and large block advised for transparent huge pages: one page fault per 2 MB instead
/// of per 4 KB; the 10⁶-triangle refinement's meshing 1.38–1.76 → 1.20–1.46 s at the same
/// peak, docs/experiments.md "glibc's huge-page heap for large outputs"; the meshes are the
/// same). glibc reads tunables only at start-up, hence the new run, which costs the start-up
/// (≈ 40 ms) and the input's reading again: below the threshold the gain is smaller than that
/// and the run goes on as it is. Returns without doing anything when GLIBC_TUNABLES is set (the
/// user's choice, empty included: `GLIBC_TUNABLES= ablmg …` keeps one run) or the new run
/// cannot start. Call it before anything is printed or written: the new run repeats it.
void rerunWithHugePageHeapIfLarge(double expectedTriangles);

}  // namespace ablmg::cli

#define ABLMG_CONCAT2(a, b) a##b
#define ABLMG_CONCAT(a, b) ABLMG_CONCAT2(a, b)
#define ABLMG_COMMAND(name, summary, fn) \
  static const bool ABLMG_CONCAT(ablmg_registered_, __LINE__) = ::ablmg::cli::registerCommand({name, summary, fn});

// ablmg: command-line front end. Parses the subcommand, runs it, and turns any ablmg::Error
// (or other exception) into one line on stderr and exit code 1. Libraries never print.
#include "ablmg/cli/command.hpp"
#include "ablmg/core/error.hpp"

#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>

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

}  // namespace ablmg::cli

static void usage(std::ostream& os) {
  os << "usage: ablmg <command> [options]   (ablmg <command> --help for details)\n\ncommands:\n";
  for (const auto& c : ablmg::cli::commands())
    os << "  " << c.name << std::string(10 - std::min<size_t>(9, std::strlen(c.name)), ' ') << c.summary << "\n";
}

/// Threads of this process that are running now (OpenBLAS, pulled in by CHOLMOD, starts its
/// own pool when it is loaded, before main()).
static int ownRunningThreads() {
  int running = 0;
  std::error_code ec;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task", ec)) {
    std::ifstream stat(task.path() / "stat");
    std::string line;
    std::getline(stat, line);
    const auto close = line.rfind(')');  // "pid (comm) S ...": the state follows the name
    if (close != std::string::npos && close + 2 < line.size() && line[close + 2] == 'R') ++running;
  }
  return std::max(running, 1);
}

/// Runnable tasks on the machine besides this process's: the smallest of three samples of
/// /proc/stat's procs_running 1 ms apart, so that a passing task is not taken for load; 0 when
/// /proc/stat cannot be read. A sample that shows none ends it (the smallest is then 0), so
/// an idle machine costs one read and no waiting.
static int otherRunnableTasks() {
  int fewest = 1 << 30;
  for (int sample = 0; sample < 3 && fewest > 0; ++sample) {
    if (sample > 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    std::ifstream stat("/proc/stat");
    std::ostringstream text;  // one read; the interrupt line before procs_running has ~10³ words
    text << stat.rdbuf();
    const std::string s = text.str();
    const auto at = s.find("\nprocs_running ");
    const int running = at == std::string::npos ? -1 : std::atoi(s.c_str() + at + 15);
    if (running < 1) return 0;
    fewest = std::min(fewest, running - ownRunningThreads());
  }
  return std::max(fewest, 0);
}

/// OpenMP threads busy-wait at every barrier by default (libgomp spins ~3·10⁵ times before it
/// sleeps), which is fastest on an idle machine but slow when other processes want the cores:
/// a 8·10⁴-triangle remesh (bench_remesh.sh's ring, 2 cores) took 0.55 s idle, 1.5 s beside one
/// busy process and up to 9 s beside a parallel build, against 0.60 / 0.8 s with passive waits.
/// libgomp reads OMP_WAIT_POLICY once, before main(), so when other tasks are running and the
/// user has set neither OMP_WAIT_POLICY nor GOMP_SPINCOUNT, the process sets
/// OMP_WAIT_POLICY=PASSIVE and runs itself again (once: the second run sees the variable).
/// Results do not depend on it (every parallel region gives the same bits for any schedule).
static void avoidBusyWaitingUnderLoad(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT")) return;
  if (otherRunnableTasks() == 0) return;
  setenv("OMP_WAIT_POLICY", "PASSIVE", 1);
  execv("/proc/self/exe", argv);  // returns only on failure: carry on with busy waits
  unsetenv("OMP_WAIT_POLICY");
}

/// glibc serves a request below its mmap threshold from the heap, and raises the threshold to
/// the size of every mmapped block freed (up to 32 MB): past the first freed array of 10⁶
/// triangles, every array of a remesh lives in the heap, where freed blocks between live ones
/// stay resident. A fixed 4 MB threshold gives the large arrays back on free (the 10⁶-triangle
/// refinement of bench_remesh.sh: peak 231–252 → 196–198 MB; 1 MB cost 0.8 CPU s of page faults).
/// The price is a fresh mapping, page faults included, for every large array: 1.8·10⁵ faults
/// against 0.7·10⁵ in that refinement, 0.6–0.9 s of its 2.1–2.7 s on a virtual machine whose
/// faults cost ≈ 6 µs (huge_pages.cpp takes most of it back: one fault per 2 MB of a large
/// block). So only the commands that build one large mesh and exit (mesh, remesh, surface),
/// where the peak is what a user runs out of, fix the threshold; the loops (adapt,
/// transient), which allocate the same arrays again every cycle, and solve and stats keep
/// glibc's own policy (the tanh layer's loop to 1.1·10⁵ vertices: 1.78·10⁵ → 0.4–0.5·10⁵ faults,
/// 10.9 → 8.2–9.3 s wall, peak 115 → 132–144 MB). The user's GLIBC_TUNABLES still win: mallopt
/// is skipped then.
static void keepLargeArraysMapped() {
  if (std::getenv("GLIBC_TUNABLES")) return;
  mallopt(M_MMAP_THRESHOLD, 4 << 20);
}

/// The program's arguments, for the commands that run it again (rerunWithHugePageHeapIfLarge).
static char** programArguments = nullptr;

void ablmg::cli::rerunWithHugePageHeapIfLarge(double expectedTriangles) {
  if (!(expectedTriangles >= kHugePageHeapTriangles) || !programArguments || std::getenv("GLIBC_TUNABLES")) return;
  std::cout.flush();
  std::cerr.flush();
  setenv("GLIBC_TUNABLES", "glibc.malloc.hugetlb=1:glibc.malloc.mmap_threshold=4194304", 1);
  execv("/proc/self/exe", programArguments);  // returns only on failure: carry on in this run
  unsetenv("GLIBC_TUNABLES");
}

int main(int argc, char** argv) {
  programArguments = argv;
  if (argc >= 2 &&
      (!std::strcmp(argv[1], "mesh") || !std::strcmp(argv[1], "remesh") || !std::strcmp(argv[1], "surface")))
    keepLargeArraysMapped();
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
    usage(argc < 2 ? std::cerr : std::cout);
    return argc < 2 ? 2 : 0;
  }
  avoidBusyWaitingUnderLoad(argv);
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

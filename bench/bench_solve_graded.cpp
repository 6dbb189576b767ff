// Benchmark: the P1 solve (ordering + CHOLMOD factorisation + triangular solves) at ≈ 10⁵
// unknowns on a uniform mesh and on two adapted ones, with each fill-reducing ordering, to
// show whether the solve depends on the grading. Not a test: run by hand,
//   bash scripts/make_bench_meshes.sh              # the adapted meshes (not committed)
//   ./build/bench/bench_solve_graded --benchmark_counters_tabular=true
// Meshes: uniform = fem::unitSquareMesh(317) (99 856 unknowns); wavefront, tanhlayer = the
// last cycle (≈ 9.5·10⁴ vertices) of `ablmg adapt --problem P` with the vertex schedule of
// scripts/make_bench_meshes.sh, read from $ABLMG_BENCH_MESHES (default
// bench/results/graded_meshes). uniform1M = unitSquareMesh(1001), assembly included.
// Counters: unknowns, factor non-zeros (lnz), factorisation flops (CHOLMOD's fl: the
// load-independent measure), ordering seconds; the error of the solution so that a fast
// wrong answer shows. BM_Solve times the solves after a first one, reported apart (t_first):
// run each mesh in a process of its own (--benchmark_filter='BM_Solve/M/') for t_first to be
// the first solve of a fresh process, as scripts/bench_solve.sh does. BM_Analyse (by hand:
// --benchmark_filter=BM_Analyse): each ordering's factor non-zeros and flops on the 10⁵ and
// 10⁶ uniform grids, without factorising.
#include "ablmg/fem/assemble.hpp"
#include "ablmg/fem/solve.hpp"
#include "ablmg/fem/structured_mesh.hpp"
#include "ablmg/fem/test_problems.hpp"
#include "ablmg/io/medit.hpp"

#include <Eigen/CholmodSupport>
#include <benchmark/benchmark.h>
#include <cholmod.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>
#include <string>

using namespace ablmg;
using namespace ablmg::fem;

namespace {

const char* const kMeshes[] = {"uniform", "wavefront", "tanhlayer", "uniform1M"};

struct Case {
  Mesh2 mesh;
  TestProblem problem;
  LinearSystem system;
};

/// The mesh and its assembled system, made once per process.
const Case& caseOf(int index) {
  static std::map<int, Case> cache;
  auto it = cache.find(index);
  if (it != cache.end()) return it->second;
  const std::string name = kMeshes[index];
  Case c;
  if (name == "uniform" || name == "uniform1M") {
    c.mesh = unitSquareMesh(name == "uniform" ? 317 : 1001);
    c.problem = makeProblem("smooth");
  } else {
    const char* env = std::getenv("ABLMG_BENCH_MESHES");
    const std::filesystem::path dir = env ? env : "bench/results/graded_meshes";
    c.mesh = io::readMesh((dir / (name + ".mesh")).string());
    c.problem = makeProblem(name);
  }
  c.system = assemble(c.mesh, c.problem.poisson());
  return cache.emplace(index, std::move(c)).first->second;
}

Ordering orderingOf(int k) {
  return k == 2 ? Ordering::Metis : k == 3 ? Ordering::Cholmod : Ordering::GeometricNestedDissection;
}
const char* const kOrderings[] = {"geometric(smallest separator)", "geometric(longer axis)", "metis", "cholmod(amd)",
                                  "geometric, one factorisation"};

/// The options of ordering k (4: the default ordering, factorised whole rather than split).
SolveOptions optionsOf(int k) {
  SolveOptions options;
  options.ordering = orderingOf(k);
  options.cut = k == 1 ? CutChoice::LongerAxis : CutChoice::SmallestSeparator;
  if (k == 4) options.splitMinUnknowns = std::numeric_limits<int>::max();
  return options;
}

void phaseCounters(benchmark::State& state, const SolveStats& stats) {
  state.counters["t_order"] = stats.orderingSeconds;
  state.counters["t_symbolic"] = stats.symbolicSeconds;
  state.counters["t_numeric"] = stats.numericSeconds;
  state.counters["t_triangular"] = stats.triangularSeconds;
}

void BM_Solve(benchmark::State& state) {
  const int meshIndex = int(state.range(0)), orderingIndex = int(state.range(1));
  state.SetLabel(std::string(kMeshes[meshIndex]) + " " + kOrderings[orderingIndex]);
  const Case* c = nullptr;
  try {
    c = &caseOf(meshIndex);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  const SolveOptions options = optionsOf(orderingIndex);
  SolveStats stats;
  // The first solve, untimed by the loop: it maps the factor's pages fresh from the kernel
  // (first-touch faults), which later solves of the same size reuse. Reported apart
  // (t_first), so that every mesh's timed runs are alike whichever mesh the process ran before.
  const auto start = std::chrono::steady_clock::now();
  Eigen::VectorXd x = solveSystem(c->system, &stats, options);
  state.counters["t_first"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (auto _ : state) {
    x = solveSystem(c->system, &stats, options);
    benchmark::DoNotOptimize(x.data());
  }
  const Eigen::VectorXd u = c->system.expand(x);
  state.counters["unknowns"] = stats.unknowns;
  state.counters["lnz"] = stats.factorNonZeros;
  state.counters["GFlop"] = stats.factorFlops * 1e-9;
  phaseCounters(state, stats);
  state.counters["maxVertexError"] = (u - interpolate(c->mesh, c->problem.u)).cwiseAbs().maxCoeff();
}

/// The ordering alone (geometric, smallest separator or longer axis; METIS), for its CPU time.
void BM_Ordering(benchmark::State& state) {
  const int meshIndex = int(state.range(0)), k = int(state.range(1));
  state.SetLabel(std::string(kMeshes[meshIndex]) + " " + kOrderings[k]);
  const LinearSystem& sys = caseOf(meshIndex).system;
  for (auto _ : state) {
    std::vector<int> perm =
        k == 2 ? metisNestedDissection(sys.A)
               : geometricNestedDissection(sys.A, sys.dofPoints, 500,
                                           k == 1 ? CutChoice::LongerAxis : CutChoice::SmallestSeparator);
    benchmark::DoNotOptimize(perm.data());
  }
}

/// Ordering + CHOLMOD's symbolic analysis, no numeric factorisation: the factor's non-zeros and
/// flops of each ordering of one whole factorisation (CHOLMOD's etree postorder on), where METIS
/// and NESDIS take seconds at 10⁶ unknowns. Ordering k: 0 ours (default cuts), 1 METIS_NodeND,
/// 2 CHOLMOD's NESDIS (its ordering runs inside the analysis). CPU: the process, both threads.
void BM_Analyse(benchmark::State& state) {
  const int meshIndex = int(state.range(0)), k = int(state.range(1));
  const char* const names[] = {"geometric(smallest separator)", "metis", "cholmod nesdis"};
  state.SetLabel(std::string(kMeshes[meshIndex]) + " " + names[k]);
  Eigen::SparseMatrix<double> A = caseOf(meshIndex).system.A;
  const std::vector<Vec2>& points = caseOf(meshIndex).system.dofPoints;
  cholmod_common c;
  cholmod_start(&c);
  c.print = 0;
  c.nmethods = 1;
  c.method[0].ordering = k == 2 ? CHOLMOD_NESDIS : CHOLMOD_GIVEN;
  A.makeCompressed();
  cholmod_sparse v = Eigen::viewAsCholmod(Eigen::Ref<Eigen::SparseMatrix<double>>(A));  // no copy
  v.stype = -1;                                                                         // the lower triangle is read
  for (auto _ : state) {
    std::vector<int> perm = k == 0   ? geometricNestedDissection(A, points)
                            : k == 1 ? metisNestedDissection(A)
                                     : std::vector<int>();
    cholmod_factor* L = cholmod_analyze_p(&v, perm.empty() ? nullptr : perm.data(), nullptr, 0, &c);
    if (!L) state.SkipWithError("cholmod_analyze failed");
    cholmod_free_factor(&L, &c);
  }
  state.counters["unknowns"] = double(A.rows());
  state.counters["lnz"] = c.lnz;
  state.counters["GFlop"] = c.fl * 1e-9;
  cholmod_finish(&c);
}

/// Assembly + solve at 10⁶ unknowns (uniform), the default ordering (argument 0) or the
/// default ordering factorised whole (argument 4).
void BM_AssembleAndSolve1M(benchmark::State& state) {
  const Mesh2 mesh = unitSquareMesh(1001);
  const PoissonProblem p = makeProblem("smooth").poisson();
  const SolveOptions options = optionsOf(int(state.range(0)));
  state.SetLabel(kOrderings[state.range(0)]);
  PoissonSolution s;
  for (auto _ : state) {
    s = solvePoisson(mesh, p, options);
    benchmark::DoNotOptimize(s.u.data());
  }
  state.counters["unknowns"] = s.stats.unknowns;
  state.counters["t_assembly"] = s.stats.assemblySeconds;
  phaseCounters(state, s.stats);
  state.counters["t_solve"] = s.stats.solveSeconds;
  state.counters["GFlop"] = s.stats.factorFlops * 1e-9;
}

}  // namespace

BENCHMARK(BM_Solve)
    ->ArgsProduct({{0, 1, 2}, {0, 4, 1, 2, 3}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(3);
BENCHMARK(BM_Ordering)->ArgsProduct({{0, 1, 2, 3}, {0, 1, 2}})->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK(BM_Analyse)
    ->ArgsProduct({{0, 3}, {0, 1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime()
    ->Iterations(1);
BENCHMARK(BM_AssembleAndSolve1M)->Arg(0)->Arg(4)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK_MAIN();

// Benchmark: P1 Poisson assembly + CHOLMOD solve time against unknowns,
// 10⁴ … 10⁶, on a uniform mesh of the unit square ("smooth" manufactured solution, exact
// Dirichlet data, load by the degree-5 rule). Not a test: run by hand,
//   ./bench/bench_poisson --benchmark_counters_tabular=true
// Counters: unknowns, nonzeros, and the error so that a fast wrong answer would show.
#include "ablmg/fem/assemble.hpp"
#include "ablmg/fem/error_norms.hpp"
#include "ablmg/fem/solve.hpp"
#include "ablmg/fem/structured_mesh.hpp"
#include "ablmg/fem/test_problems.hpp"

#include <benchmark/benchmark.h>

#include <cmath>

using namespace ablmg;
using namespace ablmg::fem;

namespace {

/// n × n cells: (n − 1)² unknowns; n = 101, 317, 1001 give ≈ 10⁴, 10⁵, 10⁶.
const Mesh2& meshOf(int n) {
  static std::map<int, Mesh2> cache;
  auto it = cache.find(n);
  if (it == cache.end()) it = cache.emplace(n, unitSquareMesh(n)).first;
  return it->second;
}

void BM_Assemble(benchmark::State& state) {
  const Mesh2& m = meshOf(int(state.range(0)));
  const PoissonProblem p = makeProblem("smooth").poisson();
  LinearSystem sys;
  for (auto _ : state) {
    sys = assemble(m, p);
    benchmark::DoNotOptimize(sys.b.data());
  }
  state.counters["unknowns"] = double(sys.A.rows());
  state.counters["nonzeros"] = double(sys.A.nonZeros());
}

void BM_Solve(benchmark::State& state) {
  const Mesh2& m = meshOf(int(state.range(0)));
  const LinearSystem sys = assemble(m, makeProblem("smooth").poisson());
  for (auto _ : state) {
    Eigen::VectorXd x = solveSystem(sys);
    benchmark::DoNotOptimize(x.data());
  }
  state.counters["unknowns"] = double(sys.A.rows());
}

void BM_AssembleAndSolve(benchmark::State& state) {
  const Mesh2& m = meshOf(int(state.range(0)));
  const TestProblem tp = makeProblem("smooth");
  const PoissonProblem p = tp.poisson();
  PoissonSolution s;
  for (auto _ : state) {
    s = solvePoisson(m, p);
    benchmark::DoNotOptimize(s.u.data());
  }
  state.counters["unknowns"] = s.stats.unknowns;
  state.counters["nonzeros"] = double(s.stats.nonZeros);
  state.counters["t_assembly"] = s.stats.assemblySeconds;
  state.counters["t_solve"] = s.stats.solveSeconds;
  state.counters["maxVertexError"] = (s.u - interpolate(m, tp.u)).cwiseAbs().maxCoeff();
}

}  // namespace

BENCHMARK(BM_Assemble)->Arg(101)->Arg(317)->Arg(1001)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Solve)->Arg(101)->Arg(317)->Arg(1001)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_AssembleAndSolve)
    ->Arg(101)
    ->Arg(317)
    ->Arg(1001)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1)
    ->Repetitions(1);
BENCHMARK_MAIN();

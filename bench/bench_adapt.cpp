// Benchmarks of the adapt/ phases that do not need the mesher: Hessian recovery (both
// methods), metric construction at a target complexity, gradation — on a perturbed uniform
// mesh of the unit square carrying the wave-front solution's nodal interpolant.
//   bench_adapt --benchmark_filter=Recovery
#include "ablmg/adapt/gradation.hpp"
#include "ablmg/adapt/hessian_recovery.hpp"
#include "ablmg/adapt/metric_from_hessian.hpp"
#include "ablmg/fem/error_norms.hpp"
#include "ablmg/fem/structured_mesh.hpp"
#include "ablmg/fem/test_problems.hpp"

#include <benchmark/benchmark.h>

using namespace ablmg;

namespace {
struct Setup {
  Mesh2 mesh;
  std::vector<double> u;
  explicit Setup(int n) : mesh(fem::unitSquareMesh(n, 0.15, 1)) {
    const auto p = fem::makeProblem("wavefront");
    const Eigen::VectorXd v = fem::interpolate(mesh, p.u);
    u.assign(v.data(), v.data() + v.size());
  }
};

void recovery(benchmark::State& state, adapt::HessianMethod method) {
  const Setup s(int(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(adapt::recoverHessians(s.mesh, s.u, method));
  state.counters["vertices"] = s.mesh.numVertices();
  state.SetItemsProcessed(state.iterations() * s.mesh.numVertices());
}
void BM_RecoveryLsq(benchmark::State& state) { recovery(state, adapt::HessianMethod::LeastSquares); }
void BM_RecoveryDouble(benchmark::State& state) { recovery(state, adapt::HessianMethod::DoubleRecovery); }

void BM_MetricFromHessians(benchmark::State& state) {
  const Setup s(int(state.range(0)));
  const auto h = adapt::recoverHessians(s.mesh, s.u, adapt::HessianMethod::LeastSquares);
  adapt::MetricOptions o;
  o.targetVertices = double(s.mesh.numVertices());
  for (auto _ : state) benchmark::DoNotOptimize(adapt::metricFromHessians(s.mesh, h, o));
  state.SetItemsProcessed(state.iterations() * s.mesh.numVertices());
}

void BM_Gradation(benchmark::State& state) {
  const Setup s(int(state.range(0)));
  const auto h = adapt::recoverHessians(s.mesh, s.u, adapt::HessianMethod::LeastSquares);
  adapt::MetricOptions o;
  o.targetVertices = double(s.mesh.numVertices());
  const auto m = adapt::metricFromHessians(s.mesh, h, o);
  for (auto _ : state) {
    auto copy = m;
    const auto stats = adapt::limitGradation(s.mesh, copy, {1.3});
    state.counters["sweeps"] = stats.sweeps;
    benchmark::DoNotOptimize(copy);
  }
  state.SetItemsProcessed(state.iterations() * s.mesh.numVertices());
}
}  // namespace

BENCHMARK(BM_RecoveryLsq)->Arg(100)->Arg(316)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RecoveryDouble)->Arg(100)->Arg(316)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MetricFromHessians)->Arg(100)->Arg(316)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Gradation)->Arg(100)->Arg(316)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();

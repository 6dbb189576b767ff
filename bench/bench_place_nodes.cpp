// Benchmark: bubble node placement time against node count, 10⁴ … 10⁶,
// on the paper's radius-10 disk with its constant anisotropic metric (h1 = 2.5 h2, θ = π/4)
// scaled so that N* ≈ the requested count, plus the graded ring metric of §4.3 scaled the same
// way. Not a test: run by hand,
//   OMP_NUM_THREADS=2 ./bench/bench_place_nodes --benchmark_counters_tabular=true
// Counters: nodes, steps, awake bubble-steps, final/initial residual, time per node — so that
// a fast wrong answer (too few steps, no convergence) would show. The second argument is the
// early-stopping knob PlacementOptions::relativeTolerance in units of 1e-3: 10 (the default,
// a ×100 residual drop) and 100 (×10).
#include "ablmg/mesher/place_nodes.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <string>

using namespace ablmg;
using namespace ablmg::mesher;

namespace {

/// Sizes (h1, h2) of a constant metric with h1 = 2.5 h2 giving ≈ n nodes on the radius-10 disk.
std::pair<double, double> sizesFor(double n) {
  const double h1h2 = 2.0 / std::sqrt(3.0) * std::numbers::pi * 100.0 / n;
  const double h2 = std::sqrt(h1h2 / 2.5);
  return {2.5 * h2, h2};
}

void report(benchmark::State& state, const PlacementResult& r) {
  const auto& s = r.stats;
  state.counters["nodes"] = double(s.finalNodes);
  state.counters["predicted"] = double(s.predictedNodes);
  state.counters["steps"] = double(s.steps);
  state.counters["awake/step"] = s.steps ? double(s.activeBubbleSteps) / s.steps : 0.0;
  state.counters["res_drop"] = s.finalResidual > 0 ? s.initialResidual / s.finalResidual : 0.0;
  state.counters["s_init"] = s.secondsInitial;
  state.counters["s_dyn"] = s.secondsDynamics;
  state.counters["s_adj"] = s.secondsAdjacency;
  state.counters["s_pop"] = s.secondsPopulation;
  const double total = s.secondsInitial + s.secondsDynamics + s.secondsAdjacency + s.secondsPopulation;
  state.counters["us/node"] = 1e6 * total / double(s.finalNodes);
}

void BM_PlaceConstant(benchmark::State& state) {
  const auto [h1, h2] = sizesFor(double(state.range(0)));
  const Domain disk = Domain::disk({0, 0}, 10);
  ConstantMetricField m(Metric2::fromSizes(h1, h2, std::numbers::pi / 4));
  PlacementOptions o;
  o.relativeTolerance = state.range(1) * 1e-3;
  PlacementResult r;
  for (auto _ : state) {
    r = placeNodes(disk, m, o);
    benchmark::DoNotOptimize(r.nodes.positions.data());
  }
  report(state, r);
}

void BM_PlaceRing(benchmark::State& state) {
  // §4.3 ring metric h1 = 0.15|r − 6| + 0.2, h2 = h1/2, scaled by s so that N* ≈ range(0).
  const double s = std::sqrt(4451.0 / double(state.range(0)));
  const std::string h1 = std::to_string(s) + "*(0.15*abs(sqrt(x^2+y^2)-6)+0.2)";
  AnalyticMetricField m(AnalyticMetricField::Form::Sizes, h1, "0.5*" + h1, "0");
  const Domain disk = Domain::disk({0, 0}, 10);
  PlacementOptions o;
  o.relativeTolerance = state.range(1) * 1e-3;
  PlacementResult r;
  for (auto _ : state) {
    r = placeNodes(disk, m, o);
    benchmark::DoNotOptimize(r.nodes.positions.data());
  }
  report(state, r);
}

}  // namespace

BENCHMARK(BM_PlaceConstant)
    ->ArgsProduct({{10'000, 100'000, 1'000'000}, {10}})
    ->Args({10'000, 100})
    ->Args({100'000, 100})
    ->Unit(benchmark::kSecond)
    ->Iterations(1);
BENCHMARK(BM_PlaceRing)->ArgsProduct({{10'000, 100'000}, {10}})->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_MAIN();

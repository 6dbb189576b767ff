// Benchmark: solution transfer (adapt/transfer.hpp) between two unrelated meshes of the unit
// square with ≈ 10⁵ vertices each (perturbed structured meshes, 316² and 331² cells, different
// seeds), one and two P1 fields, interpolation and the conservative L2 projection. Not a test:
//   ./bench/bench_transfer --benchmark_counters_tabular=true
// Counters: vertices, supermesh pieces, CG iterations and the relative mass defect, so that a
// fast wrong answer would show.
#include "ablmg/adapt/transfer.hpp"
#include "ablmg/fem/structured_mesh.hpp"

#include <benchmark/benchmark.h>

#include <cmath>

using namespace ablmg;
using namespace ablmg::adapt;

namespace {

struct Setup {
  Mesh2 from = fem::unitSquareMesh(316, 0.15, 1), to = fem::unitSquareMesh(331, 0.15, 2);
  std::vector<Eigen::VectorXd> fields;
  Setup() {
    for (int f = 0; f < 2; ++f) {
      Eigen::VectorXd u(from.numVertices());
      for (int i = 0; i < from.numVertices(); ++i) {
        const Vec2& p = from.vertices[std::size_t(i)];
        u[i] = f == 0 ? std::exp(-200 * (p - Vec2(0.6, 0.4)).squaredNorm()) : std::tanh((p.x() - 0.5) / 0.01);
      }
      fields.push_back(std::move(u));
    }
  }
};
const Setup& setup() {
  static const Setup s;
  return s;
}

void run(benchmark::State& state, TransferMethod method) {
  const Setup& s = setup();
  const std::span<const Eigen::VectorXd> fields(s.fields.data(), std::size_t(state.range(0)));
  TransferStats stats;
  for (auto _ : state) {
    auto out = transferFields(s.from, s.to, fields, {method}, &stats);
    benchmark::DoNotOptimize(out.front().data());
  }
  state.counters["vertices_old"] = s.from.numVertices();
  state.counters["vertices_new"] = s.to.numVertices();
  state.counters["pieces"] = double(stats.supermeshPieces);
  state.counters["cg_iterations"] = stats.solverIterations;
  state.counters["mass_defect"] = stats.maxRelativeMassDefect();
}

void BM_Projection(benchmark::State& state) { run(state, TransferMethod::L2Projection); }
void BM_Interpolation(benchmark::State& state) { run(state, TransferMethod::Interpolation); }

}  // namespace

BENCHMARK(BM_Projection)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Interpolation)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();

// Benchmark: ABLMG connection time against node count, 10⁴ … 10⁶, on
// the paper's radius-10 disk with its constant anisotropic metric (h1 = 2.5 h2, θ = π/4)
// scaled to the requested count. The nodes are placed once per size outside the timed loop
// (early-stopped placement, tolerance 1e-2). Not a test: run by hand,
//   OMP_NUM_THREADS=2 ./bench/bench_connect --benchmark_counters_tabular=true
// Counters: nodes, triangles, repaired triangles, eq. (12) deletions and swaps, the two
// phases (local meshes, scaffold + repair) and µs per node.
#include "ablmg/mesher/connect.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <numbers>

using namespace ablmg;
using namespace ablmg::mesher;

namespace {

const PlacementResult& placed(long n) {
  static std::map<long, PlacementResult> cache;
  auto it = cache.find(n);
  if (it != cache.end()) return it->second;
  const double h1h2 = 2.0 / std::sqrt(3.0) * std::numbers::pi * 100.0 / double(n);
  const double h2 = std::sqrt(h1h2 / 2.5);
  PlacementOptions o;
  o.tolerance = 1e-2;
  return cache[n] = placeNodes(Domain::disk({0, 0}, 10),
                               ConstantMetricField(Metric2::fromSizes(2.5 * h2, h2, std::numbers::pi / 4)), o);
}

void BM_Connect(benchmark::State& state) {
  const PlacementResult& p = placed(state.range(0));
  const Domain disk = Domain::disk({0, 0}, 10);
  ConnectOptions o;
  o.threads = int(state.range(1));
  ConnectResult r;
  for (auto _ : state) {
    r = connect(p, disk, o);
    benchmark::DoNotOptimize(r.mesh.triangles.data());
  }
  const auto& s = r.stats;
  state.counters["nodes"] = double(p.nodes.size());
  state.counters["triangles"] = double(r.mesh.numTriangles());
  state.counters["repaired"] = double(s.repairedTriangles);
  state.counters["deleted"] = double(s.deletedEdges);
  state.counters["swaps"] = double(s.swaps);
  state.counters["s_local"] = s.secondsLocalMeshes;
  state.counters["s_repair"] = s.secondsRepair;
  state.counters["us/node"] = 1e6 * (s.secondsLocalMeshes + s.secondsRepair) / double(p.nodes.size());
}

}  // namespace

BENCHMARK(BM_Connect)->ArgsProduct({{10'000, 100'000, 1'000'000}, {1, 2}})->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_MAIN();

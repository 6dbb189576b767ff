#!/usr/bin/env bash
# The benchmark suite, one command:
#
#   bash scripts/bench.sh                      # 10⁴, 10⁵, 10⁶ triangles (about 30 s after the build)
#   BENCH_SIZES="10000 100000" bash scripts/bench.sh   # a quick run
#
# For each size, build/bench/bench_stages meshes the radius-10 disk with a constant anisotropic
# metric (one process per size, so the peak memory is that size's) and times every stage:
# initial placement, dynamics (and per step), adjacency upkeep, population control, ABLMG
# connection, validation, .mesh and .vtu writing, P1 assembly and CHOLMOD solve. Then it writes
# bench/results/latest.md (the table, with the machine and date) and
# bench/results/latest.json (every figure, with the fitted growth exponents), and the table into
# docs/benchmarks.md (between <!-- bench.sh:begin --> and <!-- bench.sh:end -->). The Google
# Benchmark programs beside it (bench_place_nodes, bench_connect, bench_poisson, bench_adapt)
# measure single stages in more detail.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -x build/bench/bench_stages ]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DABLMG_BUILD_BENCH=ON > /dev/null
  cmake --build build -j"$(nproc)" --target bench_stages
fi
export OMP_WAIT_POLICY=passive
mkdir -p bench/results
files=()
for n in ${BENCH_SIZES:-10000 100000 1000000}; do
  echo "== $n triangles" >&2
  build/bench/bench_stages --triangles "$n" --json "bench/results/stages_$n.json" > /dev/null
  files+=("bench/results/stages_$n.json")
done
build/bench/bench_stages --table "${files[@]}" --md bench/results/latest.md --json bench/results/latest.json
python3 scripts/update_benchmarks.py bench.sh bench/results/latest.md --command "bash scripts/bench.sh"

#!/usr/bin/env bash
# How much an adaptive run's errors owe to one mesh: `ablmg adapt` on one problem with the
# placement seeds 0 … SEEDS−1 (PlacementOptions::seed: the same schedule and metric, the initial
# nodes jittered by 0.1 metric units, so each seed gives another mesh of the same statistics),
# and per cycle the spread of the vertex count and of the L2 and H1 errors over the seeds.
# That spread is the floor under any comparison of two runs that build different meshes (the
# DOLFINx loop against `ablmg adapt`, 2 MPI ranks against 1: docs/benchmarks.md).
#
#   bash scripts/seed_scatter.sh                                   # L-shape, 1000 … 32000, 5 seeds
#   PROBLEM=wavefront TARGETS=1000,2000,4000 SEEDS=3 bash scripts/seed_scatter.sh
#
# Writes bench/results/seed_scatter_PROBLEM.md and the section seed_scatter of docs/benchmarks.md.
set -euo pipefail
cd "$(dirname "$0")/.."
PROBLEM=${PROBLEM:-lshape}
TARGETS=${TARGETS:-1000,2000,4000,8000,16000,32000}
SEEDS=${SEEDS:-5}
if [ ! -x build/bin/ablmg ]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
  cmake --build build -j"$(nproc)" --target ablmg
fi
out=bench/results/seed_scatter_$PROBLEM
mkdir -p "$out"
for ((s = 0; s < SEEDS; ++s)); do
  OMP_WAIT_POLICY=passive build/bin/ablmg adapt --problem "$PROBLEM" --target-vertices "$TARGETS" --seed "$s" \
    --vtu off --uniform off -v 0 --out-dir "$out/seed_$s" > "$out/seed_$s.log"
done
python3 - "$out" "$SEEDS" "$PROBLEM" "$TARGETS" > "$out.md" <<'PY'
import csv, sys
out, seeds, problem, targets = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]
runs = [list(csv.DictReader(open(f"{out}/seed_{s}/convergence.csv"))) for s in range(seeds)]
print(f"**{problem}**, `ablmg adapt --problem {problem} --target-vertices {targets} --seed S`, "
      f"S = 0 … {seeds - 1}: per cycle the mean over the seeds and the spread (max − min) / mean.\n")
print("| cycle | N mean | N spread | L2 mean | L2 spread | H1 mean | H1 spread | L2 seed 0 / mean |")
print("|---:|---:|---:|---:|---:|---:|---:|---:|")
for c in range(min(len(r) for r in runs)):
    col = lambda k: [float(r[c][k]) for r in runs]
    n, l2, h1 = col("vertices"), col("l2_error"), col("h1_error")
    mean = lambda v: sum(v) / len(v)
    spread = lambda v: (max(v) - min(v)) / mean(v)
    print(f"| {c} | {mean(n):.0f} | {100 * spread(n):.1f} % | {mean(l2):.3e} | {100 * spread(l2):.1f} % | "
          f"{mean(h1):.3e} | {100 * spread(h1):.1f} % | {l2[0] / mean(l2):.3f} |")
PY
cat "$out.md"
python3 scripts/update_benchmarks.py seed_scatter "$out.md" \
  --command "PROBLEM=$PROBLEM TARGETS=$TARGETS SEEDS=$SEEDS bash scripts/seed_scatter.sh"

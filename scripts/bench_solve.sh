#!/usr/bin/env bash
# The P1 solve against the grading: ordering + CHOLMOD factorisation + solves at ≈ 10⁵
# unknowns on a uniform mesh and on the wave-front and tanh-layer adapted meshes, for each
# fill-reducing ordering, and assembly + solve at 10⁶ unknowns. One command:
#
#   bash scripts/bench_solve.sh        # ≈ 4 min after the build (the adapted meshes: ≈ 1 min more)
#
# Writes bench/results/solve_graded.json and regenerates the section "Solver ordering against
# the grading" of docs/benchmarks.md (scripts/update_benchmarks.py). Flops and factor non-zeros are CHOLMOD's counts (independent of the
# machine's load); times are wall clock (mean of 3 runs) and depend on it.
set -euo pipefail
cd "$(dirname "$0")/.."
# Configure for the benchmarks if needed, and always bring the binaries up to date (a no-op
# when they are): a stale benchmark would time old code.
if [ ! -f build/CMakeCache.txt ] || ! grep -q '^ABLMG_BUILD_BENCH:BOOL=ON' build/CMakeCache.txt; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DABLMG_BUILD_BENCH=ON > /dev/null
fi
cmake --build build -j2 --target ablmg bench_solve_graded > /dev/null
bash scripts/make_bench_meshes.sh bench/results/graded_meshes
json=bench/results/solve_graded.json
# Each mesh in a process of its own, so that every mesh's first solve (t_first) maps fresh
# pages and its timed solves reuse them alike; then the 10⁶ run, in its own process too.
parts=()
for filter in 'BM_Solve/0/' 'BM_Solve/1/' 'BM_Solve/2/' 'BM_AssembleAndSolve1M'; do
  part=$(mktemp)
  OMP_WAIT_POLICY=passive ./build/bench/bench_solve_graded --benchmark_out="$part" --benchmark_out_format=json \
    --benchmark_filter="$filter" > /dev/null
  parts+=("$part")
done
/usr/bin/python3 - "$json" "${parts[@]}" <<'PY'
import json, sys
merged = None
for path in sys.argv[2:]:
    data = json.load(open(path))
    if merged is None:
        merged = data
    else:
        merged["benchmarks"] += data["benchmarks"]
json.dump(merged, open(sys.argv[1], "w"), indent=1)
PY
rm -f "${parts[@]}"
body=$(mktemp)
/usr/bin/python3 - "$json" > "$body" <<'PY'
import json, sys
data = json.load(open(sys.argv[1]))
ctx = data["context"]
rows = [b for b in data["benchmarks"] if b["name"].startswith("BM_Solve")]
one = [b for b in data["benchmarks"] if b["name"].startswith("BM_AssembleAndSolve1M")]
load = ", ".join("%.1f" % x for x in ctx.get("load_avg", []))
print(f"Load average at the start: {load} (a shared machine: wall times are noisy; flops and factor")
print("non-zeros are CHOLMOD's counts and are not). Wall = ordering + factorisation + solves, mean of 3 runs")
print("after a first one; first = that first solve, which maps the factor's memory fresh (each mesh runs in a")
print("process of its own, and the default ordering's row is its first solve); CPU = the timed runs on the")
print("calling thread (the other thread's share not counted). The phases (wall, last")
print("run): ordering; symbolic = the permuted matrices and CHOLMOD's analysis; numeric = the factorisation;")
print("triangular = the solves. \"geometric, one factorisation\": the default ordering factorised whole")
print("(the default factorises the two sides of the first cut apart, on two threads: fem/split_cholesky.hpp).")
print()
print("| mesh | ordering | unknowns | factor nnz | GFlop | ordering s | symbolic s | numeric s | triangular s | solve wall s | solve CPU s | first s |")
print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for b in rows:
    mesh, order = b["label"].split(" ", 1)
    print(f"| {mesh} | {order} | {b['unknowns']:.0f} | {b['lnz']/1e6:.2f}M | {b['GFlop']:.3f} | "
          f"{b['t_order']:.3f} | {b['t_symbolic']:.3f} | {b['t_numeric']:.3f} | {b['t_triangular']:.3f} | "
          f"{b['real_time']/1e3:.3f} | {b['cpu_time']/1e3:.3f} | {b['t_first']:.3f} |")
default = [b for b in rows if b["label"].endswith("(smallest separator)")]
if default:
    print()
    for key, what, scale in (("real_time", "repeated solves", 1e-3), ("t_first", "first solve of a process", 1)):
        t = {b["label"].split(" ", 1)[0]: b[key] * scale for b in default}
        print(f"Default ordering, {what}: " + ", ".join(f"{m} {v:.3f} s" for m, v in t.items()) +
              f"; largest / smallest {max(t.values()) / min(t.values()):.2f}.")
print()
print("10⁶ unknowns (`unitSquareMesh(1001)`), assembly included:")
print()
print("| solver | assembly s | ordering s | symbolic s | numeric s | triangular s | GFlop | total wall s | CPU s |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
for b in one:
    print(f"| {b['label']} | {b['t_assembly']:.2f} | {b['t_order']:.2f} | {b['t_symbolic']:.2f} | {b['t_numeric']:.2f} | "
          f"{b['t_triangular']:.2f} | {b['GFlop']:.1f} | {b['real_time']/1e3:.2f} | {b['cpu_time']/1e3:.2f} |")
PY
/usr/bin/python3 scripts/update_benchmarks.py bench_solve.sh "$body" --command "bash scripts/bench_solve.sh"
rm -f "$body"

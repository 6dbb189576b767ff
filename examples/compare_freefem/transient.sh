#!/usr/bin/env bash
# Time-dependent adaptation, measured: `ablmg transient` (interval-intersected metric, defaults)
# against a fixed uniform mesh of the same average vertex count, against the metric of the current
# solution alone, and against FreeFem++'s usual adaptmesh time loop (transient_loop.idp) at the
# same average vertex count. One command, from anywhere:
#
#   examples/compare_freefem/transient.sh [--problem movingpeak|front|movingpeak,front|all] [--vertices N]
#                                         [--out DIR] [--no-docs]
#
# Per problem, in OUT/NAME/ (OUT default out/transient under the repository):
#  adaptive/   ablmg transient --vertices N
#  uniform/    ablmg transient --uniform --vertices <adaptive's average>
#  coarse/     ablmg transient --vertices N/10 (does it reach the uniform run's error?)
#  current/    ablmg transient --metric current --vertices N
#  freefem/    FreeFem++ transient_NAME.edp, err chosen so that its average vertex count matches
#              (one run at err 0.002, one at the err scaled by the vertex ratio; the closer kept)
#  equal/      ablmg transient --vertices N scaled to FreeFem++'s average vertex count (the
#              error and CPU comparison at equal N̄)
#  summary.md  the table; error_vs_time.png (adaptive, current, uniform, FreeFem on one plot)
# CPU seconds (user + sys, /usr/bin/time) for both programs: the machine may be shared, and CPU
# time is what a loaded machine does not inflate. Then docs/benchmarks.md's section "transient"
# is rewritten (scripts/update_benchmarks.py) and the plots copied to docs/figures/. When
# build/bench/bench_transfer exists (-DABLMG_BUILD_BENCH=ON), its table is added.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=$(cd "$here/../.." && pwd)
build=${ABLMG_BUILD:-$repo/build}
ablmg=$build/bin/ablmg
problems="movingpeak"
vertices=4000
out="$repo/out/transient"
docs=1
while [[ $# -gt 0 ]]; do
  case "$1" in
    --problem) problems=${2//,/ }; [[ $problems == all ]] && problems="movingpeak front"; shift 2 ;;
    --vertices) vertices=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --no-docs) docs=0; shift ;;
    *) echo "transient.sh: unknown argument '$1' (valid: --problem NAME|all --vertices N --out DIR --no-docs)" >&2; exit 2 ;;
  esac
done
[[ -x $ablmg ]] || { echo "transient.sh: $ablmg not found (build the ablmg target, or set ABLMG_BUILD)" >&2; exit 1; }
command -v FreeFem++ > /dev/null || { echo "transient.sh: FreeFem++ not found" >&2; exit 1; }

json() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))[sys.argv[2]])" "$1" "$2"; }
cpu() { awk '{print $1 + $2}' "$1"; }  # /usr/bin/time -f "%U %S" output → CPU seconds
run_ablmg() {  # DIR ARGS...: one run, CPU time in DIR.time
  local dir=$1; shift
  mkdir -p "$dir"
  /usr/bin/time -f "%U %S" -o "$dir.time" "$ablmg" transient "$@" --out-dir "$dir" > "$dir.log"
}
run_freefem() {  # DIR ERR
  local dir=$1 err=$2
  mkdir -p "$dir"
  (cd "$here" && /usr/bin/time -f "%U %S" -o "$dir.time" FreeFem++ -nw "transient_$name.edp" -err "$err" -k 20 \
     -out "$dir/steps.csv" -summary "$dir/summary.json" > "$dir.log" 2>&1)
}

body=$(mktemp)
{
  echo "Heat equation u_t − κΔu = f with the exact u of fem/transient_problems.hpp, BDF2, Δt and final"
  echo "time the problem's defaults; remesh every 20 steps (both programs). Space-time L2 = (Σ Δt ‖u − u_h‖²)^½,"
  echo "L2(H1) likewise with the H1 seminorm; N̄ = average vertex count over the steps; CPU = user + sys"
  echo "seconds of the whole run (errors included), both programs; max mass defect = largest relative"
  echo "∫u change of a transfer."
  echo
} > "$body"
for name in $problems; do
  dir=$out/$name
  rm -rf "$dir"; mkdir -p "$dir"
  run_ablmg "$dir/adaptive" --problem "$name" --vertices "$vertices" --label "ablmg, interval metric"
  nbar=$(json "$dir/adaptive/report.json" average_vertices)
  run_ablmg "$dir/uniform" --problem "$name" --uniform --vertices "$nbar" --frames off --label uniform
  run_ablmg "$dir/coarse" --problem "$name" --vertices "$((vertices / 10))" --frames off --label "ablmg, N/10"
  run_ablmg "$dir/current" --problem "$name" --vertices "$vertices" --metric current --frames off \
    --label "ablmg, current metric"
  run_freefem "$dir/freefem_a" 0.002
  na=$(json "$dir/freefem_a/summary.json" average_vertices)
  errb=$(python3 -c "print(0.002 * $na / $nbar)")
  run_freefem "$dir/freefem_b" "$errb"
  nb=$(json "$dir/freefem_b/summary.json" average_vertices)
  ff=$(python3 -c "print('freefem_a' if abs($na - $nbar) <= abs($nb - $nbar) else 'freefem_b')")
  mv "$dir/$ff" "$dir/freefem"; mv "$dir/$ff.time" "$dir/freefem.time"
  # FreeFem++'s N̄ follows err in steps: ablmg again with N scaled to FreeFem++'s N̄ (N̄/N is
  # steady), so that the two are compared at equal average vertex count.
  nff=$(json "$dir/freefem/summary.json" average_vertices)
  neq=$(python3 -c "print(round($vertices * $nff / $nbar))")
  run_ablmg "$dir/equal" --problem "$name" --vertices "$neq" --frames off --label "ablmg, FreeFem's N̄"
  "$ablmg" transient --problem "$name" --vertices "$vertices" --frames off --label "ablmg, interval metric" \
    --plot-with "ablmg, current metric=$dir/current" --plot-with "uniform=$dir/uniform" \
    --plot-with "FreeFem++ adaptmesh=$dir/freefem" --out-dir "$dir/plot" > /dev/null
  cp "$dir/plot/error_vs_time.png" "$dir/error_vs_time.png"
  row() {  # LABEL REPORT.json CPUFILE
    local st=$(json "$2" space_time_l2) sh=$(json "$2" space_time_h1) n=$(json "$2" average_vertices)
    local extra="–"
    [[ $2 == */report.json ]] && extra=$(python3 -c "print('%.1e' % $(json "$2" max_mass_defect))")
    printf "| %s | %.0f | %.3e | %.3e | %.1f | %s |\n" "$1" "$n" "$st" "$sh" "$(cpu "$3")" "$extra"
  }
  {
    echo "### $name"
    echo
    echo "| run | N̄ | space-time L2 | L2(H1) | CPU s | max mass defect |"
    echo "|---|---|---|---|---|---|"
    row "ablmg, interval metric (N = $vertices)" "$dir/adaptive/report.json" "$dir/adaptive.time"
    row "ablmg, metric of the current solution" "$dir/current/report.json" "$dir/current.time"
    row "ablmg, interval metric (N = $((vertices / 10)))" "$dir/coarse/report.json" "$dir/coarse.time"
    row "uniform mesh (same N̄ as the first row)" "$dir/uniform/report.json" "$dir/uniform.time"
    row "FreeFem++ adaptmesh every 20 steps (err $(json "$dir/freefem/summary.json" err))" "$dir/freefem/summary.json" "$dir/freefem.time"
    row "ablmg, interval metric (N = $neq, FreeFem++'s N̄)" "$dir/equal/report.json" "$dir/equal.time"
    python3 - "$dir" <<'PY'
import json, sys
d = sys.argv[1]
a, u, c, cur, f, e = (json.load(open(f"{d}/{k}/{n}")) for k, n in
                      [("adaptive", "report.json"), ("uniform", "report.json"), ("coarse", "report.json"),
                       ("current", "report.json"), ("freefem", "summary.json"), ("equal", "report.json")])
cpu = lambda k: sum(float(x) for x in open(f"{d}/{k}.time").read().split())
print()
print(f"uniform / adaptive space-time L2 at the same N̄: {u['space_time_l2'] / a['space_time_l2']:.1f}×; "
      f"the N/10 adaptive run ({c['average_vertices']:.0f} vertices) has {c['space_time_l2'] / u['space_time_l2']:.2f}× "
      f"the uniform run's error with {u['average_vertices'] / c['average_vertices']:.1f}× fewer vertices.")
print(f"Largest L2 error over the steps: interval metric {a['max_l2']:.2e}, current metric {cur['max_l2']:.2e}.")
print(f"Interval / current metric space-time L2: {a['space_time_l2'] / cur['space_time_l2']:.2f}.")
print(f"At equal N̄ ({f['average_vertices']:.0f} FreeFem++, {e['average_vertices']:.0f} ablmg): FreeFem++ / ablmg "
      f"space-time L2 {f['space_time_l2'] / e['space_time_l2']:.2f}×, CPU {cpu('freefem'):.1f} s against "
      f"{cpu('equal'):.1f} s.")
PY
    echo
    echo "![error against time, $name](figures/transient_$name.png)"
    echo
  } >> "$body"
done
bench=$build/bench/bench_transfer
if [[ -x $bench ]]; then  # the transfer alone, 10^5-vertex meshes (bench/bench_transfer.cpp)
  cut -d' ' -f1 /proc/loadavg > "$out/loadavg"
  for threads in 1 2; do
    OMP_NUM_THREADS=$threads OMP_WAIT_POLICY=passive "$bench" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
      --benchmark_format=json > "$out/bench_transfer_$threads.json" 2> /dev/null
  done
  python3 - "$out" >> "$body" <<'PY'
import json, sys
out = sys.argv[1]
print("### Transfer of 10⁵-vertex fields")
print()
print("bench/bench_transfer.cpp: two unrelated perturbed structured meshes of the unit square")
print("(1.0·10⁵ → 1.1·10⁵ vertices); medians of 5 runs. Wall time is what a caller waits for; on a")
print("shared machine it is inflated by the other processes, so the main thread's CPU time is given too")
print(f"(load average {open(f'{out}/loadavg').read().strip()} on {__import__('os').cpu_count()} cores when the benchmark started).")
print()
print("| transfer | fields | threads | wall ms | CPU ms (main thread) | pieces | CG iterations | mass defect |")
print("|---|---|---|---|---|---|---|---|")
for threads in (1, 2):
    for b in json.load(open(f"{out}/bench_transfer_{threads}.json"))["benchmarks"]:
        if b.get("aggregate_name") != "median":
            continue
        name, fields = b["run_name"].split("/")[0].replace("BM_", ""), b["run_name"].split("/")[1]
        print(f"| {name} | {fields} | {threads} | {b['real_time']:.0f} | {b['cpu_time']:.0f} | "
              f"{b['pieces']:.3g} | {b['cg_iterations']:.0f} | {b['mass_defect']:.1e} |")
print()
PY
fi
cat "$body"
if [[ $docs == 1 ]]; then
  mkdir -p "$repo/docs/figures"
  for name in $problems; do cp "$out/$name/error_vs_time.png" "$repo/docs/figures/transient_$name.png"; done
  python3 "$repo/scripts/update_benchmarks.py" transient "$body" \
    --command "examples/compare_freefem/transient.sh --problem ${problems// /,} --vertices $vertices"
fi
rm -f "$body"

#!/usr/bin/env bash
# The solver's fill-reducing ordering on every library problem's adapted mesh: our geometric
# nested dissection (fem/ordering.hpp) against METIS_NodeND, by CHOLMOD's flop count of the
# factorisation (load-independent) and by the solve's wall time (ordering + factorisation +
# triangular solves). One command:
#
#   bash scripts/bench_ordering_library.sh      # ≈ 5 min the first time (the adaptive loops), then ≈ 1 min
#
# Meshes: the last cycle of `ablmg adapt --problem P --cycles 7 --target-vertices
# 1500,…,96000` (≈ 10⁵ vertices; cached in bench/results/library_meshes, not committed), for the
# problems of examples/compare_freefem/run.sh. Each mesh is solved by `ablmg solve` with each
# ordering, three times alternated; the table keeps the best wall time of the three. Writes
# bench/results/ordering_library.json and regenerates the section "Solver ordering across the
# library" of docs/benchmarks.md.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --build build -j2 --target ablmg > /dev/null
ablmg=$PWD/build/bin/ablmg
out=bench/results/library_meshes
mkdir -p "$out"
schedule=1500,3000,6000,12000,24000,48000,96000
# name|problem|parameter (KEY=VALUE, or empty)
specs=(
  "wavefront|wavefront|"
  "wavefront_steep|wavefront|alpha=1000"
  "peak|peak|"
  "lshape|lshape|"
  "tanhlayer|tanhlayer|"
  "reentrant_5pi4|reentrant|omega=3.9269908169872414"
  "reentrant_7pi4|reentrant|omega=5.497787143782138"
  "slit|reentrant|omega=6.283185307179586"
  "linesing|linesing|"
  "multiple|multiple|"
)
rows=$(mktemp)
for spec in "${specs[@]}"; do
  IFS='|' read -r name problem param <<< "$spec"
  dir=$out/$name
  paramArgs=() params=""
  if [ -n "$param" ]; then
    paramArgs=(--param "$param")
    params="\"${param%%=*}\": ${param#*=}"
  fi
  if [ ! -f "$dir/cycle_6.mesh" ]; then
    echo "== $name: 7 adaptive cycles up to 96000 vertices" >&2
    "$ablmg" adapt --problem "$problem" "${paramArgs[@]}" --cycles 7 --target-vertices "$schedule" \
      --uniform off --medit on --vtu off --out-dir "$dir" > "$dir.log"
  fi
  for run in 1 2 3; do
    for ordering in geometric metis; do
      config=$dir/solve_$ordering.json
      cat > "$config" <<EOF
{"mesh": "cycle_6.mesh", "problem": "$problem", "params": {$params}, "solver": {"ordering": "$ordering"},
 "output": {"vtu": "solve_$ordering.vtu", "report": "solve_${ordering}_$run.json"}}
EOF
      "$ablmg" solve "$config" > /dev/null
      echo "$name $ordering $run $dir/solve_${ordering}_$run.json" >> "$rows"
    done
  done
done
/usr/bin/python3 - "$rows" bench/results/ordering_library.json <<'PY'
import json, sys
runs = {}
for line in open(sys.argv[1]):
    name, ordering, run, path = line.split()
    solve = json.load(open(path))["solve"]
    runs.setdefault(name, {}).setdefault(ordering, []).append(solve)
table = {}
for name, by in runs.items():
    table[name] = {o: {"unknowns": r[0]["unknowns"], "factor_flops": r[0]["factor_flops"],
                       "factor_nonzeros": r[0]["factor_nonzeros"],
                       "t_ordering": min(x["t_ordering"] for x in r), "t_solve": min(x["t_solve"] for x in r)}
                   for o, r in by.items()}
json.dump(table, open(sys.argv[2], "w"), indent=1)
PY
rm -f "$rows"
body=$(mktemp)
/usr/bin/python3 - bench/results/ordering_library.json > "$body" <<'PY'
import json, math, sys
t = json.load(open(sys.argv[1]))
print("The final mesh of each library problem's adaptive loop (7 cycles to 96 000 vertices), solved by")
print("`ablmg solve` with our geometric nested dissection and with METIS_NodeND. GFlop and factor")
print("non-zeros are CHOLMOD's counts (the same on any machine); times are wall clock, best of three")
print("alternated runs; solve = ordering + factorisation + triangular solves.")
print()
print("| problem | unknowns | GFlop geometric | GFlop METIS | flops ratio | ordering s geometric / METIS | solve s geometric / METIS |")
print("|---|---:|---:|---:|---:|---:|---:|")
logs, solves = [], []
for name, r in t.items():
    g, m = r["geometric"], r["metis"]
    ratio = g["factor_flops"] / m["factor_flops"]
    logs.append(math.log(ratio))
    solves.append(math.log(g["t_solve"] / m["t_solve"]))
    print(f"| {name} | {g['unknowns']} | {g['factor_flops']*1e-9:.3f} | {m['factor_flops']*1e-9:.3f} | {ratio:.2f} | "
          f"{g['t_ordering']:.3f} / {m['t_ordering']:.3f} | {g['t_solve']:.3f} / {m['t_solve']:.3f} |")
print()
print(f"Geometric mean over the {len(logs)} problems: flops geometric / METIS {math.exp(sum(logs)/len(logs)):.2f}, "
      f"solve time geometric / METIS {math.exp(sum(solves)/len(solves)):.2f}.")
PY
/usr/bin/python3 scripts/update_benchmarks.py ordering_library "$body" --command "bash scripts/bench_ordering_library.sh"
rm -f "$body"

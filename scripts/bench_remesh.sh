#!/usr/bin/env bash
# `ablmg remesh` throughput, side by side with MMG2D on every input, one command:
#
#   MMG=/path/to/mmg2d_O3 bash scripts/bench_remesh.sh   # MMG: default mmg2d_O3 on the PATH
#   REPEAT=1 bash scripts/bench_remesh.sh                # one run per program and input (default 3)
#
# Inputs (made here, in bench/results/remesh_inputs/ and bench/results/graded_meshes/, not
# committed):
#   ring:  the ring metric on the radius-10 disk, 8.4·10⁴ triangles (`ablmg mesh
#          examples/configs/speed_ring_84k.json`), remeshed to its own metric (-hgrad 1.3);
#   wave:  Mitchell's wave front α = 20 (the adaptive loop of examples/compare_freefem, p = 4,
#          FreeFem's vertex schedule): cycle 14's mesh (6.8·10⁴ vertices) and the metric of the
#          next cycle (-hgrad -1, as the loop does), 2.3·10⁵ output triangles;
#   layer: the tanh layer's last adaptive cycle (scripts/make_bench_meshes.sh: 4.6·10⁴ vertices
#          and the metric for 9.4·10⁴, anisotropy up to ≈ 10⁴; -hgrad -1);
#   refine: a uniform coarse mesh of the unit square (h = 0.01216, 1.6·10⁴ triangles) and the
#          isotropic metric h/8: 10⁶ output triangles (-hgrad -1).
# Each remesh runs REPEAT times; the table gives the fastest wall clock (/usr/bin/time, the
# whole process) and its peak memory, the output triangles per second, the reading, meshing
# and writing times (ablmg: --report; MMG: its -v 5 timers, writing = total − reading − library
# call), and the edge statistics of `ablmg stats` (MMG's output measured the same way).
# Writes bench/results/remesh.md and the section bench_remesh.sh of docs/benchmarks.md.
# The environment is left as it is (OpenMP's default busy-waiting; a loaded machine wants
# OMP_WAIT_POLICY=passive, see README).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -x build/bin/ablmg ]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
  cmake --build build -j"$(nproc)" --target ablmg
fi
ablmg=$PWD/build/bin/ablmg
in=bench/results/remesh_inputs
mkdir -p "$in"
if [ ! -f "$in/ring.sol" ]; then
  echo "== making the ring input" >&2
  "$ablmg" mesh examples/configs/speed_ring_84k.json -o "$in/ring.mesh" > /dev/null
fi
if [ ! -f "$in/wave.sol" ]; then
  echo "== making the wave-front input (16 adaptive cycles, ~20 s)" >&2
  "$ablmg" adapt --problem wavefront --param alpha=20 --p 4 --cycles 16 \
    --target-vertices 441,139,187,253,474,706,1166,2020,3226,5451,8995,15000,24969,41625,69153,115091 \
    --medit on --vtu off --uniform off --out-dir "$in/adapt" > /dev/null
  cp "$in/adapt/cycle_14.mesh" "$in/wave.mesh"
  cp "$in/adapt/cycle_14_metric.sol" "$in/wave.sol"
fi

if [ ! -f "$in/refine.sol" ]; then
  echo "== making the 8x refinement input" >&2
  echo '{"domain": {"rectangle": [0, 0, 1, 1]}, "metric": {"h": "0.01216"}}' > "$in/refine_coarse.json"
  "$ablmg" mesh "$in/refine_coarse.json" -o "$in/refine.mesh" > /dev/null
  awk 'BEGIN {h = 0.01216 / 8; m = 1 / (h * h)} /^SolAtVertices/ {print; getline; print; getline; print "1 3"; n = $0; sol = 1; next}
       sol && NF == 3 {print m, 0, m; next} {print}' "$in/refine.sol" > "$in/refine.sol.tmp"
  mv "$in/refine.sol.tmp" "$in/refine.sol"
fi
bash scripts/make_bench_meshes.sh bench/results/graded_meshes > /dev/null
cp bench/results/graded_meshes/tanhlayer_bg.mesh "$in/layer.mesh"
cp bench/results/graded_meshes/tanhlayer_bg.sol "$in/layer.sol"
MMG=${MMG:-$(command -v mmg2d_O3 || true)}
REPEAT=${REPEAT:-3}

stats() {  # stats OUT.mesh OUT.sol -> "±10 % | [1/√2,√2] | q min / mean"
  local s
  s=$("$ablmg" stats "$1" --sol "$2")
  local within unit qmin qmean
  within=$(sed -n 's/.*|l-1| <= 0.1: \([0-9.]*\)%.*/\1/p' <<< "$s")
  unit=$(sed -n 's/.*l in \[1\/sqrt2, sqrt2\]: \([0-9.]*\)%.*/\1/p' <<< "$s")
  qmin=$(sed -n 's/.*quality q: *min \([0-9.]*\) .*/\1/p' <<< "$s")
  qmean=$(sed -n 's/.*quality q: *min [0-9.]* *mean \([0-9.]*\).*/\1/p' <<< "$s")
  echo "$within % | $unit % | $qmin / $qmean"
}

best() {  # best CMD... -> "seconds KB cpu-seconds" of the fastest of REPEAT runs
  local b="" kb="" cpu=""
  for _ in $(seq "$REPEAT"); do
    local s k u y
    read -r s k u y < <(/usr/bin/time -f "%e %M %U %S" "$@" 2>&1 > /dev/null | tail -1)
    if [ -z "$b" ] || awk "BEGIN {exit !($s < $b)}"; then b=$s; kb=$k; cpu=$(awk "BEGIN {print $u + $y}"); fi
  done
  echo "$b $kb $cpu"
}

triangles() { awk '/^Triangles/ {getline; print; exit}' "$1"; }

# ablmg's stage times from its report: "read meshing write".
ablmgStages() { /usr/bin/python3 -c "import json,sys; s=json.load(open(sys.argv[1]))['seconds']; print('%.2f %.2f %.2f' % (s['read'], s['meshing'], s['write']))" "$1"; }
# MMG's from its -v 5 log: "read library write" (past a minute MMG prints "2m5s (125.687s)": the
# last field, in parentheses, is the one in seconds).
mmgStages() {
  awk '/DATA READING COMPLETED/ {r = $(NF)} /MMG2DLIB: ELAPSED TIME/ {l = $(NF)} /^ *ELAPSED TIME/ {t = $(NF)}
       END {gsub(/[()s]/, "", r); gsub(/[()s]/, "", l); gsub(/[()s]/, "", t); printf "%.2f %.2f %.2f\n", r, l, t - r - l}' "$1"
}

out=bench/results/remesh.md
{
  echo "# \`ablmg remesh\` throughput ($(date -u +%Y-%m-%d), $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs))"
  echo
  echo "Wall clock of the whole process, fastest of $REPEAT (load average at the start: $(cut -d' ' -f1-3 /proc/loadavg); the"
  echo "machine is shared, so times move with its load: CPU s, user + system, moves less); triangles/s ="
  echo "output triangles / wall; read, mesh, write: the program's own timers (ablmg: that run's --report;"
  echo "MMG: a separate -v 5 run)."
  echo
  echo "| case | program | in vertices | out triangles | wall s | CPU s | triangles/s | read / mesh / write s | peak MB | ±10 % | [1/√2, √2] | q min / mean |"
  echo "|---|---|---:|---:|---:|---:|---:|---|---:|---|---|---|"
  for c in ring wave layer refine; do
    grad=$([ $c = ring ] && echo 1.3 || echo -1)
    nin=$(awk '/^Vertices/ {getline; print; exit}' "$in/$c.mesh")
    read -r s kb cpu < <(best "$ablmg" remesh -in "$in/$c.mesh" -sol "$in/$c.sol" -out "$in/$c.o.mesh" -hgrad "$grad" -v -1 --report "$in/$c.report.json")
    nt=$(triangles "$in/$c.o.mesh")
    read -r tr tm tw < <(ablmgStages "$in/$c.report.json")
    echo "| $c | ablmg | $nin | $nt | $s | $cpu | $(awk "BEGIN {printf \"%.0f\", $nt / $s}") | $tr / $tm / $tw | $((kb / 1024)) | $(stats "$in/$c.o.mesh" "$in/$c.o.sol") |"
    if [ -n "$MMG" ] && [ -x "$MMG" ]; then
      read -r s kb cpu < <(best "$MMG" -in "$in/$c.mesh" -sol "$in/$c.sol" -out "$in/$c.mmg.mesh" -hgrad "$grad" -v -1)
      "$MMG" -in "$in/$c.mesh" -sol "$in/$c.sol" -out "$in/$c.mmg.mesh" -hgrad "$grad" -v 5 > "$in/$c.mmg.log" 2>&1
      nt=$(triangles "$in/$c.mmg.mesh")
      read -r tr tm tw < <(mmgStages "$in/$c.mmg.log")
      echo "| $c | $(basename "$MMG") | $nin | $nt | $s | $cpu | $(awk "BEGIN {printf \"%.0f\", $nt / $s}") | $tr / $tm / $tw | $((kb / 1024)) | $(stats "$in/$c.mmg.mesh" "$in/$c.mmg.sol") |"
    else
      echo "| $c | MMG2D not found (set MMG=) | | | | | | | | | | |"
    fi
  done
} > "$out"
cat "$out"
tail -n +3 "$out" > "$out.body"
python3 scripts/update_benchmarks.py bench_remesh.sh "$out.body" --command "${MMG:+MMG=$MMG }bash scripts/bench_remesh.sh"
rm -f "$out.body"

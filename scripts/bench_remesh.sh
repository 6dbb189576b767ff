#!/usr/bin/env bash
# `ablmg remesh` throughput (output triangles per second at ≈ 10⁵ triangles, file reading and
# writing included), one command:
#
#   bash scripts/bench_remesh.sh            # about a minute after the build
#   MMG=/path/to/mmg2d_O3 bash scripts/bench_remesh.sh   # also time MMG2D on the same files
#
# Inputs (made here, in bench/results/remesh_inputs/, not committed):
#   ring: the ring metric on the radius-10 disk, 8.4·10⁴ triangles (`ablmg mesh
#         examples/configs/speed_ring_84k.json`), remeshed to its own metric (with -hgrad 1.3,
#         remesh's default);
#   wave: Mitchell's wave front α = 20 (the adaptive loop of examples/compare_freefem, p = 4,
#         FreeFem's vertex schedule): cycle 14's mesh (6.8·10⁴ vertices) and the metric of the
#         next cycle (-hgrad -1, as the loop does), 2.3·10⁵ output triangles.
# Each remesh runs 3 times; the table gives the fastest wall clock (/usr/bin/time, the whole
# process) and its peak memory, the output triangles per second, and the edge statistics of
# `ablmg stats` (MMG's output measured the same way). Writes bench/results/remesh.md and the
# table into docs/benchmarks.md (between <!-- bench_remesh.sh:begin --> and <!-- bench_remesh.sh:end -->).
# The environment is left as it is (OpenMP's default busy-waiting; a loaded machine wants
# OMP_WAIT_POLICY=passive, see docs/limitations.md).
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

best() {  # best CMD... -> "seconds KB" of the fastest of 3 runs
  local b="" kb=""
  for _ in 1 2 3; do
    local line
    line=$(/usr/bin/time -f "%e %M" "$@" 2>&1 > /dev/null | tail -1)
    local s=${line% *} k=${line#* }
    if [ -z "$b" ] || awk "BEGIN {exit !($s < $b)}"; then b=$s; kb=$k; fi
  done
  echo "$b $kb"
}

triangles() { awk '/^Triangles/ {getline; print; exit}' "$1"; }

out=bench/results/remesh.md
{
  echo "# \`ablmg remesh\` throughput ($(date -u +%Y-%m-%d), $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs))"
  echo
  echo "Command: \`bash scripts/bench_remesh.sh\`. Wall clock of the whole process (reading, gradation,"
  echo "placement, connection, validation, writing), fastest of 3; triangles/s = output triangles / wall."
  echo
  echo "| case | program | in vertices | out triangles | wall s | triangles/s | peak MB | ±10 % | [1/√2, √2] | q min / mean |"
  echo "|---|---|---:|---:|---:|---:|---:|---|---|---|"
  for c in ring wave; do
    grad=$([ $c = ring ] && echo 1.3 || echo -1)
    nin=$(awk '/^Vertices/ {getline; print; exit}' "$in/$c.mesh")
    read -r s kb < <(best "$ablmg" remesh -in "$in/$c.mesh" -sol "$in/$c.sol" -out "$in/$c.o.mesh" -hgrad "$grad" -v -1)
    nt=$(triangles "$in/$c.o.mesh")
    echo "| $c | ablmg | $nin | $nt | $s | $(awk "BEGIN {printf \"%.0f\", $nt / $s}") | $((kb / 1024)) | $(stats "$in/$c.o.mesh" "$in/$c.o.sol") |"
    if [ -n "${MMG:-}" ] && [ -x "$MMG" ]; then
      read -r s kb < <(best "$MMG" -in "$in/$c.mesh" -sol "$in/$c.sol" -out "$in/$c.mmg.mesh" -hgrad "$grad" -v -1)
      nt=$(triangles "$in/$c.mmg.mesh")
      echo "| $c | $(basename "$MMG") | $nin | $nt | $s | $(awk "BEGIN {printf \"%.0f\", $nt / $s}") | $((kb / 1024)) | $(stats "$in/$c.mmg.mesh" "$in/$c.mmg.sol") |"
    fi
  done
} > "$out"
cat "$out"
tail -n +3 "$out" > "$out.body"
python3 scripts/update_benchmarks.py bench_remesh.sh "$out.body" --command "${MMG:+MMG=$MMG }bash scripts/bench_remesh.sh"
rm -f "$out.body"

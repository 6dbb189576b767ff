#!/usr/bin/env bash
# FreeFem++'s classic adaptmesh loop and ablmg's adaptive loop side by side on Mitchell's wave
# front, at matched vertex counts. One command, from anywhere:
#
#   examples/compare_freefem/run.sh [--cycles K] [--alpha A] [--shape-blend W] [--out DIR]
#
#   --cycles K  FreeFem++ cycles (default 12: up to 1.5·10⁴ vertices; 16: up to 1.2·10⁵)
#   --alpha A   wave-front steepness (default 20)
#   --shape-blend W  ablmg's metric shape (adapt/metric_from_hessian.hpp; default 0.25, the
#               measured best for the H1 error on this problem; "none" = the L4 metric's own)
#   --out DIR   output directory (default out/compare_freefem under the repository)
#   --update-docs  also write the table into docs/benchmarks.md (between <!-- compare_freefem:begin -->
#               and <!-- compare_freefem:end -->, with the date, machine, commit and this command)
#   ABLMG_BUILD=DIR  build directory (default build under the repository)
#
# Steps: 1. install freefem++ with apt-get if FreeFem++ is missing (needs root or sudo);
# 2. configure + build ablmg and the compare_freefem_plot program if missing (cmake Release);
# 3. FreeFem++ wavefront.edp → DIR/freefem.csv, DIR/freefem_final.mesh;
# 4. ablmg adapt --p 4 --shape-blend 0.25 with FreeFem's vertex count of each cycle as the target of the same cycle
#    → DIR/ablmg/ (convergence.csv/.json, cycle_K.mesh);
# 5. compare_freefem_plot → DIR/compare.png (L2 and H1 vs N, both final meshes) and
#    DIR/compare.md (matched table, error ratios, per-cycle and whole-run times).
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=$(cd "$here/../.." && pwd)
cycles=12
alpha=20
blend=0.25
out="$repo/out/compare_freefem"
updateDocs=0
args="$*"
while [[ $# -gt 0 ]]; do
  case "$1" in
    --cycles) cycles=$2; shift 2 ;;
    --alpha) alpha=$2; shift 2 ;;
    --shape-blend) blend=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --update-docs) updateDocs=1; shift ;;
    *) echo "run.sh: unknown argument '$1' (valid: --cycles K --alpha A --shape-blend W --out DIR --update-docs)" >&2; exit 2 ;;
  esac
done
build=${ABLMG_BUILD:-$repo/build}
mkdir -p "$out"
out=$(cd "$out" && pwd)

# 1. FreeFem++ (Debian package freefem++), only if missing.
if ! command -v FreeFem++ > /dev/null; then
  echo "== installing freefem++ (apt-get)"
  sudo=""
  if [[ $(id -u) -ne 0 ]]; then
    command -v sudo > /dev/null || { echo "run.sh: FreeFem++ is missing; run as root or install freefem++" >&2; exit 1; }
    sudo=sudo
  fi
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get update -q
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -q freefem++
fi

# 2. ablmg and the comparison program, only if missing.
if [[ ! -x "$build/bin/ablmg" || ! -x "$build/examples/compare_freefem_plot" ]]; then
  echo "== building ablmg in $build"
  [[ -f "$build/CMakeCache.txt" ]] || cmake -S "$repo" -B "$build" -DCMAKE_BUILD_TYPE=Release
  cmake --build "$build" --target ablmg compare_freefem_plot -j "$(nproc)"
fi

now() { date +%s.%N; }

# 3. FreeFem++'s loop.
echo "== FreeFem++ adaptmesh loop: wave front alpha=$alpha, $cycles cycles"
t0=$(now)
(cd "$out" && FreeFem++ -nw "$here/wavefront.edp" -alpha "$alpha" -cycles "$cycles" \
  -out freefem.csv -mesh freefem_final.mesh > freefem.log 2>&1) || { tail -30 "$out/freefem.log" >&2; exit 1; }
t1=$(now)
grep '^Cycle' "$out/freefem.log"

# 4. ablmg's loop at FreeFem's vertex counts, cycle by cycle.
targets=$(tail -n +2 "$out/freefem.csv" | cut -d, -f2 | paste -sd,)
echo "== ablmg adapt: target vertices $targets"
rm -rf "$out/ablmg"
t2=$(now)
blendArgs=()
[[ "$blend" != none ]] && blendArgs=(--shape-blend "$blend")
"$build/bin/ablmg" adapt --problem wavefront --param alpha="$alpha" --p 4 "${blendArgs[@]}" --target-vertices "$targets" \
  --uniform off --vtu off --medit on --out-dir "$out/ablmg" | tee "$out/ablmg.log"
t3=$(now)

# 5. Table and picture.
"$build/examples/compare_freefem_plot" --freefem "$out/freefem.csv" --freefem-mesh "$out/freefem_final.mesh" \
  --ablmg "$out/ablmg" --freefem-wall "$(awk "BEGIN { print $t1 - $t0 }")" --ablmg-wall "$(awk "BEGIN { print $t3 - $t2 }")" \
  --png "$out/compare.png" --md "$out/compare.md"
cat "$out/compare.md"
if [[ $updateDocs == 1 ]]; then
  python3 "$repo/scripts/update_benchmarks.py" compare_freefem "$out/compare.md" \
    --command "examples/compare_freefem/run.sh $args"
fi

#!/usr/bin/env bash
# FreeFem++'s usual adaptmesh loop and ablmg's adaptive loop (its defaults) side by side on the
# problems of fem/test_problems.hpp. One command, from anywhere:
#
#   examples/compare_freefem/run.sh --problem NAME|all [--maxnv N] [--out DIR] [--no-docs]
#
#   NAME     wavefront, wavefront_steep (alpha 1000), peak, lshape, tanhlayer, reentrant_5pi4,
#            reentrant_7pi4, linesing, multiple; all = every one of them, in that order
#   --maxnv  FreeFem's loop stops after its first cycle with at least N/2 vertices (default 1.2e5)
#   --out    work directory (default out/compare_freefem under the repository)
#   --no-docs  do not rewrite docs/benchmarks.md and docs/figures/
#   ABLMG_BUILD=DIR  build directory (default build under the repository)
#   ABLMG_ADAPT_FLAGS="..."  extra flags for ablmg adapt (experiments only; the docs are made without)
#
# Per problem, in OUT/NAME/:
# 1. FreeFem++ -nw NAME.edp (loop.idp: P1, err halved each cycle from a 16x16 grid, one
#    adaptmesh per cycle, errors against the exact solution) -> freefem.csv, freefem_final.mesh;
# 2. ablmg adapt --problem ... --vertices N (N = FreeFem's final vertex count; the default
#    schedule) -> ablmg/ (convergence.csv, cycle_K.mesh);
# 3. time to accuracy: ablmg adapt --vertices 2N --stop-h1 E --png off (E = FreeFem's final H1 error), wall;
# 4. compare_freefem_plot -> compare.md (tables), summary.md (one row), compare.png.
# Then docs/benchmarks.md's section compare_freefem is rebuilt from every
# OUT/*/compare.md present (each says when and at which commit it was measured) and the plots
# are copied to docs/figures/compare_freefem_NAME.png.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=$(cd "$here/../.." && pwd)
all="wavefront wavefront_steep peak lshape tanhlayer reentrant_5pi4 reentrant_7pi4 slit linesing multiple"
problem=""
maxnv=1.2e5
out="$repo/out/compare_freefem"
docs=1
while [[ $# -gt 0 ]]; do
  case "$1" in
    --problem) problem=$2; shift 2 ;;
    --maxnv) maxnv=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --no-docs) docs=0; shift ;;
    *) echo "run.sh: unknown argument '$1' (valid: --problem NAME|all --maxnv N --out DIR --no-docs)" >&2; exit 2 ;;
  esac
done
[[ -n "$problem" ]] || { echo "run.sh: --problem NAME|all is required (NAME: $all)" >&2; exit 2; }
problemArg=$problem
[[ "$problem" == all ]] && problem=$all
build=${ABLMG_BUILD:-$repo/build}
mkdir -p "$out"
out=$(cd "$out" && pwd)

# NAME -> "script.edp|FreeFem++ arguments|ablmg adapt arguments"
spec() {
  local w5=3.9269908169872414 w7=5.497787143782138 w8=6.283185307179586
  case "$1" in
    wavefront) echo "wavefront.edp||--problem wavefront" ;;
    wavefront_steep) echo "wavefront.edp|-alpha 1000|--problem wavefront --param alpha=1000" ;;
    peak) echo "peak.edp||--problem peak" ;;
    lshape) echo "lshape.edp||--problem lshape" ;;
    tanhlayer) echo "tanhlayer.edp||--problem tanhlayer" ;;
    reentrant_5pi4) echo "reentrant.edp|-omega $w5|--problem reentrant --param omega=$w5" ;;
    reentrant_7pi4) echo "reentrant.edp|-omega $w7|--problem reentrant --param omega=$w7" ;;
    slit) echo "slit.edp||--problem reentrant --param omega=$w8" ;;
    linesing) echo "linesing.edp||--problem linesing" ;;
    multiple) echo "multiple.edp||--problem multiple" ;;
    *) echo "run.sh: unknown problem '$1' (valid: $all, all)" >&2; return 1 ;;
  esac
}
for name in $problem; do spec "$name" > /dev/null; done

command -v FreeFem++ > /dev/null || { echo "run.sh: FreeFem++ is missing (Debian package freefem++)" >&2; exit 1; }
if [[ ! -x "$build/bin/ablmg" || ! -x "$build/examples/compare_freefem_plot" ]]; then
  echo "== building ablmg in $build"
  [[ -f "$build/CMakeCache.txt" ]] || cmake -S "$repo" -B "$build" -DCMAKE_BUILD_TYPE=Release
  cmake --build "$build" --target ablmg compare_freefem_plot -j 2
fi
now() { date +%s.%N; }
commit=$(git -C "$repo" rev-parse --short HEAD 2> /dev/null || echo unknown)
read -r -a extra <<< "${ABLMG_ADAPT_FLAGS:-}"
maxnvArg=""
[[ "$maxnv" == 1.2e5 ]] || maxnvArg=" --maxnv $maxnv"

for name in $problem; do
  IFS='|' read -r edp ffargs abargs <<< "$(spec "$name")"
  dir="$out/$name"
  rm -rf "$dir"
  mkdir -p "$dir"
  echo "== $name: FreeFem++ $edp $ffargs"
  t0=$(now)
  # shellcheck disable=SC2086
  (cd "$dir" && FreeFem++ -nw "$here/$edp" $ffargs -maxnv "$maxnv" -out freefem.csv -mesh freefem_final.mesh \
    > freefem.log 2>&1) || { tail -30 "$dir/freefem.log" >&2; exit 1; }
  t1=$(now)
  grep '^Cycle' "$dir/freefem.log" | tail -3
  nff=$(tail -n 1 "$dir/freefem.csv" | cut -d, -f2)
  h1ff=$(tail -n 1 "$dir/freefem.csv" | cut -d, -f5)
  echo "== $name: ablmg adapt $abargs --vertices $nff ${extra[*]}"
  t2=$(now)
  # shellcheck disable=SC2086
  "$build/bin/ablmg" adapt $abargs --vertices "$nff" "${extra[@]}" --uniform off --vtu off --medit on \
    --out-dir "$dir/ablmg" > "$dir/ablmg.log"
  t3=$(now)
  grep -E '^(Cycle|Rates)' "$dir/ablmg.log" | sed 's/ t: .*//' | tail -4
  echo "== $name: ablmg adapt $abargs --vertices $((2 * nff)) --stop-h1 $h1ff (time to FreeFem's final H1 error)"
  t4=$(now)
  # shellcheck disable=SC2086
  # Like FreeFem++'s loop (run -nw), the timed run draws no pictures.
  "$build/bin/ablmg" adapt $abargs --vertices $((2 * nff)) --stop-h1 "$h1ff" "${extra[@]}" --uniform off --vtu off \
    --png off --out-dir "$dir/reach" > "$dir/reach.log"
  t5=$(now)
  reached=$(awk -F, -v e="$h1ff" 'NR > 1 && $5 <= e { r = 1 } END { print r ? "yes" : "no" }' "$dir/reach/convergence.csv")
  reachWall=$(awk "BEGIN { print $t5 - $t4 }")
  [[ "$reached" == yes ]] || reachWall=nan
  {
    "$build/examples/compare_freefem_plot" --problem "$name" --freefem "$dir/freefem.csv" \
      --freefem-mesh "$dir/freefem_final.mesh" --ablmg "$dir/ablmg" --freefem-wall "$(awk "BEGIN { print $t1 - $t0 }")" \
      --ablmg-wall "$(awk "BEGIN { printf \"%.1f\", $t3 - $t2 }")" --reach-wall "$reachWall" \
      --png "$dir/compare.png" --md "$dir/compare_body.md" --summary "$dir/summary.md"
  } > /dev/null
  {
    echo "### $name"
    echo
    echo "Measured $(date -u +%Y-%m-%d), commit $commit, \`examples/compare_freefem/run.sh --problem $name$maxnvArg\`" \
      "(FreeFem++ $edp $ffargs; ablmg adapt $abargs --vertices $nff${extra[*]:+ ${extra[*]}})."
    tail -n +2 "$dir/compare_body.md"
  } > "$dir/compare.md"
  cat "$dir/summary.md"
done

[[ $docs == 1 ]] || exit 0
# The docs section, from every problem measured so far in OUT (in the order of $all); each
# problem's part says when and at which commit it was measured, the whole gets the provenance
# line of scripts/update_benchmarks.py.
mkdir -p "$repo/docs/figures"
body="$out/section.md"
{
  echo "| problem | N final | worst L2 ratio | worst H1 ratio | ablmg rates L2 / H1 | FreeFem rates L2 / H1 | errors fall | q mean min | time to FreeFem's H1 / its loop (s) | cycle to N final (s), ablmg / FreeFem |"
  echo "|---|---:|---:|---:|---:|---:|---|---:|---:|---:|"
  for name in $all; do [[ -f "$out/$name/summary.md" ]] && cat "$out/$name/summary.md"; done
  echo
  for name in $all; do
    [[ -f "$out/$name/compare.md" ]] || continue
    cat "$out/$name/compare.md"
    cp "$out/$name/compare.png" "$repo/docs/figures/compare_freefem_$name.png"
  done
} > "$body"
/usr/bin/python3 "$repo/scripts/update_benchmarks.py" compare_freefem "$body" \
  --command "examples/compare_freefem/run.sh --problem $problemArg$maxnvArg"
echo "Wrote docs/benchmarks.md (section compare_freefem) and docs/figures/compare_freefem_*.png"

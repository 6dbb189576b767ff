#!/usr/bin/env bash
# Adapted meshes at ≈ 10⁵ vertices for the solver benchmark (bench/bench_solve_graded.cpp) and
# the extreme-anisotropy remesh benchmark (scripts/bench_remesh.sh): the last cycle of the
# adaptive loop on the wave front and on the tanh layer, same vertex schedule, written as
# Medit files with the metric the loop would remesh to next. Not committed; reproducible:
#
#   bash scripts/make_bench_meshes.sh [OUT_DIR]     # default bench/results/graded_meshes
#
# Writes OUT_DIR/P.mesh (the last cycle's mesh, ≈ 9.5·10⁴ vertices) and OUT_DIR/P_bg.mesh +
# OUT_DIR/P_bg.sol (the cycle before: the background mesh and the metric the last remesh was
# made from, for `ablmg remesh` / MMG), P = wavefront, tanhlayer.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-bench/results/graded_meshes}
ablmg=${ABLMG:-$PWD/build/bin/ablmg}
[ -x "$ablmg" ] || { echo "build ablmg first (cmake --build build --target ablmg)" >&2; exit 1; }
mkdir -p "$out"
schedule=1500,3000,6000,12000,24000,48000,96000
for p in wavefront tanhlayer; do
  [ -f "$out/$p.mesh" ] && continue
  if [ ! -f "$out/$p.adapt/cycle_6.mesh" ]; then
    echo "== $p: 7 adaptive cycles up to 96000 vertices" >&2
    "$ablmg" adapt --problem "$p" --cycles 7 --target-vertices "$schedule" --uniform off \
      --medit on --vtu off --out-dir "$out/$p.adapt" > "$out/$p.adapt.log"
  fi
  cp "$out/$p.adapt/cycle_6.mesh" "$out/$p.mesh"
  cp "$out/$p.adapt/cycle_5.mesh" "$out/${p}_bg.mesh"
  cp "$out/$p.adapt/cycle_5_metric.sol" "$out/${p}_bg.sol"
done
ls -l "$out"/*.mesh >&2

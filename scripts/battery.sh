#!/usr/bin/env bash
# Mitchell's battery (fem/material_problems.hpp: five materials, κ from 0.05 to 25) through
# `ablmg adapt`: errors against the reference solution (the loop's own at REFERENCE vertices),
# per cycle, the interface check of the final mesh, and the pictures docs/figures/battery_mesh.png
# (the final mesh of a run to 4000 vertices, materials in colour, interfaces in red) and
# docs/figures/battery_convergence.png.
#
#   bash scripts/battery.sh                          # to 16000 vertices, reference 64000
#   VERTICES=4000 REFERENCE=32000 bash scripts/battery.sh
#
# Writes bench/results/battery/ and the section battery of docs/benchmarks.md.
set -euo pipefail
cd "$(dirname "$0")/.."
VERTICES=${VERTICES:-16000}
REFERENCE=${REFERENCE:-64000}
if [ ! -x build/bin/ablmg ]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
  cmake --build build -j"$(nproc)" --target ablmg
fi
out=bench/results/battery
mkdir -p "$out"
cmd="ablmg adapt --problem battery --vertices $VERTICES --reference-vertices $REFERENCE --vtu off"
OMP_WAIT_POLICY=passive build/bin/ablmg adapt --problem battery --vertices "$VERTICES" \
  --reference-vertices "$REFERENCE" --vtu off -v 0 --out-dir "$out" > "$out/run.log"
# the picture from a run to 4000 vertices (the final mesh of the measured run is too dense to see, and its PNG ~3 MB)
OMP_WAIT_POLICY=passive build/bin/ablmg adapt --problem battery --vertices 4000 --reference-vertices 0 --vtu off \
  -v 0 --out-dir "$out/picture" > "$out/picture.log"
cp "$out/picture/final_mesh.png" docs/figures/battery_mesh.png
cp "$out/convergence.png" docs/figures/battery_convergence.png
python3 - "$out" "$cmd" > "$out.md" <<'PY'
import json, sys
out, cmd = sys.argv[1], sys.argv[2]
j = json.load(open(f"{out}/convergence.json"))
print(f"`{cmd}`: errors against the reference solution on {j['definition']['reference_vertices']} vertices.\n")
print("| cycle | vertices | L2 error | H1 error | est. L2 interpolant | q mean / min |")
print("|---|---|---|---|---|---|")
for c in j["cycles"]:
    print(f"| {c['cycle']} | {c['vertices']} | {c['l2_error']:.3g} | {c['h1_error']:.3g} | "
          f"{c['l2_interp_estimate']:.3g} | {c['q_mean']:.3f} / {c['q_min']:.3f} |")
r, i = j["rates"], j["interfaces"]
print(f"\nRates over the last {r['window']} sizes: L2 {r['l2']:.2f}, H1 {r['h1']:.2f}, "
      f"estimate {r['l2_interp_estimate']:.2f}. Interfaces of the final mesh: {i['uncovered']:.2g} of their "
      f"length {i['length']:.4g} not on chains of its interface edges. Pictures: "
      "docs/figures/battery_convergence.png (this run), docs/figures/battery_mesh.png (the final mesh of "
      "the same loop to 4000 vertices: materials in colour, interfaces in red).")
PY
python3 scripts/update_benchmarks.py battery "$out.md" --command "bash scripts/battery.sh"
cat "$out.md"

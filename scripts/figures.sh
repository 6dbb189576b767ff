#!/usr/bin/env bash
# Re-measures the quality figures of the README (not the timings: scripts/bench.sh and
# scripts/bench_remesh.sh do those) and prints them as Markdown tables:
#   1. bubble placement on the paper's disks: nodes vs N*, nearest neighbours, residual drop;
#   2. the ABLMG meshes of the same cases: q, edge lengths, repaired triangles;
#   3. the same disks given as mesh + metric pairs to `ablmg remesh`;
#   4. the parametric surfaces of Table 2;
#   5. the adaptive loop: the flagship and the other problems of the library.
# Usage: bash scripts/figures.sh [OUT_DIR]   (default out/figures; needs build/bin/ablmg;
# about a minute on 2 cores). Deterministic: the same build gives the same tables.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-out/figures}
bin=build/bin/ablmg
[ -x "$bin" ] || { echo "build first: cmake -S . -B build && cmake --build build -j" >&2; exit 1; }
mkdir -p "$out"
export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}
cases="constant ring line eq4"
config() { [ "$1" = eq4 ] && echo examples/configs/paper_eq4_square_hole.json || echo "examples/configs/paper_disk_$1.json"; }

for c in $cases; do
  "$bin" mesh "$(config $c)" -o "$out/$c.mesh" --report "$out/$c.report.json" > /dev/null
  "$bin" stats "$out/$c.mesh" --sol "$out/$c.sol" --json "$out/$c.stats.json" > /dev/null
  "$bin" remesh -in "$out/$c.mesh" -sol "$out/$c.sol" -out "$out/$c.pair.mesh" -hgrad -1 -v 0 \
    --report "$out/$c.pair.report.json" > /dev/null
done
for s in "paper-fig16 0.0594" "paper-fig16 0.02" "sphere-patch 0.05" "torus 0.05" "torus-closed 0.05"; do
  set -- $s
  "$bin" surface --surface "$1" --h "$2" -o "$out/surface_$1_$2.mesh" --json "$out/surface_$1_$2.json" > /dev/null
done
"$bin" adapt --problem wavefront --target-vertices 1500,3000,6000,12000,12000 --p 4 --shape-blend 0.25 \
  --vtu off --out-dir "$out/flagship" > /dev/null
for p in lshape peak tanhlayer; do
  for g in off 1.3; do
    extra=""; [ "$g" = off ] || extra="--hgrad $g"
    "$bin" adapt --problem "$p" --target-vertices 500,1000,2000,4000,8000 $extra --vtu off \
      --out-dir "$out/adapt_${p}_$g" > /dev/null
  done
done

python3 - "$out" $cases <<'EOF'
import json, sys, os
out, cases = sys.argv[1], sys.argv[2:]
load = lambda p: json.load(open(os.path.join(out, p)))
pct = lambda x: f"{100 * x:.1f} %"
print("### Bubble placement\n")
print("| case | nodes | N* | nodes / N* | nearest neighbour in [0.85, 1.15] | residual drop | steps |\n|---|---|---|---|---|---|---|")
for c in cases:
    p = load(f"{c}.report.json")["stats"]["placement"]
    print(f"| {c} | {p['finalNodes']} | {p['predictedNodes']} | {p['finalNodes'] / p['predictedNodes']:.3f} | "
          f"{pct(p['nearestInRange'])} | ×{p['initialResidual'] / p['finalResidual']:.0f} | {p['steps']} |")
def quality_rows(suffix, report):
    for c in cases:
        q = load(f"{c}{suffix}")["quality"] if suffix.endswith("stats.json") else load(f"{c}{suffix}")["quality"]
        r = load(f"{c}{report}")
        rep = r["stats"]["connect"]["repairedTriangles"]
        e, l = q["element_quality"], q["edge_length"]
        print(f"| {c} | {q['vertices']} | {q['triangles']} | {e['mean']:.3f} | {e['min']:.3f} | {pct(l['in_sqrt2'])} | "
              f"{pct(l['within_10pct'])} | {rep} |")
head = "| case | nodes | triangles | q mean | q min | edges in [1/√2, √2] | ±10 % | repaired |\n|---|---|---|---|---|---|---|---|"
print("\n### ABLMG meshes, `ablmg mesh` + `ablmg stats --sol`\n\n" + head)
quality_rows(".stats.json", ".report.json")
print("\n### The same cases as mesh + metric pairs, `ablmg remesh -hgrad -1 --report`\n\n" + head)
quality_rows(".pair.report.json", ".pair.report.json")
print("\n### Surfaces\n\n| surface, h | N | E | α 0–0.6 / 0.6–0.8 / 0.8–1.0 | α min | α mean | edges in [h/√2, h√2] |\n|---|---|---|---|---|---|---|")
for f in sorted(x for x in os.listdir(out) if x.startswith("surface_") and x.endswith(".json")):
    q = load(f)["quality"]; a = q["element_quality"]; b = a["bins"]
    print(f"| {f[8:-5]} | {q['vertices']} | {q['triangles']} | {pct(b[0] + b[1] + b[2])} / {pct(b[3])} / {pct(b[4])} | "
          f"{a['min']:.3f} | {a['mean']:.3f} | {pct(q['edge_length']['in_sqrt2'])} |")
print("\n### Adaptive loop\n\n| run | last cycle: vertices, L2, H1, L2 interpolant | rates L2 / H1 / interpolant (last 4) | q mean / min (last) | q min (all cycles) |\n|---|---|---|---|---|")
for d in ["flagship"] + sorted(x for x in os.listdir(out) if x.startswith("adapt_")):
    j = load(f"{d}/convergence.json"); last = j["cycles"][-1]; r = j["rates"]
    print(f"| {d} | {last['vertices']}, {last['l2_error']:.3g}, {last['h1_error']:.3g}, {last['l2_interp_error']:.3g} | "
          f"{r['l2']:.2f} / {r['h1']:.2f} / {r['l2_interp']:.2f} | {last['q_mean']:.3f} / {last['q_min']:.3f} | "
          f"{min(c['q_min'] for c in j['cycles']):.3f} |")
EOF

#!/usr/bin/env bash
# Re-measures the quality figures (not the timings: scripts/bench.sh and scripts/bench_remesh.sh
# do those) and writes them as Markdown tables into docs/benchmarks.md, between the markers
# <!-- figures.sh:begin --> and <!-- figures.sh:end -->, with the date, machine and commit:
#   1. bubble placement on the paper's disks: nodes vs N*, nearest neighbours, residual drop;
#   2. the ABLMG meshes of the same cases: q, edge lengths, repaired triangles;
#   3. the same disks given as mesh + metric pairs to `ablmg remesh`;
#   4. the parametric surfaces of Table 2;
#   5. the adaptive loop: the flagship per cycle, and the other problems of the library.
# Usage: bash scripts/figures.sh [OUT_DIR]   (default out/figures; needs build/bin/ablmg;
# about 20 s on 2 cores). Deterministic: the same build gives the same tables.
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
    hgrad=$g; [ "$g" = off ] && hgrad=0   # 0: no gradation (the default is 1.3)
    "$bin" adapt --problem "$p" --target-vertices 500,1000,2000,4000,8000 --hgrad $hgrad --vtu off \
      --out-dir "$out/adapt_${p}_$g" > /dev/null
  done
done

python3 - "$out" $cases > "$out/figures.md" <<'EOF'
import json, sys, os
out, cases = sys.argv[1], sys.argv[2:]
load = lambda p: json.load(open(os.path.join(out, p)))
pct = lambda x: f"{100 * x:.1f} %"
label = {"constant": "constant h1 = 0.5, h2 = 0.2, θ = π/4", "ring": "ring h1 = 0.15\\|r − 6\\| + 0.2, h2 = h1/2",
         "line": "line h1 = 0.1\\|y\\| + 0.2, h2 = h1/2", "eq4": "eq. (4), h = 0.05, square minus a square hole"}
paper_q = {"constant": "0.9253", "ring": "0.9119", "line": "0.9727", "eq4": "0.952†"}
print("### Bubble placement (§3), `ablmg mesh CONFIG --report R.json`\n")
print("| case | nodes | N* | nodes / N* | nearest neighbour in [0.85, 1.15] | residual drop | steps |\n|---|---|---|---|---|---|---|")
for c in cases:
    p = load(f"{c}.report.json")["stats"]["placement"]
    print(f"| {label[c]} | {p['finalNodes']} | {p['predictedNodes']} | {p['finalNodes'] / p['predictedNodes']:.3f} | "
          f"{pct(p['nearestInRange'])} | ×{p['initialResidual'] / p['finalResidual']:.0f} | {p['steps']} |")
def quality_rows(suffix, report, paper):
    for c in cases:
        q = load(f"{c}{suffix}")["quality"]
        rep = load(f"{c}{report}")["stats"]["connect"]["repairedTriangles"]
        e, l = q["element_quality"], q["edge_length"]
        qm = f"{e['mean']:.3f} ({paper_q[c]})" if paper else f"{e['mean']:.3f}"
        print(f"| {label[c]} | {q['vertices']} | {q['triangles']} | {qm} | {e['min']:.3f} | {pct(l['in_sqrt2'])} | "
              f"{pct(l['within_10pct'])} | {rep} |")
head = "| case | nodes | triangles | q mean{} | q min | edges in [1/√2, √2] | ±10 % | repaired |\n|---|---|---|---|---|---|---|---|"
print("\n### ABLMG meshes (§4.3), `ablmg mesh CONFIG` + `ablmg stats MESH --sol SOL`\n\n" + head.format(" (paper)"))
quality_rows(".stats.json", ".report.json", True)
print("\n† the paper's figure is for its union-circle region, whose geometry it does not give.")
print("\n### The same cases as mesh + metric pairs, `ablmg remesh -hgrad -1 --report R.json`\n\n" + head.format(""))
quality_rows(".pair.report.json", ".pair.report.json", False)
print("\n### Surfaces (§5–6, Table 2), `ablmg surface --surface NAME --h H --json R.json`\n")
print("Paper, Fig. 16 surface: N 4385, E 8512, α min 0.329, α mean 0.899.\n")
print("| surface, h | N | E | α 0–0.6 / 0.6–0.8 / 0.8–1.0 | α min | α mean | edges in [h/√2, h√2] |\n|---|---|---|---|---|---|---|")
for f in sorted(x for x in os.listdir(out) if x.startswith("surface_") and x.endswith(".json")):
    q = load(f)["quality"]; a = q["element_quality"]; b = a["bins"]
    print(f"| {f[8:-5]} | {q['vertices']} | {q['triangles']} | {pct(b[0] + b[1] + b[2])} / {pct(b[3])} / {pct(b[4])} | "
          f"{a['min']:.3f} | {a['mean']:.3f} | {pct(q['edge_length']['in_sqrt2'])} |")
print("\n### The flagship loop, `ablmg adapt --problem wavefront --target-vertices 1500,3000,6000,12000,12000 --p 4 --shape-blend 0.25`\n")
print("| cycle | vertices | L2 error | H1 error | q mean / min |\n|---|---|---|---|---|")
for i, c in enumerate(load("flagship/convergence.json")["cycles"]):
    print(f"| {i}{' (uniform)' if i == 0 else ''} | {c['vertices']} | {c['l2_error']:.3g} | {c['h1_error']:.3g} | "
          f"{c['q_mean']:.3f} / {c['q_min']:.3f} |")
print("\n### Adaptive loop on the library's problems, `ablmg adapt --problem NAME --target-vertices 500,1000,2000,4000,8000 --hgrad 1.3|0`\n")
print("| run | last cycle: vertices, L2, H1, L2 interpolant | rates L2 / H1 / interpolant (last 4) | q mean / min (last) | q min (all cycles) |\n|---|---|---|---|---|")
for d in ["flagship"] + sorted(x for x in os.listdir(out) if x.startswith("adapt_")):
    j = load(f"{d}/convergence.json"); last = j["cycles"][-1]; r = j["rates"]
    print(f"| {d} | {last['vertices']}, {last['l2_error']:.3g}, {last['h1_error']:.3g}, {last['l2_interp_error']:.3g} | "
          f"{r['l2']:.2f} / {r['h1']:.2f} / {r['l2_interp']:.2f} | {last['q_mean']:.3f} / {last['q_min']:.3f} | "
          f"{min(c['q_min'] for c in j['cycles']):.3f} |")
EOF
cat "$out/figures.md"
python3 scripts/update_benchmarks.py figures.sh "$out/figures.md" --command "bash scripts/figures.sh"

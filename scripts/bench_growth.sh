#!/usr/bin/env bash
# Growth of `ablmg remesh` from 10⁵ to 10⁷ triangles, one coarse background for every size:
#
#   bash scripts/bench_growth.sh                      # 10⁵, 10⁶, 4·10⁶, 10⁷ triangles, one run each
#   SIZES="100000 1000000" REPEAT=3 bash scripts/bench_growth.sh
#   ABLMG=/path/to/ablmg bash scripts/bench_growth.sh  # another build (default build/bin/ablmg)
#
# Input (made here, in build/growth_inputs/, not committed): the uniform coarse mesh of the unit
# square of bench_remesh.sh's refine case (h = 0.01216, 1.5·10⁴ triangles) with the isotropic
# metric h / (8 √(T / 10⁶)) at every vertex, T the target triangle count (8× in h for 10⁶, as
# there); `-hgrad -1`, OMP_NUM_THREADS=2, OMP_WAIT_POLICY=passive unless set.
# Each size runs REPEAT times (default 1); the row is the fastest by meshing time, with its
# /usr/bin/time peak memory and CPU seconds, and its --report stage times. The fitted exponent
# is the least-squares slope of log(time) against log(triangles) over the sizes run.
# Writes build/growth_inputs/growth.md and the section bench_growth.sh of docs/benchmarks.md.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -x build/bin/ablmg ]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
  cmake --build build -j"$(nproc)" --target ablmg
fi
ablmg=${ABLMG:-$PWD/build/bin/ablmg}
in=build/growth_inputs
mkdir -p "$in"
SIZES=${SIZES:-100000 1000000 4000000 10000000}
REPEAT=${REPEAT:-1}
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-2} OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}
if [ ! -f "$in/coarse.sol" ]; then
  echo '{"domain": {"rectangle": [0, 0, 1, 1]}, "metric": {"h": "0.01216"}}' > "$in/coarse.json"
  "$ablmg" mesh "$in/coarse.json" -o "$in/coarse.mesh" > /dev/null
fi
load=$(cut -d' ' -f1-3 /proc/loadavg)
rows=$in/growth.rows
: > "$rows"
for T in $SIZES; do
  awk -v T="$T" 'BEGIN {h = 0.01216 / (8 * sqrt(T / 1e6)); m = 1 / (h * h)}
       /^SolAtVertices/ {print; getline; print; getline; print "1 3"; sol = 1; next}
       sol && NF == 3 {printf "%.17g 0 %.17g\n", m, m; next} {print}' "$in/coarse.sol" > "$in/t$T.sol"
  best=""
  for _ in $(seq "$REPEAT"); do
    echo "== $T triangles" >&2
    /usr/bin/time -f "%e %M %U %S" -o "$in/t$T.time" "$ablmg" remesh -in "$in/coarse.mesh" -sol "$in/t$T.sol" \
      -out "$in/t$T.o.mesh" -hgrad -1 -v -1 --report "$in/t$T.report.json" > /dev/null
    m=$(/usr/bin/python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['seconds']['meshing'])" "$in/t$T.report.json")
    if [ -z "$best" ] || awk "BEGIN {exit !($m < $best)}"; then
      best=$m
      cp "$in/t$T.report.json" "$in/t$T.best.json"
      cp "$in/t$T.time" "$in/t$T.best.time"
    fi
  done
  echo "$T $in/t$T.best.json $(cat "$in/t$T.best.time")" >> "$rows"
  rm -f "$in/t$T.o.mesh" "$in/t$T.o.sol"
done

out=$in/growth.md
/usr/bin/python3 - "$rows" "$REPEAT" "$load" "$OMP_NUM_THREADS" "$OMP_WAIT_POLICY" > "$out" << 'EOF'
import json, math, sys
rows, repeat, load, threads, wait = sys.argv[1:]
runs = []
for line in open(rows):
    t, rep, wall, kb, user, system = line.split()
    r = json.load(open(rep))
    p, s = r["stats"]["placement"], r["seconds"]
    imp = r["stats"]["improve"]["seconds"]
    place = sum(p[k] for k in ("secondsInitial", "secondsDynamics", "secondsAdjacency", "secondsPopulation", "secondsDefects"))
    runs.append(dict(target=int(t), tri=r["quality"]["triangles"], wall=float(wall), cpu=float(user) + float(system),
                     kb=int(kb), mesh=s["meshing"], read=s["read"], write=s["write"], steps=p["steps"],
                     stop="plateau" if p["qualityPlateau"] else "stall" if p["stalled"] else "cap" if p["hitStepCap"] else "residual",
                     edits=p["inserted"] + p["deleted"], init=p["secondsInitial"], dyn=p["secondsDynamics"],
                     adj=p["secondsAdjacency"], pop=p["secondsPopulation"], defects=p["secondsDefects"], place=place,
                     improve=imp, rest=s["meshing"] - place - imp, within=r["quality"]["edge_length"]["within_10pct"],
                     qmin=r["quality"]["element_quality"]["min"]))

def fit(key):
    if len(runs) < 2:
        return "—"
    x = [math.log(r["tri"]) for r in runs]
    y = [math.log(max(r[key], 1e-9)) for r in runs]
    mx, my = sum(x) / len(x), sum(y) / len(y)
    return "%.2f" % (sum((a - mx) * (b - my) for a, b in zip(x, y)) / sum((a - mx) ** 2 for a in x))

print(f"`ablmg remesh` of one coarse background (1.5·10⁴ triangles) to an isotropic metric, {threads} threads,")
print(f"OMP_WAIT_POLICY={wait}, fastest meshing of {repeat} run(s) per size; load average at the start: {load}")
print("(the machine may be shared: CPU s, user + system of the whole process, and the step counts move")
print("less than wall times). Stage times are the run's --report (meshing = placement + connection +")
print("post-pass + validation; \"rest\" = connection and validation; defects: the defect-annealing")
print("passes and their share test); peak memory: /usr/bin/time; bytes / triangle = peak / triangles.")
print()
cols = [("triangles", "tri", "%d"), ("wall s", "wall", "%.2f"), ("CPU s", "cpu", "%.2f"), ("meshing s", "mesh", "%.2f"),
        ("steps (stop)", None, None), ("edits", "edits", "%d"), ("lattice s", "init", "%.2f"), ("dynamics s", "dyn", "%.2f"),
        ("adjacency s", "adj", "%.2f"), ("population s", "pop", "%.2f"), ("defects s", "defects", "%.2f"),
        ("rest s", "rest", "%.2f"),
        ("post-pass s", "improve", "%.2f"), ("read / write s", None, None), ("peak MB", None, None),
        ("bytes / triangle", None, None), ("±10 %", None, None), ("q min", "qmin", "%.3f")]
print("| " + " | ".join(c[0] for c in cols) + " |")
print("|" + "---:|" * len(cols))
for r in runs:
    cells = []
    for name, key, f in cols:
        if key:
            cells.append(f % r[key])
        elif name.startswith("steps"):
            cells.append(f"{r['steps']} ({r['stop']})")
        elif name.startswith("read"):
            cells.append("%.2f / %.2f" % (r["read"], r["write"]))
        elif name == "peak MB":
            cells.append("%d" % (r["kb"] // 1024))
        elif name.startswith("bytes"):
            cells.append("%d" % (r["kb"] * 1024 / r["tri"]))
        else:
            cells.append("%.1f %%" % (100 * r["within"]))
    print("| " + " | ".join(cells) + " |")
ex = ["triangles", "wall s", "CPU s", "meshing s", "", "", "lattice s", "dynamics s", "adjacency s", "population s",
      "defects s", "rest s", "post-pass s"]
keys = {"wall s": "wall", "CPU s": "cpu", "meshing s": "mesh", "lattice s": "init", "dynamics s": "dyn",
        "adjacency s": "adj", "population s": "pop", "defects s": "defects", "rest s": "rest", "post-pass s": "improve"}
cells = ["**exponent (fit)**"] + [fit(keys[c]) if c in keys else "" for c in ex[1:]]
print("| " + " | ".join(cells + [""] * (len(cols) - len(cells))) + " |")
EOF
cat "$out"
python3 scripts/update_benchmarks.py bench_growth.sh "$out" \
  --command "SIZES=\"$SIZES\" REPEAT=$REPEAT bash scripts/bench_growth.sh"

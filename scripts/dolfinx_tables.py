#!/usr/bin/env python3
"""The tables of scripts/bench_dolfinx.sh from its CSVs, into docs/benchmarks.md.

    python3 scripts/dolfinx_tables.py OUT_DIR docs/benchmarks.md

OUT_DIR/serial/<problem>_compare.csv (the DOLFINx loop against `ablmg adapt`, and DOLFINx on
ablmg adapt's meshes), OUT_DIR/mpi2/<problem>.csv (the same loop on 2 ranks, compared with OUT_DIR/serial_snapped/
<problem>.csv when present: both with the metric snapped) and, if present,
OUT_DIR/mpi2_1m/wavefront.csv (the time split at ~10^6 triangles) become the section
<!-- bench_dolfinx:begin/end --> (scripts/update_benchmarks.py).
"""
import csv
import math
import pathlib
import subprocess
import sys
import tempfile


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def fitted_at(rows, key, n, last=4):
    """The log-log least-squares line through the last `last` cycles, evaluated at n: the curve
    without the mesh-to-mesh scatter of single cycles."""
    xs = [math.log(float(r["vertices"])) for r in rows[-last:]]
    ys = [math.log(float(r[key])) for r in rows[-last:]]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    b = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    return math.exp(my + b * (math.log(n) - mx)), b


def main():
    out, doc = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
    md = []
    for name in ("wavefront", "lshape"):
        cmp_csv = out / "serial" / f"{name}_compare.csv"
        if not cmp_csv.exists():
            continue
        title = {"wavefront": "Wave front (α = 20)", "lshape": "Reentrant corner (L-shape)"}[name]
        md += [f"**{title}**: the DOLFINx loop against `ablmg adapt --problem {name}` (same schedule), "
               "L2 and H1 error ratios at equal N (ablmg adapt's curve interpolated log-log at the DOLFINx "
               "loop's N), and DOLFINx's errors on ablmg adapt's own meshes over ablmg's (measured against "
               "the degree-4 interpolant / against the exact expression at the quadrature points, as ablmg "
               "measures).", "",
               "| cycle | N DOLFINx loop | L2 | H1 | N ablmg adapt | L2 | H1 | L2 ratio | H1 ratio | "
               "same mesh L2 | H1 | same mesh, ablmg's measure L2 | H1 |",
               "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
        for t in rows(cmp_csv):
            md.append(f"| {t['cycle']} | {t['dolfinx_vertices']} | {float(t['dolfinx_l2']):.3e} | "
                      f"{float(t['dolfinx_h1']):.3e} | {t['ablmg_vertices']} | {float(t['ablmg_l2']):.3e} | "
                      f"{float(t['ablmg_h1']):.3e} | {float(t['l2_ratio']):.3f} | {float(t['h1_ratio']):.3f} | "
                      f"{float(t['same_mesh_l2_ratio']):.4f} | {float(t['same_mesh_h1_ratio']):.4f} | "
                      f"{float(t['same_mesh_l2_ratio_expr']):.6f} | {float(t['same_mesh_h1_ratio_expr']):.6f} |")
        loop, adapt = rows(out / "serial" / f"{name}.csv"), rows(out / "serial" / f"{name}_ablmg_adapt" / "convergence.csv")
        fits = []
        for key, label in (("l2_error", "L2"), ("h1_error", "H1")):
            (el, bl), (ea, ba) = fitted_at(loop, key, 1e5), fitted_at(adapt, key, 1e5)
            fits.append(f"{label} {el / ea:.3f} (rates {bl:.3f} / {ba:.3f})")
        md += ["", f"The curves at N = 10⁵ (log-log least-squares lines through the last 4 cycles), DOLFINx loop "
               f"over ablmg adapt: {'; '.join(fits)}.", ""]
        mpi = out / "mpi2" / f"{name}.csv"
        if mpi.exists():
            snapped = out / "serial_snapped" / f"{name}.csv"
            serial = rows(snapped if snapped.exists() else out / "serial" / f"{name}.csv")
            how = " (both with the metric snapped, `--metric-quantum 0.00390625`)" if snapped.exists() else ""
            md += [f"{title}, 2 MPI ranks against serial{how} (N, error ratios), and the 2-rank time split per cycle "
                   "(remesh: ablmg.hessian_metric + ablmg.remesh on rank 0 building this cycle's mesh; solve: "
                   "create_mesh + assembly + PETSc solve; errors: the two norms; wall s):", "",
                   "| cycle | N serial | N 2 ranks | L2 2 ranks / serial | H1 | remesh | solve | errors | CG its |",
                   "|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
            for s, m in zip(serial, rows(mpi)):
                md.append(f"| {m['cycle']} | {s['vertices']} | {m['vertices']} | "
                          f"{float(m['l2_error']) / float(s['l2_error']):.4f} | "
                          f"{float(m['h1_error']) / float(s['h1_error']):.4f} | {float(m['t_mesh']):.2f} | "
                          f"{float(m['t_solve']):.2f} | {float(m['t_errors']):.2f} | {m['ksp_iterations']} |")
            md.append("")
            m_rows = rows(mpi)
            fits = []
            for key, label in (("l2_error", "L2"), ("h1_error", "H1")):
                fits.append(f"{label} {fitted_at(m_rows, key, 1e5)[0] / fitted_at(serial, key, 1e5)[0]:.3f}")
            md += [f"The curves at N = 10⁵, 2 ranks over serial: {'; '.join(fits)}.", ""]
    big = out / "mpi2_1m" / "wavefront.csv"
    if big.exists():
        md += ["Wave front on 2 MPI ranks, a uniform 10⁵-vertex mesh then one adapted mesh of 5·10⁵ target "
               "vertices (≈ 10⁶ triangles): the split of the wall time (remesh on rank 0, the others "
               "waiting; solve distributed):", "",
               "| cycle | N | triangles | remesh | solve | errors | CG its |", "|---:|---:|---:|---:|---:|---:|---:|"]
        for m in rows(big):
            md.append(f"| {m['cycle']} | {m['vertices']} | {m['triangles']} | {float(m['t_mesh']):.2f} | "
                      f"{float(m['t_solve']):.2f} | {float(m['t_errors']):.2f} | {m['ksp_iterations']} |")
        md.append("")
    with tempfile.NamedTemporaryFile("w", suffix=".md", delete=False) as f:
        f.write("\n".join(md))
    root = pathlib.Path(__file__).resolve().parents[1]
    subprocess.run([sys.executable, str(root / "scripts" / "update_benchmarks.py"), "bench_dolfinx", f.name,
                    "--command", "bash scripts/bench_dolfinx.sh", "--doc", str(doc)], check=True)


if __name__ == "__main__":
    main()

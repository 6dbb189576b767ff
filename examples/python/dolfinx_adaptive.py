#!/usr/bin/env python3
"""DOLFINx in ablmg's adaptive loop: a solver nobody here wrote, on ablmg's meshes.

    /usr/bin/python3 examples/python/dolfinx_adaptive.py [--problem wavefront|lshape|all]
        [--target-vertices N0,N1,...] [--compare] [--out-dir DIR] [--reference DIR] [--check]
    mpirun -n 2 /usr/bin/python3 examples/python/dolfinx_adaptive.py ...   (the same, distributed)

The loop is that of `ablmg adapt --problem NAME --target-vertices N0,N1,...`
(adapt/adaptive_loop.cpp), with DOLFINx 0.5 (FEniCSx) in place of our P1 solver:

  1. mesh_0 = ablmg.uniform_mesh(domain, N0)                       (rank 0)
  2. the arrays go to DOLFINx: dolfinx.mesh.create_mesh with a P1 triangle coordinate element
     (rank 0 gives points and triangles, the other ranks empty arrays; DOLFINx partitions),
     our boundary refs become its facet tags (distribute_entity_data + meshtags_from_entities)
  3. DOLFINx assembles -Laplace(u) = f with u = u_exact on the facets of every ref, and solves
     with PETSc (CG + BoomerAMG, relative tolerance 1e-12)
  4. errors by DOLFINx's assemble_scalar against the exact solution interpolated in degree 4
     (quadrature degree 8, as ablmg's error norms)
  5. u_h is gathered to rank 0 in ablmg's vertex order (mesh.geometry.input_global_indices:
     DOLFINx renumbers vertices and dofs) and ablmg.hessian_metric computes the metric of the
     next target with the defaults of `ablmg adapt` (ablmg.ADAPT_DEFAULTS; without its
     dual-weighted and H1-weighted density and dual share, which need a second solve or the
     indicators of u_h, and its saddle shape, which
     needs lattice rows remesh does not take); ablmg.remesh(..., domain=D, options=MeshOptions('adapt')) meshes the exact
     domain as the loop does; back to 2.

--compare also runs `ablmg adapt --dual-weight 0 --h1-weight 0 --dual-share 0 --saddle-shape 0` with the same schedule and solves
with DOLFINx on each of its meshes (written with --medit on; ablmg adapt's dual-weighted density and dual
share need a second solve per cycle, which this loop does not do, so they are off there): the first comparison is the two loops (the same mesher,
a different solver, hence slightly different metrics and meshes), the second the two solvers on
identical meshes. Writes DIR/<problem>.csv (this loop), DIR/<problem>_compare.csv,
DIR/<problem>.png and DIR/<problem>.md (table). --reference DIR compares vertex counts and
errors with the CSV of an earlier run (serial against MPI). --check asserts the properties
the CTest tests rely on (errors fall; agreement with ablmg adapt / the reference).
"""
import argparse
import csv
import math
import os
import pathlib
import subprocess
import sys
import time

import numpy as np
from mpi4py import MPI
from petsc4py import PETSc

import dolfinx
import dolfinx.fem.petsc
import ufl
from dolfinx import cpp as _cpp

import ablmg

COMM = MPI.COMM_WORLD
ROOT = COMM.rank == 0
HERE = pathlib.Path(__file__).resolve().parent
REPO = HERE.parents[1]


# --- 1. The problems (fem/test_problems.cpp) ---------------------------------------------------

class WaveFront:
    """Mitchell's wave front: u = atan(alpha (r - r0)), r = |x - (xc, yc)|, on the unit square."""
    name, alpha, xc, yc, r0 = "wavefront", 20.0, -0.05, -0.05, 0.7

    def exact_numpy(self, x):
        return np.arctan(self.alpha * (np.hypot(x[0] - self.xc, x[1] - self.yc) - self.r0))

    def exact_ufl(self, x):
        return ufl.atan(self.alpha * (ufl.sqrt((x[0] - self.xc) ** 2 + (x[1] - self.yc) ** 2) - self.r0))

    def f_ufl(self, x):
        return -ufl.div(ufl.grad(self.exact_ufl(x)))


class LShape:
    """Mitchell's reentrant corner: u = r^(2/3) sin(2 theta / 3), theta in [0, 3 pi / 2], f = 0."""
    name = "lshape"

    @staticmethod
    def theta(x, y):
        # The domain has no angle in (-pi/2, 0): a slightly negative angle is the side y = 0
        # reached with round-off. DOLFINx maps interpolation points through the cell (y = -1e-17
        # on that side), and theta = 2 pi there made the degree-4 interpolant, hence the L2 error,
        # 6x too large on the first adapted meshes.
        t = np.arctan2(y, x)
        return np.where(t < -np.pi / 4, t + 2 * np.pi, np.maximum(t, 0))

    def exact_numpy(self, x):
        r = np.hypot(x[0], x[1])
        return r ** (2.0 / 3.0) * np.sin(2.0 * self.theta(x[0], x[1]) / 3.0)

    def exact_ufl(self, x):
        t = ufl.atan_2(x[1], x[0])
        theta = ufl.conditional(ufl.lt(t, -ufl.pi / 4), t + 2 * ufl.pi, ufl.max_value(t, 0))
        return ufl.sqrt(x[0] ** 2 + x[1] ** 2) ** (2.0 / 3.0) * ufl.sin(2.0 * theta / 3.0)

    def f_ufl(self, x):
        return None


PROBLEMS = {"wavefront": WaveFront(), "lshape": LShape()}
VERIFY_FAILURES = []


# --- 2. ablmg's mesh into DOLFINx -----------------------------------------------------------------

def to_dolfinx(m, comm=COMM):
    """create_mesh on every rank of comm (its rank 0 gives the arrays), facet tags from our refs."""
    if comm.rank == 0:
        x = np.ascontiguousarray(m.points, dtype=np.float64)
        cells = np.asarray(m.triangles, dtype=np.int64)
        edges = np.asarray(m.boundary_edges, dtype=np.int64)
        refs = np.asarray(m.boundary_refs, dtype=np.int32)
    else:
        x, cells = np.zeros((0, 2)), np.zeros((0, 3), dtype=np.int64)
        edges, refs = np.zeros((0, 2), dtype=np.int64), np.zeros(0, dtype=np.int32)
    domain = ufl.Mesh(ufl.VectorElement("Lagrange", ufl.triangle, 1))
    mesh = dolfinx.mesh.create_mesh(comm, cells, x, domain)
    entities, values = _cpp.io.distribute_entity_data(mesh._mesh, 1, edges, refs)  # 0.5: the C++ mesh
    mesh.topology.create_connectivity(1, 2)
    facets = dolfinx.mesh.meshtags_from_entities(mesh, 1, _cpp.graph.AdjacencyList_int32(entities),
                                                 values.astype(np.int32))
    return mesh, facets


def gather_nodal(mesh, V, uh, n_global, comm=COMM):
    """u_h at our vertices, in our order, on rank 0 (None elsewhere)."""
    gdofs = mesh.geometry.dofmap.array.reshape(-1, 3)
    vdofs = V.dofmap.list.array.reshape(-1, 3)
    node_to_dof = np.empty(mesh.geometry.x.shape[0], dtype=np.int64)
    node_to_dof[gdofs.ravel()] = vdofs.ravel()
    original = np.asarray(mesh.geometry.input_global_indices, dtype=np.int64)
    parts = comm.gather((original, uh.x.array[node_to_dof].copy()), root=0)
    if comm.rank != 0:
        return None
    u = np.full(n_global, np.nan)
    for idx, val in parts:
        u[idx] = val
    assert np.isfinite(u).all(), "a vertex got no value"
    return u


# --- 3. DOLFINx's solve and errors ------------------------------------------------------------

def solve(problem, mesh, facets, degree=4, comm=COMM, errors=True):
    t0 = time.perf_counter()
    V = dolfinx.fem.FunctionSpace(mesh, ("Lagrange", 1))
    x = ufl.SpatialCoordinate(mesh)
    u_bc = dolfinx.fem.Function(V)
    u_bc.interpolate(problem.exact_numpy)  # nodal values, as ablmg's Dirichlet data
    dofs = dolfinx.fem.locate_dofs_topological(V, 1, facets.indices)  # every ref: u = u_exact
    bc = dolfinx.fem.dirichletbc(u_bc, dofs)
    u, v = ufl.TrialFunction(V), ufl.TestFunction(V)
    a = ufl.inner(ufl.grad(u), ufl.grad(v)) * ufl.dx
    f = problem.f_ufl(x)
    zero = dolfinx.fem.Constant(mesh, PETSc.ScalarType(0))
    L = (f if f is not None else zero) * v * ufl.dx(metadata={"quadrature_degree": 5})  # ablmg: degree 5
    lp = dolfinx.fem.petsc.LinearProblem(a, L, bcs=[bc], petsc_options={
        "ksp_type": "cg", "pc_type": "hypre", "pc_hypre_type": "boomeramg", "ksp_rtol": 1e-12, "ksp_atol": 1e-16,
        "ksp_max_it": 1000})
    uh = lp.solve()
    reason = lp.solver.getConvergedReason()
    assert reason > 0, f"PETSc KSP did not converge (reason {reason})"
    t_solve = time.perf_counter() - t0

    t0 = time.perf_counter()
    if not errors:
        return V, uh, (math.nan,) * 4, t_solve, 0.0, lp.solver.getIterationNumber()
    W = dolfinx.fem.FunctionSpace(mesh, ("Lagrange", degree))
    ue = dolfinx.fem.Function(W)
    ue.interpolate(problem.exact_numpy)
    dx8 = ufl.dx(metadata={"quadrature_degree": 8})

    def norms(exact):
        e = uh - exact
        return [math.sqrt(comm.allreduce(dolfinx.fem.assemble_scalar(dolfinx.fem.form(q * dx8)), op=MPI.SUM))
                for q in (e * e, ufl.inner(ufl.grad(e), ufl.grad(e)))]

    # The errors: against the degree-4 interpolant; and against the exact expression at the
    # quadrature points, which is how ablmg measures (fem/error_norms.hpp): the two differ by
    # the interpolant's own error, a few % in H1 on the corner triangle of the L-shape.
    l2, h1 = norms(ue)
    l2x, h1x = norms(problem.exact_ufl(x))
    t_err = time.perf_counter() - t0
    return V, uh, (l2, h1, l2x, h1x), t_solve, t_err, lp.solver.getIterationNumber()


def wait_for_root():
    """Other ranks wait without spinning (a blocking MPI call busy-polls a core that rank 0's
    OpenMP threads need while it remeshes)."""
    req = COMM.Ibarrier()
    while not req.Test():
        time.sleep(0.002)


# --- 4. The loop --------------------------------------------------------------------------------

def run_loop(problem, targets, out_dir, verify=False, errors=True, metric_quantum=None):
    domain = ablmg.Domain.problem(problem.name)
    options = ablmg.MeshOptions("adapt")
    rows = []
    t0 = time.perf_counter()
    m = ablmg.uniform_mesh(domain, targets[0], options=options) if ROOT else None
    t_mesh = time.perf_counter() - t0
    for k in range(len(targets)):
        if not ROOT:
            wait_for_root()
        else:
            COMM.Ibarrier().Wait()
        mesh, facets = to_dolfinx(m)
        V, uh, (l2, h1, l2x, h1x), t_solve, t_err, its = solve(problem, mesh, facets, errors=errors)
        t_solve = COMM.allreduce(t_solve, op=MPI.MAX)
        n_global = COMM.bcast(m.num_vertices if ROOT else None, root=0)
        u = gather_nodal(mesh, V, uh, n_global)
        if verify and COMM.size > 1 and ROOT:  # the same mesh solved on rank 0 alone
            ms, fs = to_dolfinx(m, MPI.COMM_SELF)
            Vs, us, errs, _, _, _ = solve(problem, ms, fs, comm=MPI.COMM_SELF)
            u_serial = gather_nodal(ms, Vs, us, n_global, MPI.COMM_SELF)
            du = np.abs(u - u_serial).max() / np.abs(u_serial).max()
            de = max(abs(l2 / errs[0] - 1), abs(h1 / errs[1] - 1))
            print(f"  verify: {COMM.size}-rank u_h against rank 0 alone on this mesh: max |du|/|u| {du:.1e}, "
                  f"errors {de:.1e} apart", flush=True)
            if du > 1e-8 or de > 1e-8:
                VERIFY_FAILURES.append(f"{problem.name} cycle {k}: distributed solve differs from the serial one "
                                       f"(u {du:.1e}, errors {de:.1e})")
        row = {"cycle": k, "vertices": n_global, "triangles": COMM.bcast(m.num_triangles if ROOT else None, root=0),
               "l2_error": l2, "h1_error": h1, "l2_error_expr": l2x, "h1_error_expr": h1x, "t_mesh": t_mesh, "t_solve": t_solve, "t_errors": t_err,
               "ksp_iterations": its, "ranks": COMM.size}
        rows.append(row)
        if ROOT:
            print(f"Cycle {k}: N={row['vertices']} T={row['triangles']} L2={l2:.3e} H1={h1:.3e}  t: remesh "
                  f"{t_mesh:.2f}s DOLFINx solve {t_solve:.2f}s ({its} CG its, {COMM.size} ranks) errors {t_err:.2f}s",
                  flush=True)
        if k + 1 == len(targets):
            break
        t0 = time.perf_counter()
        if ROOT:
            metric = ablmg.hessian_metric(m.points, m.triangles, u, targets[k + 1])
            m = ablmg.remesh(m.points, m.triangles, metric, m.boundary_edges, m.boundary_refs, domain=domain,
                             options=options, metric_quantum=metric_quantum)
        t_mesh = time.perf_counter() - t0
    if ROOT:
        write_csv(out_dir / f"{problem.name}.csv", rows)
    return rows


def write_csv(path, rows):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)


def read_csv(path):
    with open(path) as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


# --- 5. Against `ablmg adapt` -------------------------------------------------------------------

def loglog_at(xs, ys, x):
    """y(x) by log-log interpolation of the curve (xs increasing), extrapolated at the ends."""
    lx, ly = np.log(xs), np.log(ys)
    i = int(np.clip(np.searchsorted(lx, math.log(x)) - 1, 0, len(lx) - 2))
    t = (math.log(x) - lx[i]) / (lx[i + 1] - lx[i]) if lx[i + 1] != lx[i] else 0.0
    return math.exp(ly[i] + t * (ly[i + 1] - ly[i]))


def compare(problem, targets, rows, out_dir, ablmg_bin):
    """ablmg adapt with the same schedule; DOLFINx on each of its meshes. Rank 0 runs ablmg."""
    adapt_dir = out_dir / f"{problem.name}_ablmg_adapt"
    if ROOT:
        subprocess.run([str(ablmg_bin), "adapt", "--problem", problem.name, "--target-vertices",
                        ",".join(str(int(t)) for t in targets), "--dual-weight", "0", "--h1-weight", "0",
                        "--dual-share", "0", "--saddle-shape", "0", "--uniform", "off", "--vtu", "off",
                        "--medit", "on", "--out-dir", str(adapt_dir)], check=True, stdout=subprocess.DEVNULL)
        ours = read_csv(adapt_dir / "convergence.csv")
        COMM.Ibarrier().Wait()
    else:
        wait_for_root()
    same = []
    for k in range(len(targets)):
        m = ablmg.read_mesh(str(adapt_dir / f"cycle_{k}.mesh")) if ROOT else None
        mesh, facets = to_dolfinx(m)
        _, _, errors, _, _, _ = solve(problem, mesh, facets)
        same.append(errors)
    if not ROOT:
        return None
    table = []
    n_ours = np.array([r["vertices"] for r in ours])
    for k, r in enumerate(rows):
        o = ours[k]
        table.append({
            "cycle": k, "target": int(targets[k]), "dolfinx_vertices": r["vertices"], "dolfinx_l2": r["l2_error"],
            "dolfinx_h1": r["h1_error"], "ablmg_vertices": int(o["vertices"]), "ablmg_l2": o["l2_error"],
            "ablmg_h1": o["h1_error"],
            # the loops at equal N: ablmg adapt's curve interpolated (log-log) at DOLFINx's N
            "l2_ratio": r["l2_error"] / loglog_at(n_ours, [x["l2_error"] for x in ours], r["vertices"]),
            "h1_ratio": r["h1_error"] / loglog_at(n_ours, [x["h1_error"] for x in ours], r["vertices"]),
            # the solvers on identical meshes (ablmg adapt's cycle k)
            "same_mesh_l2_ratio": same[k][0] / o["l2_error"], "same_mesh_h1_ratio": same[k][1] / o["h1_error"],
            # the same, DOLFINx's errors measured as ablmg's (exact expression at the quadrature points)
            "same_mesh_l2_ratio_expr": same[k][2] / o["l2_error"],
            "same_mesh_h1_ratio_expr": same[k][3] / o["h1_error"]})
    write_csv(out_dir / f"{problem.name}_compare.csv", table)
    curves = {"DOLFINx loop L2": ([r["vertices"] for r in rows], [r["l2_error"] for r in rows]),
              "DOLFINx loop H1": ([r["vertices"] for r in rows], [r["h1_error"] for r in rows]),
              "ablmg adapt L2": (list(n_ours), [x["l2_error"] for x in ours]),
              "ablmg adapt H1": (list(n_ours), [x["h1_error"] for x in ours])}
    ablmg.loglog_plot(str(out_dir / f"{problem.name}.png"), curves, slopes=[-0.5, -1.0], xlabel="vertices N",
                      ylabel="error", title=f"{problem.name}: DOLFINx in the loop vs ablmg adapt")
    with open(out_dir / f"{problem.name}.md", "w") as f:
        f.write("| cycle | N DOLFINx loop | L2 | H1 | N ablmg adapt | L2 | H1 | L2 ratio at equal N | H1 ratio "
                "| same mesh: L2 ratio | H1 ratio | same mesh, ablmg's measure: L2 | H1 |\n"
                "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n")
        for t in table:
            f.write(f"| {t['cycle']} | {t['dolfinx_vertices']} | {t['dolfinx_l2']:.3e} | {t['dolfinx_h1']:.3e} | "
                    f"{t['ablmg_vertices']} | {t['ablmg_l2']:.3e} | {t['ablmg_h1']:.3e} | {t['l2_ratio']:.3f} | "
                    f"{t['h1_ratio']:.3f} | {t['same_mesh_l2_ratio']:.4f} | {t['same_mesh_h1_ratio']:.4f} | "
                    f"{t['same_mesh_l2_ratio_expr']:.5f} | {t['same_mesh_h1_ratio_expr']:.5f} |\n")
    for t in table:
        print(f"  cycle {t['cycle']}: DOLFINx loop / ablmg adapt at equal N: L2 {t['l2_ratio']:.3f} H1 "
              f"{t['h1_ratio']:.3f};  DOLFINx / ablmg on the same mesh: L2 {t['same_mesh_l2_ratio']:.5f} "
              f"H1 {t['same_mesh_h1_ratio']:.5f} (measured as ablmg: L2 {t['same_mesh_l2_ratio_expr']:.5f} "
              f"H1 {t['same_mesh_h1_ratio_expr']:.5f})")
    return table


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--problem", default="all", choices=["wavefront", "lshape", "all"])
    ap.add_argument("--target-vertices", default="1000,2000,4000,8000,16000,32000,64000,100000")
    ap.add_argument("--out-dir", default=str(REPO / "out" / "dolfinx"))
    ap.add_argument("--compare", action="store_true", help="also run ablmg adapt and solve on its meshes")
    ap.add_argument("--ablmg", default=os.environ.get("ABLMG_BIN", str(REPO / "build" / "bin" / "ablmg")))
    ap.add_argument("--reference", help="directory of an earlier run's CSVs (e.g. serial) to compare with")
    ap.add_argument("--reference-error-tol", type=float, default=0.01,
                    help="relative tolerance on the errors against --reference after cycle 0 (default 1 %%)")
    ap.add_argument("--check", action="store_true", help="assert the properties the CTest tests check")
    ap.add_argument("--metric-quantum", type=float, default=None,
                    help="snap the metric to a grid of this step before remeshing (e.g. 0.00390625 = 2^-8; "
                         "adapt/metric_snap.hpp), so that the round-off of a distributed solve cannot change "
                         "the mesh; off by default, as in ablmg adapt, whose meshes the default run reproduces")
    ap.add_argument("--no-errors", action="store_true", help="skip the error norms (timing runs at 10^6)")
    args = ap.parse_args()
    targets = [float(t) for t in args.target_vertices.split(",")]
    out_dir = pathlib.Path(args.out_dir)
    if ROOT:
        out_dir.mkdir(parents=True, exist_ok=True)
        print(f"dolfinx_adaptive: DOLFINx {dolfinx.__version__}, {COMM.size} MPI rank(s), ablmg {ablmg.__version__}; "
              f"targets {args.target_vertices}; output {out_dir}", flush=True)
    failures = []
    for name in (["wavefront", "lshape"] if args.problem == "all" else [args.problem]):
        problem = PROBLEMS[name]
        if ROOT:
            print(f"== {name}", flush=True)
        rows = run_loop(problem, targets, out_dir, verify=args.check, errors=not args.no_errors,
                        metric_quantum=args.metric_quantum)
        table = compare(problem, targets, rows, out_dir, args.ablmg) if args.compare else None
        if not (ROOT and args.check):
            continue
        if not (rows[-1]["l2_error"] < rows[0]["l2_error"] and rows[-1]["h1_error"] < rows[0]["h1_error"]):
            failures.append(f"{name}: errors do not fall")
        if table:
            for t in table[1:]:  # cycle 0 is the same uniform mesh in both loops
                if abs(t["l2_ratio"] - 1) > 0.10 or abs(t["h1_ratio"] - 1) > 0.10:
                    failures.append(f"{name} cycle {t['cycle']}: DOLFINx loop / ablmg adapt L2 {t['l2_ratio']:.3f} "
                                    f"H1 {t['h1_ratio']:.3f} (more than 10 % apart)")
            for t in table:  # the two solvers on one mesh, errors measured alike
                if abs(t["same_mesh_l2_ratio_expr"] - 1) > 1e-3 or abs(t["same_mesh_h1_ratio_expr"] - 1) > 1e-3:
                    failures.append(f"{name} cycle {t['cycle']}: DOLFINx and ablmg on the same mesh differ: "
                                    f"L2 {t['same_mesh_l2_ratio_expr']:.6f} H1 {t['same_mesh_h1_ratio_expr']:.6f}")
            if table[0]["dolfinx_vertices"] != table[0]["ablmg_vertices"]:
                failures.append(f"{name}: cycle 0 meshes differ ({table[0]['dolfinx_vertices']} vs "
                                f"{table[0]['ablmg_vertices']} vertices)")
        if args.reference:
            ref = read_csv(pathlib.Path(args.reference) / f"{name}.csv")
            for r, s in zip(rows, ref):
                for key in ("vertices", "l2_error", "h1_error"):
                    # cycle 0 is the same mesh: its errors agree to the solver's tolerance
                    tol = 0.01 if key == "vertices" else 1e-6 if r["cycle"] == 0 else args.reference_error_tol
                    if abs(r[key] / s[key] - 1) > tol:
                        failures.append(f"{name} cycle {r['cycle']}: {key} {r[key]} vs reference {s[key]} "
                                        f"(more than {tol:g} apart)")
            print(f"  against {args.reference}: " + ", ".join(
                f"cycle {r['cycle']} N {r['vertices']}/{int(s['vertices'])} L2 {r['l2_error'] / s['l2_error']:.4f} "
                f"H1 {r['h1_error'] / s['h1_error']:.4f}" for r, s in zip(rows, ref)))
    failures += VERIFY_FAILURES
    if ROOT:
        for f in failures:
            print("CHECK FAILED:", f, file=sys.stderr)
    failed = COMM.bcast(bool(failures) if ROOT else None, root=0)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""Checks that a remeshed medit mesh keeps the input's regions (triangle references).

    check_regions.py IN.mesh OUT.mesh [--exact]

For every triangle reference: the area it covers in OUT is within 1 % of its area in IN (the
remesher resamples a boundary or interface polyline between its corners, at a 30 degree turn,
so chords cut the input's vertices there: docs/mmg_flags.md), or within 1e-9 of the total with
--exact (-nosurf: interfaces kept as the input's edges); and every OUT triangle's centroid lies
in an IN triangle of its own reference (with --exact also its three points at 0.9 of the way
from the centroid to a vertex). Prints one line, exits 1 on failure.
"""
import sys

import numpy as np


def read_medit(path):
    text = open(path, encoding="latin-1").read().replace("\r", " ")
    toks = " ".join(line.split("#")[0] for line in text.split("\n")).split()
    i, dim, verts, tris = 0, 2, None, []
    while i < len(toks):
        kw = toks[i].lower()
        i += 1
        if kw == "dimension":
            dim = int(toks[i]); i += 1
        elif kw == "vertices":
            n = int(toks[i]); i += 1
            a = np.array(toks[i:i + n * (dim + 1)], dtype=float).reshape(n, dim + 1)
            verts = a[:, :2]; i += n * (dim + 1)
        elif kw == "triangles":
            n = int(toks[i]); i += 1
            tris = np.array(toks[i:i + 4 * n], dtype=np.int64).reshape(n, 4); i += 4 * n
        elif kw == "end":
            break
    return verts, tris[:, :3] - 1, tris[:, 3]


def areas(v, t):
    a, b, c = v[t[:, 0]], v[t[:, 1]], v[t[:, 2]]
    return 0.5 * np.abs((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0]))


def locate(v, t, pts):
    """Index of an IN triangle containing each point (-1 if none), by a bucket grid."""
    lo, hi = v.min(0), v.max(0)
    nb = max(1, int(np.sqrt(len(t))))
    cell = (hi - lo) / nb + 1e-300
    tmin = v[t].min(1); tmax = v[t].max(1)
    buckets = {}
    for k in range(len(t)):
        i0, j0 = ((tmin[k] - lo) / cell).astype(int)
        i1, j1 = ((tmax[k] - lo) / cell).astype(int)
        for i in range(i0, min(i1, nb - 1) + 1):
            for j in range(j0, min(j1, nb - 1) + 1):
                buckets.setdefault((i, j), []).append(k)
    out = np.full(len(pts), -1)
    for p, q in enumerate(pts):
        i, j = np.minimum(((q - lo) / cell).astype(int), nb - 1)
        for k in buckets.get((i, j), []):
            a, b, c = v[t[k]]
            d = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
            l1 = ((b[0] - q[0]) * (c[1] - q[1]) - (b[1] - q[1]) * (c[0] - q[0])) / d
            l2 = ((c[0] - q[0]) * (a[1] - q[1]) - (c[1] - q[1]) * (a[0] - q[0])) / d
            if min(l1, l2, 1 - l1 - l2) >= -1e-12:
                out[p] = k
                break
    return out


def main():
    vi, ti, ri = read_medit(sys.argv[1])
    vo, to, ro = read_medit(sys.argv[2])
    ai, ao = areas(vi, ti), areas(vo, to)
    total = ai.sum()
    bad = []
    exact = "--exact" in sys.argv
    for r in sorted(set(ri) | set(ro)):
        a, b = ai[ri == r].sum(), ao[ro == r].sum()
        if abs(a - b) > (1e-9 * total if exact else 0.01 * a):
            bad.append(f"ref {r}: area {a:.12g} in, {b:.12g} out")
    cen = vo[to].mean(1)
    pts = [cen] + ([cen + 0.9 * (vo[to[:, k]] - cen) for k in range(3)] if exact else [])
    for p in pts:
        k = locate(vi, ti, p)
        wrong = np.nonzero((k < 0) | (ri[np.maximum(k, 0)] != ro))[0]
        if len(wrong):
            bad.append(f"{len(wrong)} triangles with points outside their region (first: {wrong[0] + 1})")
            break
    if bad:
        print("FAIL regions:", "; ".join(bad))
        return 1
    drift = max(abs(ai[ri == r].sum() - ao[ro == r].sum()) / ai[ri == r].sum() for r in set(ri))
    print(f"ok regions: {len(set(ro))} refs, area drift {drift:.2g}, {len(to)} triangles each inside its region")
    return 0


if __name__ == "__main__":
    sys.exit(main())

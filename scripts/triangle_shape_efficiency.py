#!/usr/bin/python3
"""How far a mesh's triangles are from the equilateral ones in the H1 error of P1 interpolation,
on a corner problem (u = r^a sin(a theta), a = pi/omega; every Hessian a saddle, |H| isotropic).

    scripts/triangle_shape_efficiency.py MESH.mesh [OMEGA]

MESH: a medit mesh of the wedge (-1,1)^2 without the sector omega < theta < 2 pi (OMEGA, default
3 pi / 2: the L-shape), e.g. an `ablmg adapt --medit on` cycle or FreeFem++'s final mesh of
examples/compare_freefem/run.sh. Per triangle T: e(T) = |q - I_h q|^2_{H1(T)} for the quadratic
q with u's Hessian at T's centroid (exact for it: a 3-point edge-midpoint rule), and the
efficiency eff(T) = e(T) / (the same for an equilateral triangle of T's area) = e / (lam^2 |T|^2
/ (6 sqrt(3)/4)), lam = |eigenvalue of H|. An equilateral triangle has eff 1 whatever its
orientation; the best P1 triangle for a saddle (right isosceles, legs along H's eigenvectors)
0.866 (scripts/saddle_triangle_shape.py). Prints the H1^2-weighted mean of eff, overall and by
bands of the distance r to the corner, and the Euclidean quality.
"""
import sys, numpy as np
from medit_arrays import read_medit
omega = float(sys.argv[2]) if len(sys.argv) > 2 else 1.5 * np.pi
a = np.pi / omega
P, T = read_medit(sys.argv[1])
X = P[T]; c = X.mean(1)
r = np.hypot(c[:, 0], c[:, 1]); th = np.arctan2(c[:, 1], c[:, 0]); th = np.where(th < 0, th + 2 * np.pi, th)
# u = Im z^a: u_xx = Im f'', u_xy = Re f'', u_yy = -Im f'', f'' = a (a-1) z^(a-2)
f2 = a * (a - 1) * r**(a - 2) * np.exp(1j * (a - 2) * th)
lam = np.abs(f2)
H = np.zeros((len(T), 2, 2)); H[:, 0, 0] = f2.imag; H[:, 1, 1] = -f2.imag; H[:, 0, 1] = H[:, 1, 0] = f2.real
d1 = X[:, 1] - X[:, 0]; d2 = X[:, 2] - X[:, 0]; A = 0.5 * np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
q1 = 0.5 * np.einsum('ti,tij,tj->t', d1, H, d1); q2 = 0.5 * np.einsum('ti,tij,tj->t', d2, H, d2)
g = np.linalg.solve(np.stack([d1, d2], 1), np.stack([q1, q2], 1)[..., None])[..., 0]
mids = [(d1) / 2, (d1 + d2) / 2, d2 / 2]
e = sum(np.sum((np.einsum('tij,tj->ti', H, m) - g)**2, 1) for m in mids) / 3 * A
eff = e / (lam**2 * A**2) * (np.sqrt(3) / 4) * 6
l2 = np.sum(d1**2, 1) + np.sum(d2**2, 1) + np.sum((X[:, 2] - X[:, 1])**2, 1); qE = 4 * np.sqrt(3) * A / l2
print(f"{sys.argv[1]}: {len(T)} triangles, H1^2-weighted efficiency {np.sum(e * eff) / e.sum():.4f}, "
      f"Euclidean quality mean {qE.mean():.4f}")
for lo, hi in [(0, 1e-3), (1e-3, 1e-2), (1e-2, 0.1), (0.1, 0.3), (0.3, 1), (1, 3)]:
    s = (r >= lo) & (r < hi)
    if s.any():
        print(f"  r in [{lo:g}, {hi:g}): H1^2 share {e[s].sum() / e.sum():.3f}, efficiency {np.sum(e[s] * eff[s]) / e[s].sum():.4f}, quality {qE[s].mean():.4f}")

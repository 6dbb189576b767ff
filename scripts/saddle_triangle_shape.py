#!/usr/bin/python3
"""The P1 triangle of least H1 interpolation error per unit area for a quadratic with Hessian H.

    scripts/saddle_triangle_shape.py

For H = diag(1, -1) (a saddle, as every harmonic function's) and H = I: the error of
equilateral triangles at several rotations, the best triangle found (Nelder-Mead from 30 starts),
and for metrics of aspect sqrt(a) with axes at 45 degrees to H's eigenvectors, the spread of the
error of their metric-equilateral triangles over the lattice angle. Then the lattices the
placement can build (mesher/initial_placement.hpp: one row along the short or the long axis):
short-axis rows with the long axis along an eigenvector of H (best aspect 1.367: 7.3 % less
H1^2 than equilateral), and the right isosceles long-axis lattice turned by 0-30 degrees.
"""
import numpy as np
from scipy.optimize import minimize
# error of P1 interpolation of q(x)=0.5 x^T H x on triangle, H1 seminorm squared, per area, for area fixed = sqrt(3)/4 (equilateral side 1)
rng=np.random.default_rng(0)
# quadrature exact for quadratics of gradient (degree 2): use 3-point midpoints rule (exact deg 2)
def err(V,H):
    x0,x1,x2=V; d1=x1-x0; d2=x2-x0; det=d1[0]*d2[1]-d1[1]*d2[0]; A=abs(det)/2
    q=lambda x: 0.5*x@H@x
    Gm=np.array([[d1[0],d2[0]],[d1[1],d2[1]]])
    # interpolant gradient: solve Gm^T g = [q1-q0,q2-q0]
    g=np.linalg.solve(Gm.T, np.array([q(x1)-q(x0), q(x2)-q(x0)]))
    mids=[(x0+x1)/2,(x1+x2)/2,(x2+x0)/2]
    e=sum(np.sum((H@m-g)**2) for m in mids)/3*A
    return e/A
def tri(p):
    # p = (a,b,c) parametrize triangle with vertices (0,0),(a,0),(b,c) scaled to area sqrt3/4
    a,b,c=p; V=np.array([[0,0],[a,0],[b,c]],float); A=abs(a*c)/2
    return V*np.sqrt((np.sqrt(3)/4)/A)
eq=np.array([[0,0],[1,0],[0.5,np.sqrt(3)/2]])
for name,H in [("saddle",np.diag([1.,-1.])),("convex",np.diag([1.,1.]))]:
    best=None
    for th in np.linspace(0,np.pi/3,7):
        R=np.array([[np.cos(th),-np.sin(th)],[np.sin(th),np.cos(th)]])
        print(name,"equilateral rot",round(th,2),err(eq@R.T,H))
    for k in range(30):
        p0=rng.uniform(0.3,2,3)
        r=minimize(lambda p: err(tri(p),H), p0, method='Nelder-Mead',options={'xatol':1e-9,'fatol':1e-12,'maxiter':4000})
        if best is None or r.fun<best.fun: best=r
    V=tri(best.x); e=[np.linalg.norm(V[1]-V[0]),np.linalg.norm(V[2]-V[1]),np.linalg.norm(V[0]-V[2])]
    print(name,"best",best.fun,"edges",np.round(e,3),"verts",np.round(V,3).tolist())
print("--- metric-equilateral triangles for M with axes at 45deg to H's, aspect sqrt3, versus lattice angle phi")
H=np.diag([1.,-1.])
for asp2 in [1.0, 1.5, 2.0, 3.0]:
    l1=np.sqrt(asp2); l2=1/np.sqrt(asp2)  # eigenvalues of M (det 1)
    c=np.cos(np.pi/4); R=np.array([[c,-c],[c,c]])
    M=R@np.diag([l2,l1])@R.T  # small eigenvalue (long size) along (1,1)
    Lm=np.linalg.cholesky(np.linalg.inv(M))  # maps metric space -> physical
    es=[]
    for phi in np.linspace(0,np.pi/3,13):
        Rp=np.array([[np.cos(phi),-np.sin(phi)],[np.sin(phi),np.cos(phi)]])
        V=(eq@Rp.T)@Lm.T
        es.append(err(V,H))
    print(f"aspect^2 {asp2}: min {min(es):.4f} max {max(es):.4f} mean {np.mean(es):.4f}")
# The loop's lattice (mesher Adapt preset: one row along each node's short-size direction,
# fully aligned from an aspect h1/h2 of 1.5 on): for the same saddle, the metric of aspect a with
# its long axis along an eigenvector of H, its hexagonal lattice turned so that a row runs along
# the short axis; and, for the long-axis lattice, the cost of a misoriented lattice.
print("--- short-axis lattice, long axis along an eigenvector of H = diag(1,-1): error vs aspect")
def lattice_tri(aspect, theta, phi):
    # one triangle of the lattice M^(-1/2) Q(phi) (unit hexagonal), M of sizes sqrt(a), 1/sqrt(a)
    R = lambda t: np.array([[np.cos(t), -np.sin(t)], [np.sin(t), np.cos(t)]])
    L = R(theta) @ np.diag([np.sqrt(aspect), 1 / np.sqrt(aspect)]) @ R(phi - theta)
    return np.array([[0, 0], L @ [1, 0], L @ [0.5, np.sqrt(3) / 2]])
for a in [1.0, 1.2, 1.367, 1.5, 1.7]:
    print(f"aspect {a}: {err(lattice_tri(a, 0.0, np.pi / 2), H):.4f}")
print("--- long-axis lattice, aspect sqrt3 at 45 degrees (the right isosceles one): error vs misorientation")
for d in [0, 5, 10, 20, 30]:
    print(f"{d} degrees: {err(lattice_tri(np.sqrt(3), np.pi / 4, np.pi / 4 + np.radians(d)), H):.4f}")
# Saddles that are not harmonic, H = diag(1, -beta), with the loop's shape S (eigenvalues
# |lambda|^1.05, det 1): the plain metric S with rows along its short axis (g = 0, w = 0) against
# the saddle correction S^(1/2) C S^(1/2) (C of aspect 3^(g/2) at 45 degrees) with its rows turned
# by the fraction w towards t = S^(-1/2) c1 (adapt/metric_from_hessian.hpp, saddleLatticeRows;
# w = 1: the mesher's switch). Why the saddle weight ramps over ratios 0.55-0.65 only and the
# rows switch rather than turn: the correction pays from beta ~ 0.6 on, and half-way is worse
# than either end.
print("--- non-harmonic saddles: plain (g=0,w=0), corrected (g=1,w=1), both ramped over 0.6-0.8")
def rot(a): return np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]])
def rows_tri(M, t, w):
    lam, V = np.linalg.eigh(M); Mh = V @ np.diag(np.sqrt(lam)) @ V.T
    ps = np.arctan2(*(Mh @ V[:, 1])[::-1]); pr = np.arctan2(*(Mh @ t)[::-1])
    d = pr - ps; d -= np.pi / 3 * np.round(d / (np.pi / 3))
    T = (eq @ rot(ps + w * d).T) @ np.linalg.inv(Mh).T
    return T * np.sqrt((np.sqrt(3) / 4) / (abs(np.cross(T[1] - T[0], T[2] - T[0])) / 2))
for beta in [1, 0.8, 0.75, 0.7, 0.65, 0.6, 0.5, 0.25]:
    H = np.diag([1., -beta]); S = np.diag([1., beta**1.05]); S /= np.sqrt(np.linalg.det(S)); Sh = np.sqrt(S)
    t = np.array([1 / Sh[0, 0], 1 / Sh[1, 1]]); t /= np.linalg.norm(t)
    def corrected(g, w):
        f = 3**(0.25 * g); C = rot(np.pi / 4) @ np.diag([1 / f**2, f**2]) @ rot(np.pi / 4).T
        return err(rows_tri(Sh @ C @ Sh, t, w), H)
    ramp = np.clip((beta - 0.6) / 0.2, 0, 1)
    print(f"beta {beta}: plain {corrected(0, 0):.4f} corrected {corrected(1, 1):.4f} ramped {corrected(ramp, ramp):.4f}")

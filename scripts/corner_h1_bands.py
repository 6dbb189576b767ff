#!/usr/bin/python3
"""Where the H1 error of a P1 solve of a corner problem lies, by distance r to the corner.

    scripts/corner_h1_bands.py MESH.mesh [OMEGA]

MESH: a medit mesh of the wedge (-1,1)^2 without the sector omega < theta < 2 pi (OMEGA, default
3 pi / 2: the L-shape), e.g. an `ablmg adapt --problem lshape --medit on` cycle or FreeFem++'s
final mesh of examples/compare_freefem/run.sh. Solves -Lap u = 0 with u = r^(pi/omega)
sin(pi theta/omega) on the boundary (P1, scipy), then prints the H1 and L2 errors (quadrature:
a degree-5 rule on 16 sub-triangles), the H1^2 and L2^2 shares and mean size of each band of r,
the interpolant's H1 error and the Euclidean quality.
"""
import sys, numpy as np, scipy.sparse as sp, scipy.sparse.linalg as spl
from medit_arrays import read_medit
omega = float(sys.argv[2]) if len(sys.argv) > 2 else 1.5*np.pi
a = np.pi/omega
def ang(x,y):
    t = np.arctan2(y,x); t = np.where(t<0, t+2*np.pi, t)
    t = np.where(t>omega, np.where(t>0.5*(omega+2*np.pi), 0.0, omega), t); return t
def u(x,y):
    r=np.hypot(x,y); return r**a*np.sin(a*ang(x,y))
def gu(x,y):
    r=np.hypot(x,y); t=ang(x,y); c=a*r**(a-1)
    return np.stack([c*np.sin((a-1)*t), c*np.cos((a-1)*t)],-1)
P,T=read_medit(sys.argv[1])
n=len(P)
# boundary vertices: edges used once
e = np.sort(np.concatenate([T[:,[0,1]],T[:,[1,2]],T[:,[2,0]]]),axis=1)
ue, cnt = np.unique(e, axis=0, return_counts=True)
bv = np.unique(ue[cnt==1])
x0=P[T[:,0]]; x1=P[T[:,1]]; x2=P[T[:,2]]
d1=x1-x0; d2=x2-x0; det=d1[:,0]*d2[:,1]-d1[:,1]*d2[:,0]; area=0.5*np.abs(det)
# gradients of barycentric
G = np.zeros((len(T),3,2))
G[:,1,0]= d2[:,1]/det; G[:,1,1]=-d2[:,0]/det
G[:,2,0]=-d1[:,1]/det; G[:,2,1]= d1[:,0]/det
G[:,0]=-G[:,1]-G[:,2]
K = np.einsum('tid,tjd->tij',G,G)*area[:,None,None]
rows=np.repeat(T,3,axis=1).ravel(); cols=np.tile(T,(1,3)).ravel()
A=sp.csr_matrix((K.ravel(),(rows,cols)),shape=(n,n))
uh=np.zeros(n); uh[bv]=u(P[bv,0],P[bv,1])
free=np.setdiff1d(np.arange(n),bv)
rhs=-A[free][:,bv]@uh[bv]
uh[free]=spl.spsolve(A[free][:,free].tocsc(),rhs)
gh=np.einsum('ti,tid->td',uh[T],G)
# quadrature: Dunavant degree 5 (7 pts) on subdivided triangles (4 subtriangles)
q=np.array([[1/3,1/3,0.225],[0.0597158717,0.4701420641,0.1323941527],[0.4701420641,0.0597158717,0.1323941527],[0.4701420641,0.4701420641,0.1323941527],[0.7974269853,0.1012865073,0.1259391805],[0.1012865073,0.7974269853,0.1259391805],[0.1012865073,0.1012865073,0.1259391805]])
# subdivide ref triangle into 16
N=4; subs=[]
for i in range(N):
    for j in range(N-i):
        subs.append(((i,j),(i+1,j),(i,j+1)))
        if i+j<N-1: subs.append(((i+1,j),(i+1,j+1),(i,j+1)))
qp=[];qw=[]
for s in subs:
    v=np.array(s,float)/N
    for (l1,l2,w) in q:
        p=v[0]+l1*(v[1]-v[0])+l2*(v[2]-v[0]); qp.append(p); qw.append(w/len(subs))
qp=np.array(qp); qw=np.array(qw)
err=np.zeros(len(T)); l2=np.zeros(len(T))
for (s,t),w in zip(qp,qw):
    X=x0+s*d1+t*d2
    g=gu(X[:,0],X[:,1]); err+=w*np.sum((g-gh)**2,1)
    uhq = uh[T[:,0]]*(1-s-t)+uh[T[:,1]]*s+uh[T[:,2]]*t
    l2+=w*(u(X[:,0],X[:,1])-uhq)**2
err*=area; l2*=area
c=(x0+x1+x2)/3; r=np.hypot(c[:,0],c[:,1])
print(f"{sys.argv[1]}: N={n} T={len(T)} H1={np.sqrt(err.sum()):.4e} L2={np.sqrt(l2.sum()):.4e}")
edges=[0,1e-5,1e-4,1e-3,1e-2,3e-2,0.1,0.3,1,2]
for lo,hi in zip(edges[:-1],edges[1:]):
    k=(r>=lo)&(r<hi)
    if k.sum()==0: continue
    h=np.sqrt(2*area[k]).mean()
    print(f" r in [{lo:g},{hi:g}): tri {k.sum():6d} share H1^2 {err[k].sum()/err.sum():.3f} H1^2 {err[k].sum():.3e} L2^2 share {l2[k].sum()/l2.sum():.3f} mean h {h:.2e}")
# by boundary adjacency
bt=np.isin(T,bv).any(1)
print(f" boundary-touching tris {bt.sum()} share H1^2 {err[bt].sum()/err.sum():.3f}")
rmin = np.min(np.hypot(P[:,0],P[:,1])[np.hypot(P[:,0],P[:,1])>0])
print(f" nearest vertex to corner r={rmin:.3e}")
# interpolant H1 error
gi=np.einsum('ti,tid->td',u(P[T][:,:,0],P[T][:,:,1]),G)
ei=np.zeros(len(T))
for (s,t),w in zip(qp,qw):
    X=x0+s*d1+t*d2
    ei+=w*np.sum((gu(X[:,0],X[:,1])-gi)**2,1)
ei*=area
print(f" interpolant H1 {np.sqrt(ei.sum()):.4e}  FE/interp {np.sqrt(err.sum()/ei.sum()):.3f}")
# quality
def q_(P,T):
    a_=np.linalg.norm(P[T[:,1]]-P[T[:,0]],axis=1);b_=np.linalg.norm(P[T[:,2]]-P[T[:,1]],axis=1);c_=np.linalg.norm(P[T[:,0]]-P[T[:,2]],axis=1)
    return 4*np.sqrt(3)*area/(a_**2+b_**2+c_**2)
qq=q_(P,T); print(f" euclid q mean {qq.mean():.4f} min {qq.min():.3f}")

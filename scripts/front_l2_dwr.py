#!/usr/bin/python3
"""Where the FE L2 error of the wave front is generated: a dual-weighted split of ||e||^2.

    scripts/front_l2_dwr.py MESH.mesh [ALPHA]

MESH: a medit mesh of (0,1)^2, e.g. an `ablmg adapt --problem wavefront --param alpha=1000
--medit on` cycle or FreeFem++'s final mesh of examples/compare_freefem/run.sh. Solves
-Lap u = f, u = atan(ALPHA (r - 0.7)), r = |x - (-0.05, -0.05)| (ALPHA default 1000; P1, the
load by the 7-point degree-5 rule as fem/assemble.hpp, u exact on the boundary), then the dual
-Lap z = e (e = u - u_h, z = 0 on the boundary) on MESH refined once (z) and on MESH (z_h).
By Galerkin orthogonality ||e||^2 = a(e, z) = sum_T int_T grad e . grad(z - z_h); the sum of the
per-triangle terms recovers about 2/3 of ||e||^2 with the once-refined z on a mesh that resolves
the front (2.8e4 vertices of the adaptive loop; the rest is z's own discretisation error), enough
to see where the error is generated; on meshes that do not resolve it the sum is far off. Prints, per band of
distance d to the front, the triangles, shares of L2^2, H1^2 and of the dual-weighted terms
(signed and absolute), the largest edge and the area.
"""
import sys, numpy as np, scipy.sparse as sp, scipy.sparse.linalg as spl
from medit_arrays import read_medit
al=float(sys.argv[2]) if len(sys.argv)>2 else 1000.; xc=yc=-0.05; r0=0.7
def u(x,y): return np.arctan(al*(np.hypot(x-xc,y-yc)-r0))
def f(x,y):
    r=np.hypot(x-xc,y-yc); s=r-r0; d=1+al*al*s*s
    return -(-2*al**3*s/d**2 + al/d/r)
def gu(x,y):
    r=np.hypot(x-xc,y-yc); s=r-r0; ur=al/(1+al*al*s*s)
    return np.stack([ur*(x-xc)/r, ur*(y-yc)/r],-1)
# the 7-point degree-5 rule (Strang & Fix), barycentric (s, t) and weight
q=np.array([[1/3,1/3,0.225],[0.0597158717,0.4701420641,0.1323941527],[0.4701420641,0.0597158717,0.1323941527],[0.4701420641,0.4701420641,0.1323941527],[0.7974269853,0.1012865073,0.1259391805],[0.1012865073,0.7974269853,0.1259391805],[0.1012865073,0.1012865073,0.1259391805]])
def geom(P,T):
    x0=P[T[:,0]]; d1=P[T[:,1]]-x0; d2=P[T[:,2]]-x0; det=d1[:,0]*d2[:,1]-d1[:,1]*d2[:,0]
    G=np.zeros((len(T),3,2)); G[:,1,0]=d2[:,1]/det; G[:,1,1]=-d2[:,0]/det; G[:,2,0]=-d1[:,1]/det; G[:,2,1]=d1[:,0]/det; G[:,0]=-G[:,1]-G[:,2]
    return x0,d1,d2,0.5*np.abs(det),G
def solve(P,T,load,bcval):
    n=len(P); x0,d1,d2,area,G=geom(P,T)
    K=np.einsum('tid,tjd->tij',G,G)*area[:,None,None]
    rows=np.repeat(T,3,axis=1).ravel(); cols=np.tile(T,(1,3)).ravel()
    A=sp.csr_matrix((K.ravel(),(rows,cols)),shape=(n,n))
    b=np.zeros(n)
    for s,t,w in q:
        X=x0+s*d1+t*d2; fv=load(X,np.arange(len(T)),s,t)
        for k,l in enumerate([1-s-t,s,t]): np.add.at(b,T[:,k],w*area*fv*l)
    e=np.sort(np.concatenate([T[:,[0,1]],T[:,[1,2]],T[:,[2,0]]]),axis=1)
    ue,cnt=np.unique(e,axis=0,return_counts=True); bv=np.unique(ue[cnt==1])
    x=np.zeros(n); x[bv]=bcval(P[bv]); free=np.setdiff1d(np.arange(n),bv)
    rhs=b[free]-A[free][:,bv]@x[bv]; x[free]=spl.spsolve(A[free][:,free].tocsc(),rhs)
    return x,G,area
P,T=read_medit(sys.argv[1]); n=len(P)
uh,G,area=solve(P,T,lambda X,i,s,t: f(X[:,0],X[:,1]),lambda Q:u(Q[:,0],Q[:,1]))
x0,d1,d2,_,_=geom(P,T)
# refine once: midpoints
E=np.sort(np.concatenate([T[:,[0,1]],T[:,[1,2]],T[:,[2,0]]]),axis=1)
ue,inv=np.unique(E,axis=0,return_inverse=True); inv=inv.ravel(); nt=len(T)
m01=n+inv[:nt]; m12=n+inv[nt:2*nt]; m20=n+inv[2*nt:]
Pf=np.vstack([P,0.5*(P[ue[:,0]]+P[ue[:,1]])])
a,b_,c=T[:,0],T[:,1],T[:,2]
Tf=np.vstack([np.stack([a,m01,m20],1),np.stack([m01,b_,m12],1),np.stack([m20,m12,c],1),np.stack([m01,m12,m20],1)])
parent=np.tile(np.arange(nt),4)
# child vertex barycentrics in parent (for evaluating uh at fine quadrature pts)
bary={0:[(0,0),(.5,0),(0,.5)],1:[(.5,0),(1,0),(.5,.5)],2:[(0,.5),(.5,.5),(0,1)],3:[(.5,0),(.5,.5),(0,.5)]}
kind=np.repeat(np.arange(4),nt)
def eload(X,i,s,t):
    par=parent[i]; k=kind[i]; B=np.array([bary[j] for j in range(4)])[k]  # (nf,3,2)
    ps=B[:,0,0]*(1-s-t)+B[:,1,0]*s+B[:,2,0]*t; pt=B[:,0,1]*(1-s-t)+B[:,1,1]*s+B[:,2,1]*t
    uhq=uh[T[par,0]]*(1-ps-pt)+uh[T[par,1]]*ps+uh[T[par,2]]*pt
    return u(X[:,0],X[:,1])-uhq
z,Gf,areaf=solve(Pf,Tf,eload,lambda Q:0*Q[:,0])
# coarse dual z_h: -Lap z_h = e on coarse mesh
zh,_,_=solve(P,T,lambda X,i,s,t: u(X[:,0],X[:,1])-(uh[T[i,0]]*(1-s-t)+uh[T[i,1]]*s+uh[T[i,2]]*t),lambda Q:0*Q[:,0])
# per coarse triangle: int grad e . grad(z - zh), e = u - uh; on fine children (grad z const per child)
gz=np.einsum('ti,tid->td',z[Tf],Gf); gzh=np.einsum('ti,tid->td',zh[T],G)[parent]; guh=np.einsum('ti,tid->td',uh[T],G)[parent]
x0f,d1f,d2f,_,_=geom(Pf,Tf)
ct=np.zeros(len(Tf)); l2=np.zeros(len(Tf)); h1=np.zeros(len(Tf))
for s,t,w in q:
    X=x0f+s*d1f+t*d2f; ge=gu(X[:,0],X[:,1])-guh
    ct+=w*np.sum(ge*(gz-gzh),1); h1+=w*np.sum(ge**2,1)
    l2+=w*eload(X,np.arange(len(Tf)),s,t)**2
ct*=areaf; l2*=areaf; h1*=areaf
C=np.zeros(nt); np.add.at(C,parent,ct); L=np.zeros(nt); np.add.at(L,parent,l2); H=np.zeros(nt); np.add.at(H,parent,h1)
cen=(P[T[:,0]]+P[T[:,1]]+P[T[:,2]])/3; dist=np.abs(np.hypot(cen[:,0]-xc,cen[:,1]-yc)-r0)
print(f"N={n} L2={np.sqrt(L.sum()):.4e} H1={np.sqrt(H.sum()):.4e} sum a(e,z-zh)={C.sum():.4e} (L2^2 {L.sum():.4e})")
hl=np.sqrt(np.max(np.stack([np.sum((P[T[:,1]]-P[T[:,0]])**2,1),np.sum((P[T[:,2]]-P[T[:,1]])**2,1),np.sum((P[T[:,0]]-P[T[:,2]])**2,1)]),0))
for lo,hi in zip([0,1e-4,3e-4,1e-3,3e-3,1e-2,3e-2,0.1,0.3],[1e-4,3e-4,1e-3,3e-3,1e-2,3e-2,0.1,0.3,2]):
    k=(dist>=lo)&(dist<hi)
    print(f" d in [{lo:g},{hi:g}): tri {k.sum():6d} L2^2 {L[k].sum()/L.sum():.3f} H1^2 {H[k].sum()/H.sum():.3f} DWR {C[k].sum()/C.sum():+.3f} |DWR| {np.abs(C[k]).sum()/np.abs(C).sum():.3f} max edge {hl[k].max() if k.any() else 0:.2e} area {area[k].sum():.3e}")

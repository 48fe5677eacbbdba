"""A model of the booleans' crossing search (issue #36, docs/boolean-plan.md): the
benchmark's UV spheres and the crossing-search grid copied in double arithmetic,
counting the triangles each filter rules out. Usage: python3 bench/boolean_grid_model.py 20000 100000"""
import math, sys
from collections import defaultdict
def uv_sphere(rings, seg, r=1.0, c=(0,0,0)):
    P=[(c[0],c[1],c[2]+r)]
    for i in range(1,rings):
        th=math.pi*i/rings
        for j in range(seg):
            ph=2*math.pi*j/seg
            P.append((c[0]+r*math.sin(th)*math.cos(ph), c[1]+r*math.sin(th)*math.sin(ph), c[2]+r*math.cos(th)))
    P.append((c[0],c[1],c[2]-r)); south=len(P)-1
    at=lambda i,j: 1+(i-1)*seg+j%seg
    T=[]
    for j in range(seg): T.append((0,at(1,j),at(1,j+1)))
    for i in range(1,rings-1):
        for j in range(seg):
            T.append((at(i,j),at(i+1,j),at(i+1,j+1))); T.append((at(i,j),at(i+1,j+1),at(i,j+1)))
    for j in range(seg): T.append((south,at(rings-1,j+1),at(rings-1,j)))
    return P,T
def sphere_n(n, off=(0,0,0)):
    seg=int(math.sqrt(n)); rings=n//(2*seg)+1
    return uv_sphere(rings,seg,1.0,off)
def boxes(P,T):
    return [tuple(min(P[v][k] for v in t) for k in range(3))+tuple(max(P[v][k] for v in t) for k in range(3)) for t in T]
def bounds(B):
    return tuple(min(b[k] for b in B) for k in range(3))+tuple(max(b[3+k] for b in B) for k in range(3))
def meet(p,q): return p[0]<=q[3] and q[0]<=p[3] and p[1]<=q[4] and q[1]<=p[4] and p[2]<=q[5] and q[2]<=p[5]
class Grid:
    def __init__(s,b,target):
        s.b=b; ext=[b[3+k]-b[k] for k in range(3)]; h=max(ext)/target**(1/3)
        while True:
            s.d=[int(min(max(math.ceil(ext[k]/h),1),1024)) for k in range(3)]
            if s.d[0]*s.d[1]*s.d[2]<=8*target: break
            h*=1.5
    def idx(s,k,x):
        e=s.b[3+k]-s.b[k]; f=math.floor((x-s.b[k])/e*s.d[k]); return int(min(max(f,0),s.d[k]-1))
    def cells(s,bx):
        lo=[s.idx(k,bx[k]) for k in range(3)]; hi=[s.idx(k,bx[3+k]) for k in range(3)]
        for i in range(lo[0],hi[0]+1):
            for j in range(lo[1],hi[1]+1):
                for k in range(lo[2],hi[2]+1): yield (i*s.d[1]+j)*s.d[2]+k
def run(n, off):
    PA,TA=sphere_n(n); PB,TB=sphere_n(n); PB=[(p[0]+off[0],p[1]+off[1],p[2]+off[2]) for p in PB]
    BA,BB=boxes(PA,TA),boxes(PB,TB); ba,bb=bounds(BA),bounds(BB)
    common=tuple(max(ba[k],bb[k]) for k in range(3))+tuple(min(ba[3+k],bb[3+k]) for k in range(3))
    inA=[meet(b,common) for b in BA]; inB=[meet(b,common) for b in BB]
    g=Grid(common,(len(TA)+len(TB))//2)
    pres=defaultdict(int); cellsvisited=0
    for B,inn,bit in ((BA,inA,1),(BB,inB,2)):
        for t,b in enumerate(B):
            if not inn[t]: continue
            for c in g.cells(b): pres[c]|=bit; cellsvisited+=1
    def near(B,inn,other):
        return [t for t,b in enumerate(B) if inn[t] and any(pres[c]&other for c in g.cells(b))]
    an=near(BA,inA,2); bn=near(BB,inB,1)
    binned=defaultdict(list)
    for t in bn:
        for c in g.cells(BB[t]): binned[c].append(t)
    cand=0; lookups=0
    for ta in an:
        bx=BA[ta]
        for c in g.cells(bx):
            for tb in binned.get(c,()):
                lookups+=1
                o=BB[tb]
                if not meet(bx,o): continue
                lc=(g.idx(0,max(bx[0],o[0]))*g.d[1]+g.idx(1,max(bx[1],o[1])))*g.d[2]+g.idx(2,max(bx[2],o[2]))
                if lc!=c: continue
                cand+=1
    # crossing estimate in double: triangles of A straddling B's sphere and vice versa
    cen=off
    def straddle(P,T,c):
        k=0
        for t in T:
            s=[math.dist(P[v],c)<1 for v in t]
            if any(s) and not all(s): k+=1
        return k
    sa=straddle(PA,TA,cen); sb=straddle(PB,TB,(0,0,0))
    print(f"n={n} off={off}: tris A {len(TA)} verts {len(PA)}; grid dims {g.d} cells {g.d[0]*g.d[1]*g.d[2]}")
    print(f"  A tris meeting common box {sum(inA)} ({100*sum(inA)/len(TA):.1f}%), B {sum(inB)} ({100*sum(inB)/len(TB):.1f}%)")
    print(f"  near A {len(an)} ({100*len(an)/len(TA):.2f}%), near B {len(bn)} ({100*len(bn)/len(TB):.2f}%)")
    print(f"  cell visits in mark {cellsvisited}, bin lookups {lookups}, candidate pairs {cand}")
    print(f"  A tris straddling B's sphere {sa}, B tris straddling A's {sb} (cuts ~ crossing pairs ~ {sa+sb})")
for n in [int(a) for a in sys.argv[1:]]:
    run(n,(0.5,0.0625,0.03125))
    run(n,(0.28867513459481287,)*3)

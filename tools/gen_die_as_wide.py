#!/usr/bin/env python3
"""Generates the die-as-wide-as-the-block setups of BENCHMARKS.md ("Slave nodes sliding off a
master's end"): a neo-Hookean rubber block 1 x 1 (8 x 8 Quad1PlaneStrain, c1 = 0.5, k = 10)
compressed 30 % in ten steps of large deformation by a stiff die exactly as wide (c1 = 500), the
block's top nodes (node-to-segment) or top edges (mortar) the slave side; its corners bulge past
the die's edges.  Usage: python3 tools/gen_die_as_wide.py DIR"""
import os, sys
def gen(name, law, nb=8, nd=8, steps=10, comp=0.3, mortar=False, die_w=1.0):
    nodes=[]; els=[]
    def grid(nx, ny, x0, y0, w, h):
        ids=[]
        for j in range(ny+1):
            row=[]
            for i in range(nx+1):
                nodes.append((x0+w*i/nx, y0+h*j/ny)); row.append(len(nodes))
            ids.append(row)
        return ids
    b=grid(nb, nb, 0, 0, 1, 1)
    d=grid(nd, 2, 0.5-die_w/2, 1.0, die_w, 0.2)
    for g, mat in ((b,1),(d,2)):
        ny=len(g)-1; nx=len(g[0])-1
        for j in range(ny):
            for i in range(nx):
                els.append((g[j+1][i+1], g[j+1][i], g[j][i], g[j][i+1], mat))
    nb_el=nb*nb
    s=[f"{name}.out", "rubber block compressed 30% by a die as wide as it", f"NonLinearStatic nsteps {steps} controlmode 1 rtolf 1e-8 maxiter 25",
       "domain PlaneStrain", "OutputManager",
       f"ndofman {len(nodes)} nelem {len(els)} ncrosssect 2 nmat 2 nbc 4 nic 0 nltf 1 nset 7 ncontactseg 2"]
    for k,(x,y) in enumerate(nodes): s.append(f"node {k+1} coords 2 {x:.12g} {y:.12g}")
    for k,e in enumerate(els): s.append(f"Quad1PlaneStrain {k+1} nodes 4 {e[0]} {e[1]} {e[2]} {e[3]} nlgeo 1 crossSect {e[4]} mat {e[4]}")
    s.append("linear2delementedgecontactsegment 1 edgeset 5")
    s.append("linear2delementedgecontactsegment 2 edgeset 6")
    s.append("SimpleCS 1 thick 1 material 1")
    s.append("SimpleCS 2 thick 1 material 2")
    s.append("MooneyRivlinCompressibleMat 1 d 0 c1 0.5 c2 0 k 10")
    s.append("MooneyRivlinCompressibleMat 2 d 0 c1 500 c2 0 k 10000")
    s.append("BoundaryCondition 1 loadTimeFunction 1 dofs 1 2 values 1 0 set 1")
    s.append("BoundaryCondition 2 loadTimeFunction 1 dofs 1 1 values 1 0 set 2")
    s.append(f"BoundaryCondition 3 loadTimeFunction 1 dofs 2 1 2 values 2 0 {-comp} set 3")
    if mortar:
        s.append(f"s2s{law}contact 4 loadTimeFunction 1 slavesegment 2 segmentset 1 1")
    else:
        s.append(f"n2s{law}contact 4 loadTimeFunction 1 slaveset 4 segmentset 1 1")
    s.append(f"PiecewiseLinFunction 1 npoints 2 t 2 0 {steps} f(t) 2 0 1")
    bottom=b[0]; top=b[-1]; dtop=d[-1]; dbot=d[0]
    s.append(f"Set 1 nodes {len(bottom)} "+" ".join(map(str,bottom)))
    s.append(f"Set 2 nodes 1 {b[0][0]}")
    s.append(f"Set 3 nodes {len(dtop)} "+" ".join(map(str,dtop)))
    s.append(f"Set 4 nodes {len(top)} "+" ".join(map(str,top)))
    # die bottom edges: die elements row 0 -> boundary 3 (nodes [2,3] = (x0,y0),(x1,y0))
    die_first=nb_el+1
    s.append(f"Set 5 elementboundaries {2*nd} "+" ".join(f"{die_first+i} 3" for i in range(nd)))
    # block top edges: row nb-1 -> boundary 1 (nodes [0,1] = (x1,y1),(x0,y1))
    s.append(f"Set 6 elementboundaries {2*nb} "+" ".join(f"{(nb-1)*nb+i+1} 1" for i in range(nb)))
    s.append("Set 7 allelements")
    open(name+".in","w").write("\n".join(s)+"\n")

if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    os.makedirs(out, exist_ok=True)
    os.chdir(out)
    gen("n2s_lm", "lagrangianmultiplier")
    gen("n2s_pen", "penalty")
    gen("mortar_lm", "lagrangianmultiplier", mortar=True)
    gen("mortar_pen", "penalty", mortar=True)

#!/usr/bin/env python3
"""Two blocks [0,2]x[-1,0] and [0,2]x[0,1] (n_low and n_up elements across, `rows` rows each)
pressed by a uniform pressure 10: the contact patch test at scale, for BENCHMARKS.md.
Writes s2s_N.in (mortar, multipliers) and n2s_N.in (node-to-segment, multipliers) in DIR.
Usage: gen_patch_blocks.py N_LOW N_UP ROWS DIR"""
import sys
def blocks(n_low, n_up, condition, rows=2):
    nodes=[]; elems=[]; nid=[0]
    def grid(nx, y0):
        g=[]
        for j in range(rows+1):
            r=[]
            for i in range(nx+1):
                nid[0]+=1
                nodes.append(f"node {nid[0]} coords 2 {2.0*i/nx!r} {y0+j/rows!r}")
                r.append(nid[0])
            g.append(r)
        return g
    low=grid(n_low,-1.0); up=grid(n_up,0.0)
    def quads(g):
        row=[]
        for j in range(rows):
            for i in range(len(g[0])-1):
                e=len(elems)+1
                elems.append(f"PlaneStress2d {e} nodes 4 {g[j][i]} {g[j][i+1]} {g[j+1][i+1]} {g[j+1][i]} crossSect 1 mat 1")
                row.append(e)
        return row
    el_low=quads(low); el_up=quads(up)
    top_low=[f"{e} 3" for e in el_low[(rows-1)*n_low:]]
    bottom_up=[f"{e} 1" for e in el_up[:n_up]]
    top_up=[f"{e} 3" for e in el_up[(rows-1)*n_up:]]
    left=[r[0] for r in low+up]
    j=lambda v:" ".join(map(str,v))
    return "\n".join(["mb.out","mb","StaticStructural nsteps 1 rtolf 1e-10 maxiter 20","domain 2dPlaneStress","OutputManager",
      f"ndofman {len(nodes)} nelem {len(elems)} ncrosssect 1 nmat 1 nbc 4 nic 0 nltf 1 nset 7 ncontactseg 2"]+nodes+elems+[
      "linear2delementedgecontactsegment 1 edgeset 1","linear2delementedgecontactsegment 2 edgeset 2",
      "SimpleCS 1 thick 1.0 material 1 set 3","IsoLE 1 d 0 E 1000 n 0.3 tAlpha 0",
      "BoundaryCondition 1 loadTimeFunction 1 dofs 1 1 values 1 0 set 5","BoundaryCondition 2 loadTimeFunction 1 dofs 1 2 values 1 0 set 6",
      "ConstantEdgeLoad 3 loadTimeFunction 1 dofs 2 1 2 components 2 0 -10 set 7", condition, "ConstantFunction 1 f(t) 1",
      f"Set 1 elementboundaries {2*n_up} {j(bottom_up)}", f"Set 2 elementboundaries {2*n_low} {j(top_low)}","Set 3 allelements",
      f"Set 4 nodes {len(up[0])} {j(up[0])}", f"Set 5 nodes {len(left)} {j(left)}", f"Set 6 nodes {len(low[0])} {j(low[0])}",
      f"Set 7 elementedges {2*n_up} {j(top_up)}"])+"\n"
n_low,n_up,out=int(sys.argv[1]),int(sys.argv[2]),sys.argv[4]
for name,cond in [("s2s","s2slagrangianmultipliercontact 4 loadTimeFunction 1 slavesegment 1 segmentset 1 2"),
                  ("n2s","n2slagrangianmultipliercontact 4 loadTimeFunction 1 slaveset 4 segmentset 1 2")]:
    open(f"{out}/{name}_{n_low}.in","w").write(blocks(n_low,n_up,cond,rows=int(sys.argv[3])))

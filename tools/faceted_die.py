#!/usr/bin/env python3
"""A faceted die pressed onto a block with friction (plane strain, node-to-segment): the block
4 x 1 (E = 1000, nu = 0.3, its bottom held), the die 3 wide and ten times stiffer, its bottom a
flat facet 2*flat wide touching the block (or --gap above it) and two facets rising --slope
from its ends; the die's top moved down by --press (and sideways by --shift) over --steps
steps. BENCHMARKS.md "A faceted die pressed in one step" sweeps it:

    python3 tools/faceted_die.py --nx 48 --ny 8 --nd 24 --mu 0.5 --out die.in && hertz run die.in
"""
import argparse
p = argparse.ArgumentParser()
p.add_argument("--nx", type=int, default=16)
p.add_argument("--ny", type=int, default=4)
p.add_argument("--nd", type=int, default=12)
p.add_argument("--mu", type=float, default=0.3)
p.add_argument("--press", type=float, default=0.08)
p.add_argument("--steps", type=int, default=4)
p.add_argument("--slope", type=float, default=0.1)
p.add_argument("--flat", type=float, default=0.5)
p.add_argument("--gap", type=float, default=0.0)
p.add_argument("--shift", type=float, default=0.0, help="die's sideways travel over the press")
p.add_argument("--law", default="mult", choices=["mult", "pen"])
p.add_argument("--nlgeo", type=int, default=0)
p.add_argument("--out", default="die.in")
a = p.parse_args()
nodes, elems = [], []
def node(x, y):
    nodes.append((x, y)); return len(nodes)
W, H = 2.0, 1.0
blk = [[node(-W + 2*W*i/a.nx, H*j/a.ny) for i in range(a.nx+1)] for j in range(a.ny+1)]
for j in range(a.ny):
    for i in range(a.nx):
        elems.append((blk[j][i], blk[j][i+1], blk[j+1][i+1], blk[j+1][i], 1))
# die x stations: flat facet [-flat, flat] and sides to +-1.5, nodes at breaks
L = 1.5
xs = sorted(set([round(-L + 2*L*k/a.nd, 12) for k in range(a.nd+1)] + [-a.flat, a.flat]))
yb = lambda x: H + a.gap + a.slope*max(0.0, abs(x) - a.flat)
bot = [node(x, yb(x)) for x in xs]
top = [node(x, H + a.gap + a.slope*(L - a.flat) + 0.3) for x in xs]
for k in range(len(xs)-1):
    elems.append((bot[k], bot[k+1], top[k+1], top[k], 2))
ne_blk = a.nx*a.ny
out = []
w = out.append
w("die.out\nFaceted die on a block\n")
w(f"StaticStructural nsteps {a.steps} deltat {1.0/a.steps} rtolf 1e-9 maxiter 30\n")
w("domain PlaneStrain\nOutputManager\n")
w(f"ndofman {len(nodes)} nelem {len(elems)} ncrosssect 1 nmat 2 nbc 4 nic 0 nltf 2 nset 3 ncontactseg 1\n")
for i, (x, y) in enumerate(nodes, 1):
    w(f"node {i} coords 2 {x:.12f} {y:.12f}\n")
for e, (n1, n2, n3, n4, m) in enumerate(elems, 1):
    w(f"Quad1PlaneStrain {e} nodes 4 {n1} {n2} {n3} {n4} mat {m} crossSect 1 nlgeo {a.nlgeo}\n")
# die bottom edges: boundary 1 of die elements (n1-n2)
w("linear2delementedgecontactsegment 1 edgeset 1\n")
w("SimpleCS 1 thick 1.0\n")
w("IsoLE 1 d 0 E 1000 n 0.3 tAlpha 0\n")
w("IsoLE 2 d 0 E 10000 n 0.3 tAlpha 0\n")
w("BoundaryCondition 1 loadTimeFunction 1 dofs 2 1 2 values 2 0 0 set 2\n")
w(f"BoundaryCondition 2 loadTimeFunction 2 dofs 1 2 values 1 {-a.press} set 3\n")
w(f"BoundaryCondition 3 loadTimeFunction 2 dofs 1 1 values 1 {a.shift} set 3\n")
slaves = blk[a.ny]
rec = {"mult": "n2slagrangianmultipliercontact 4", "pen": "n2spenaltycontact 4 penalty 1e6 pt 1e6"}[a.law]
w(f"{rec} loadTimeFunction 1 friction {a.mu} nodeset {len(slaves)} {' '.join(map(str, slaves))} segmentset 1 1\n")
w("ConstantFunction 1 f(t) 1.0\nPiecewiseLinFunction 2 npoints 2 t 2 0 1 f(t) 2 0 1\n")
die_ids = range(ne_blk+1, len(elems)+1)
w(f"Set 1 elementboundaries {2*len(die_ids)} " + " ".join(f"{e} 1" for e in die_ids) + "\n")
w(f"Set 2 nodes {len(blk[0])} " + " ".join(map(str, blk[0])) + "\n")
w(f"Set 3 nodes {len(top)} " + " ".join(map(str, top)) + "\n")
open(a.out, "w").write("".join(out))

#!/usr/bin/env python3
"""Generates examples/cantilever.in: a plane-stress cantilever of QPlaneStress2d elements with a
uniform shear traction on the tip (ConstantEdgeLoad) and its Timoshenko tip deflection as a check."""
import sys

L, H, nx, ny = 10.0, 1.0, 40, 4
E, nu, P, t = 1000.0, 0.3, 1.0, 1.0
nodes, order = {}, []
for j in range(2 * ny + 1):
    for i in range(2 * nx + 1):
        if i % 2 == 1 and j % 2 == 1:
            continue
        nodes[(i, j)] = len(order) + 1
        order.append((i, j))
elems = []
for ey in range(ny):
    for ex in range(nx):
        i0, j0 = 2 * ex, 2 * ey
        c = [(i0 + 2, j0 + 2), (i0, j0 + 2), (i0, j0), (i0 + 2, j0)]
        m = [(i0 + 1, j0 + 2), (i0, j0 + 1), (i0 + 1, j0), (i0 + 2, j0 + 1)]
        elems.append([nodes[p] for p in c + m])
root = [nodes[(0, j)] for j in range(2 * ny + 1)]
tip_elems = [ey * nx + nx for ey in range(ny)]  # last element of every row; edge 4 is x = L
I = t * H ** 3 / 12
G = E / (2 * (1 + nu))
d_eb = P * L ** 3 / (3 * E * I)
d_s = P * L / ((5.0 / 6.0) * G * H * t)
v_tip = -(d_eb + d_s)
tip_mid = nodes[(2 * nx, ny)]
out = [
    "cantilever.out",
    "Cantilever of QPlaneStress2d elements under a tip shear load (Timoshenko check)",
    "#",
    f"# Problem: a cantilever L = {L:g} long, H = {H:g} deep, thickness {t:g}, plane stress, E = {E:g},",
    f"# nu = {nu:g}, clamped at x = 0 (u = v = 0), loaded at x = L by a uniform shear traction whose",
    f"# resultant is P = {P:g} downwards (ConstantEdgeLoad on the tip edges).",
    f"# Mesh: {nx} x {ny} eight-node quadrilaterals, {len(order)} nodes (tools/gen_cantilever.py).",
    "#",
    "# Analytical solution (Timoshenko beam), tip deflection:",
    "#   v = -(P L^3/(3 E I) + P L/(kappa G A)),  I = t H^3/12, G = E/(2(1+nu)), A = H t, kappa = 5/6",
    f"#     = -({d_eb:.6f} + {d_s:.6f}) = {v_tip:.6f}",
    "# The check below accepts 1 % (the clamped root and the traction distribution differ from beam",
    "# theory near the ends). Reaction: the root carries the vertical force P.",
    "#",
    "# Run:  hertz run examples/cantilever.in   (writes cantilever.out, cantilever.1.vtu, cantilever.pvd)",
    "#",
    "StaticStructural nsteps 1 nmodules 1",
    "errorcheck",
    "domain 2dPlaneStress",
    "OutputManager tstep_all dofman_all element_all",
    f"ndofman {len(order)} nelem {len(elems)} ncrosssect 1 nmat 1 nbc 2 nic 0 nltf 1 nset 3",
]
for (i, j) in order:
    out.append(f"node {nodes[(i, j)]} coords 2 {i * L / (2 * nx):.6g} {j * H / (2 * ny):.6g}")
for k, e in enumerate(elems):
    out.append(f"QPlaneStress2d {k + 1} nodes 8 " + " ".join(map(str, e)) + " NIP 9")
out += [
    f"SimpleCS 1 thick {t:g} material 1 set 1",
    f"IsoLE 1 d 0. E {E:g} n {nu:g} tAlpha 0.",
    "BoundaryCondition 1 loadTimeFunction 1 dofs 2 1 2 values 2 0. 0. set 2",
    f"ConstantEdgeLoad 2 loadTimeFunction 1 dofs 2 1 2 components 2 0. {-P / (H * t):g} set 3",
    "ConstantFunction 1 f(t) 1.0",
    f"Set 1 elementranges {{(1 {len(elems)})}}",
    f"Set 2 nodes {len(root)} " + " ".join(map(str, root)),
    f"Set 3 elementedges {2 * len(tip_elems)} " + " ".join(f"{e} 4" for e in tip_elems),
    f"#%BEGIN_CHECK% tolerance {abs(v_tip) * 0.01:.4f}",
    f"#NODE tStep 1 number {tip_mid} dof 2 unknown d value {v_tip:.6f}",
    f"#NODE tStep 1 number {nodes[(2 * nx, 0)]} dof 2 unknown d value {v_tip:.6f}",
    "#%END_CHECK%",
]
open(sys.argv[1] if len(sys.argv) > 1 else "examples/cantilever.in", "w").write("\n".join(out) + "\n")

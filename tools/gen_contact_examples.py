#!/usr/bin/env python3
"""Generates the contact verification examples of examples/:
  hertz_rigid_circle.in  rigid cylinder pressed into an elastic block (plane strain, N2S penalty)
  hertz_cylinder.in      elastic cylinder cap on an elastic block (plane strain, N2S penalty)
  flat_punch.in          rigid flat punch under a prescribed force (plane strain, N2S penalty)
  cattaneo_mindlin.in    elastic cylinder on an elastic block pressed, then sheared (friction)
  hertz_mortar.in        hertz_rigid_circle.in with mortar contact (multipliers)
  hertz_cylinder_mortar.in  hertz_cylinder.in with mortar contact between the two bodies
  indentation.in         hertz_rigid_circle.in's cylinder pressed into a plastic block and lifted
  hertz_sphere_axisymmetric.in  hertz_rigid_circle.in's mesh as an axisymmetric section: a rigid sphere
All but hertz_cylinder_mortar.in and hertz_sphere_axisymmetric.in (whose x = 0 is the axis) are half models (x >= 0) with symmetry conditions on x = 0. Meshes are structured and graded:
a fine zone of spacing h near the contact, then geometric growth."""


def graded(length, h, fine, growth=1.15):
    """Coordinates 0..length: spacing h up to `fine`, then growing by `growth`."""
    xs = [0.0]
    while xs[-1] < fine - 1e-12:
        xs.append(min(xs[-1] + h, fine))
    step = h
    while xs[-1] < length - 1e-12:
        step *= growth
        nxt = xs[-1] + step
        if length - nxt < step:
            nxt = length
        xs.append(min(nxt, length))
    return xs


class Mesh:
    def __init__(self):
        self.nodes = []  # (x, y)
        self.elems = []  # (kind, nodes, extra)

    def node(self, x, y):
        self.nodes.append((x, y))
        return len(self.nodes)

    def block(self, xs, ys_of_x, kind="Quad1PlaneStrain"):
        """Structured quads over columns xs; ys_of_x(i) gives the column's y list (bottom to top).
        Returns the node id grid ids[i][j] and the element ids grid."""
        ids = [[self.node(x, y) for y in ys_of_x(i)] for i, x in enumerate(xs)]
        eids = []
        for i in range(len(xs) - 1):
            col = []
            for j in range(len(ids[i]) - 1):
                # OOFEM quad order: (x1,y1), (x0,y1), (x0,y0), (x1,y0); edge 1 = top (nodes 1-2).
                n = [ids[i + 1][j + 1], ids[i][j + 1], ids[i][j], ids[i + 1][j]]
                self.elems.append((kind, n, ""))
                col.append(len(self.elems))
            eids.append(col)
        return ids, eids


def header(out, desc, comment):
    return [out, desc] + ["# " + l if l else "#" for l in comment.strip("\n").split("\n")]


def write(path, lines):
    open(path, "w").write("\n".join(lines) + "\n")


def common_records(m, ncs_lines, mat_lines, bcs, funcs, sets, nsegs, seg_lines, analysis):
    lines = [analysis, "domain PlaneStrain", "OutputManager tstep_all"]
    lines.append(
        f"ndofman {len(m.nodes)} nelem {len(m.elems)} ncrosssect {len(ncs_lines)} nmat {len(mat_lines)} "
        f"nbc {len(bcs)} nic 0 nltf {len(funcs)} nset {len(sets)} ncontactseg {nsegs}"
    )
    for k, (x, y) in enumerate(m.nodes):
        lines.append(f"node {k + 1} coords 2 {x:.10g} {y:.10g}")
    for k, (kind, n, extra) in enumerate(m.elems):
        lines.append(f"{kind} {k + 1} nodes {len(n)} " + " ".join(map(str, n)) + (" " + extra if extra else ""))
    return lines + seg_lines + ncs_lines + mat_lines + bcs + funcs + sets


def nodeset(name_id, ids):
    return f"Set {name_id} nodes {len(ids)} " + " ".join(map(str, ids))


# ---------------------------------------------------------------------------------------------
E, NU = 1000.0, 0.3
ESTAR_RIGID = E / (1 - NU * NU)


# The rigid cylinder's problem (hertz_rigid, hertz_mortar): radius, mesh size, fine zone, block
# width and depth, indentation.
RIGID = (10.0, 0.04, 2.0, 12.0, 12.0, 0.045)


def rigid_block():
    """The block of the rigid-cylinder problem and the cylinder's node: (mesh, xs, ys, node ids,
    element ids, reference node)."""
    R, h, fine, W, H, _ = RIGID
    m = Mesh()
    xs = graded(W, h, fine)
    depth = graded(H, h, 1.0)
    ys = [-d for d in reversed(depth)]
    ids, eids = m.block(xs, lambda i: ys)
    ref = m.node(0.0, R)
    return m, xs, ys, ids, eids, ref


def rigid_records(m, ids, ref, xs, delta, ltf):
    """The rigid-cylinder problem's sets and conditions: symmetry on x = 0, the bottom held, the
    cylinder's node moved down by `delta` times load-time function `ltf`, and node-to-segment
    penalty contact of the top nodes with x <= 3."""
    top = [col[-1] for col in ids]
    contact_nodes = [top[i] for i, x in enumerate(xs) if x <= 3.0]
    sym = [ids[0][j] for j in range(len(ids[0]))]
    bottom = [col[0] for col in ids]
    sets = [
        f"Set 1 elementranges {{(1 {len(m.elems)})}}",
        nodeset(2, sym),
        nodeset(3, bottom),
        nodeset(4, [ref]),
    ]
    bcs = [
        "BoundaryCondition 1 loadTimeFunction 1 dofs 1 1 values 1 0.0 set 2",
        "BoundaryCondition 2 loadTimeFunction 1 dofs 1 2 values 1 0.0 set 3",
        f"BoundaryCondition 3 loadTimeFunction {ltf} dofs 2 1 2 values 2 0.0 {-delta:g} set 4",
        f"n2spenaltycontact 4 loadTimeFunction 1 penalty {1e4 * E:g} nodeset {len(contact_nodes)} "
        + " ".join(map(str, contact_nodes)) + " segmentset 1 1",
    ]
    return sets, bcs


def hertz_rigid():
    R, h, fine, W, H, delta = RIGID
    m, xs, ys, ids, eids, ref = rigid_block()
    comment = f"""
Hertz contact of a rigid cylinder on an elastic block, plane strain, half model (x >= 0).
Rigid circle of radius R = {R:g} (circlecontactsegment moving with node {ref}) is pushed down by
delta = {delta:g} into a block {W:g} wide and {H:g} deep, E = {E:g}, nu = {NU:g}, node-to-segment penalty
contact on the top nodes with x <= 3. The block is fine (h = {h:g}) near the contact.
Analytical solution (Hertz, rigid indenter, force F per unit thickness of the full cylinder):
  E* = E/(1 - nu^2),  a = sqrt(4 F R/(pi E*)),  p0 = sqrt(F E*/(pi R)),  p(x) = p0 sqrt(1 - x^2/a^2)
F is the computed indentation force: twice the reaction of node {ref} (half model).
Run:  cargo run --release --example hertz -- examples/hertz_rigid_circle.in
      (prints p0 and a against Hertz; `hertz run` solves and writes the results)
"""
    lines = header("hertz_rigid_circle.out", "Hertz: rigid cylinder on an elastic block (plane strain)", comment)
    sets, bcs = rigid_records(m, ids, ref, xs, delta, 1)
    lines += common_records(
        m, ["SimpleCS 1 thick 1.0 material 1 set 1"], [f"IsoLE 1 d 0. E {E:g} n {NU:g} tAlpha 0."], bcs,
        ["ConstantFunction 1 f(t) 1.0"], sets, 1,
        [f"circlecontactsegment 1 centerpoint 2 0 {R:g} radius {R:g} node {ref}"],
        "NonLinearStatic nsteps 1 controlmode 1 rtolf 1e-8 manrmsteps 1 maxiter 40",
    )
    write("examples/hertz_rigid_circle.in", lines)


# The elastic cylinder's problem (hertz_cylinder, cattaneo_mindlin): radius, mesh size, fine
# zone, block width and depth, indentation, cap width and height.
CYLINDER = (20.0, 0.02, 1.0, 8.0, 8.0, 0.022, 6.0, 6.0)


def cylinder_on_block(whole):
    """The block and the cylinder's cap of the elastic-cylinder problem, half (x >= 0) or whole:
    (mesh, xs, ys, block node and element ids, xc, hc, cap node and element ids, the number of
    block elements)."""
    R, h, fine, W, H, _, Wc, Hc = CYLINDER

    def columns(length):
        xs = graded(length, h, fine)
        return [-x for x in reversed(xs[1:])] + xs if whole else xs

    m = Mesh()
    xs = columns(W)
    depth = graded(H, h, 0.6)
    ys = [-d for d in reversed(depth)]
    bids, beids = m.block(xs, lambda i: ys)
    xc = columns(Wc)
    hc = graded(Hc, h, 0.6)

    def cap_col(i):
        yb = R - (R * R - xc[i] ** 2) ** 0.5
        return [yb + t * (Hc - yb) / Hc for t in hc]

    nb = len(m.elems)
    cids, ceids = m.block(xc, cap_col)
    return m, xs, ys, bids, beids, xc, hc, cids, ceids, nb


def hertz_cylinder():
    R, h, fine, W, H, delta, Wc, Hc = CYLINDER
    m, xs, ys, bids, beids, xc, hc, cids, ceids, nb = cylinder_on_block(False)
    btop_elems = [col[-1] for col in beids]
    cap_bottom = [col[0] for col in cids]
    contact_nodes = [cap_bottom[i] for i, x in enumerate(xc) if x <= 1.5]
    sym = [bids[0][j] for j in range(len(ys))] + [cids[0][j] for j in range(len(hc))]
    bottom = [col[0] for col in bids]
    cap_top = [col[-1] for col in cids]
    comment = f"""
Hertz contact of an elastic cylinder on an elastic block, plane strain, half model (x >= 0).
The cylinder (radius R = {R:g}) is modelled by the cap of it within x <= {Wc:g}, whose flat top is
pushed down by delta = {delta:g}; the block is {W:g} wide and {H:g} deep. Both E = {E:g}, nu = {NU:g}.
Node-to-segment penalty contact: cylinder nodes with x <= 1.5 against the block's top edges.
Analytical solution (Hertz, force F per unit thickness of the full cylinder):
  1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2,  a = sqrt(4 F R/(pi E*)),  p0 = sqrt(F E*/(pi R))
F is twice the sum of the reactions on the cap's top (half model).
Run:  cargo run --release --example hertz -- examples/hertz_cylinder.in
"""
    lines = header("hertz_cylinder.out", "Hertz: elastic cylinder on an elastic block (plane strain)", comment)
    sets = [
        f"Set 1 elementranges {{(1 {nb})}}",
        f"Set 2 elementranges {{({nb + 1} {len(m.elems)})}}",
        nodeset(3, sym),
        nodeset(4, bottom),
        nodeset(5, cap_top),
        f"Set 6 elementboundaries {2 * len(btop_elems)} " + " ".join(f"{e} 1" for e in btop_elems),
    ]
    bcs = [
        "BoundaryCondition 1 loadTimeFunction 1 dofs 1 1 values 1 0.0 set 3",
        "BoundaryCondition 2 loadTimeFunction 1 dofs 1 2 values 1 0.0 set 4",
        f"BoundaryCondition 3 loadTimeFunction 1 dofs 1 2 values 1 {-delta:g} set 5",
        f"n2spenaltycontact 4 loadTimeFunction 1 penalty {1e4 * E:g} nodeset {len(contact_nodes)} "
        + " ".join(map(str, contact_nodes)) + " segmentset 1 1",
    ]
    lines += common_records(
        m,
        ["SimpleCS 1 thick 1.0 material 1 set 1", "SimpleCS 2 thick 1.0 material 2 set 2"],
        [f"IsoLE 1 d 0. E {E:g} n {NU:g} tAlpha 0.", f"IsoLE 2 d 0. E {E:g} n {NU:g} tAlpha 0."],
        bcs, ["ConstantFunction 1 f(t) 1.0"], sets, 1, ["linear2delementedgecontactsegment 1 edgeset 6"],
        "NonLinearStatic nsteps 1 controlmode 1 rtolf 1e-8 manrmsteps 1 maxiter 40",
    )
    write("examples/hertz_cylinder.in", lines)
    # The same bodies with mortar contact: the cap's bottom edges with x <= 1.5 (edge 3 of its
    # lowest elements) are the slave segment, the block's top edges the master; multipliers.
    cap_bottom_elems = [col[0] for i, col in enumerate(ceids) if xc[i + 1] <= 1.5 + 1e-9]
    comment_m = comment.replace(
        "Node-to-segment penalty contact: cylinder nodes with x <= 1.5 against the block's top edges.",
        "Mortar contact with multipliers: the cylinder's edges with x <= 1.5 (slave) against the\n"
        "block's top edges (master), both meshed with h = 0.02 along x near the contact.",
    ).replace("hertz_cylinder.in", "hertz_cylinder_mortar.in").replace(
        "F is twice the sum of the reactions on the cap's top (half model).",
        "F is twice the sum of the nodal contact forces (half model).\n"
        "hertz: p0 and a within 1 % of Hertz (tests/suite/mortar.rs).")
    lines = header("hertz_cylinder_mortar.out",
                   "Hertz: elastic cylinder on an elastic block, mortar contact (plane strain)", comment_m)
    sets.append(f"Set 7 elementboundaries {2 * len(cap_bottom_elems)} " + " ".join(f"{e} 3" for e in cap_bottom_elems))
    bcs[3] = "s2slagrangianmultipliercontact 4 loadTimeFunction 1 slavesegment 2 segmentset 1 1"
    lines += common_records(
        m,
        ["SimpleCS 1 thick 1.0 material 1 set 1", "SimpleCS 2 thick 1.0 material 2 set 2"],
        [f"IsoLE 1 d 0. E {E:g} n {NU:g} tAlpha 0.", f"IsoLE 2 d 0. E {E:g} n {NU:g} tAlpha 0."],
        bcs, ["ConstantFunction 1 f(t) 1.0"], sets, 2,
        ["linear2delementedgecontactsegment 1 edgeset 6", "linear2delementedgecontactsegment 2 edgeset 7"],
        "NonLinearStatic nsteps 1 controlmode 1 rtolf 1e-8 manrmsteps 1 maxiter 40",
    )
    write("examples/hertz_cylinder_mortar.in", lines)


def flat_punch():
    a, h, W, H, F = 1.0, 0.025, 20.0, 20.0, 100.0
    m = Mesh()
    xs = graded(W, h, 1.5 * a)
    depth = graded(H, h, 0.5)
    ys = [-d for d in reversed(depth)]
    ids, eids = m.block(xs, lambda i: ys)
    ref = m.node(0.0, 1.0)
    top = [col[-1] for col in ids]
    contact_nodes = [top[i] for i, x in enumerate(xs) if x <= a + 1e-9]
    sym = [ids[0][j] for j in range(len(ys))]
    bottom = [col[0] for col in ids]
    comment = f"""
Rigid flat punch of half-width a = {a:g} pressed by a force F = {F:g} (per unit thickness, full punch) into
an elastic block {2 * W:g} wide and {H:g} deep (half model x >= 0), E = {E:g}, nu = {NU:g}, plane strain.
The punch is a rigid line (planecontactsegment moving with node {ref}, loaded by F/2); the block's
top nodes with x <= a are the contact nodes (node-to-segment penalty, frictionless).
Analytical solution (rigid flat punch on a half-space):
  p(x) = F / (pi sqrt(a^2 - x^2)),  |x| < a
Checks: the contact forces add up to F; p(x) within 5 % of the formula for |x| <= 0.8 a.
Run:  cargo run --release --example flat_punch
"""
    lines = header("flat_punch.out", "Rigid flat punch on an elastic block (plane strain)", comment)
    sets = [
        f"Set 1 elementranges {{(1 {len(m.elems)})}}",
        nodeset(2, sym),
        nodeset(3, bottom),
        nodeset(4, [ref]),
    ]
    bcs = [
        "BoundaryCondition 1 loadTimeFunction 1 dofs 1 1 values 1 0.0 set 2",
        "BoundaryCondition 2 loadTimeFunction 1 dofs 1 2 values 1 0.0 set 3",
        "BoundaryCondition 3 loadTimeFunction 1 dofs 1 1 values 1 0.0 set 4",
        f"NodalLoad 4 loadTimeFunction 1 dofs 2 1 2 components 2 0.0 {-F / 2:g} set 4",
        f"n2spenaltycontact 5 loadTimeFunction 1 penalty {1e4 * E:g} nodeset {len(contact_nodes)} "
        + " ".join(map(str, contact_nodes)) + " segmentset 1 1",
    ]
    lines += common_records(
        m, ["SimpleCS 1 thick 1.0 material 1 set 1"], [f"IsoLE 1 d 0. E {E:g} n {NU:g} tAlpha 0."], bcs,
        ["ConstantFunction 1 f(t) 1.0"], sets, 1, [f"planecontactsegment 1 point 2 0 0 normal 2 0 -1 node {ref}"],
        "StaticStructural nsteps 1 rtolf 1e-8 manrmsteps 1 maxiter 40",
    )
    write("examples/flat_punch.in", lines)


def cattaneo_mindlin():
    """The cylinder on the block of hertz_cylinder, whole (shear has no symmetry), pressed by a
    prescribed displacement of the cap's top, then moved sideways."""
    R, h, fine, W, H, delta, Wc, Hc = CYLINDER
    MU = 0.3
    m, xs, ys, bids, beids, xc, hc, cids, ceids, nb = cylinder_on_block(True)
    btop_elems = [col[-1] for col in beids]
    cap_bottom = [col[0] for col in cids]
    contact_nodes = [cap_bottom[i] for i, x in enumerate(xc) if abs(x) <= 1.5]
    bottom = [col[0] for col in bids]
    cap_top = [col[-1] for col in cids]
    comment = f"""
Cattaneo-Mindlin: the elastic cylinder (R = {R:g}) on the elastic block of hertz_cylinder.in, whole,
both E = {E:g}, nu = {NU:g} (elastically similar: the normal and tangential problems uncouple).
Step 1 presses the cap's flat top down by delta = {delta:g}; step 2 moves it sideways by {DX_CM:g}
(the top is held horizontally throughout): the normal force P and the shear force Q are the
reactions of the top, Q about half of mu P.
Node-to-segment penalty contact with Coulomb friction mu = {MU:g} (pt = penalty): cylinder nodes with
|x| <= 1.5 against the block's top edges; the block's bottom is held.
Analytical solution (Cattaneo 1938, Mindlin 1949; Johnson, Contact Mechanics, 7.1), Hertz's a and p0
for the force P, P and Q per unit thickness:
  stick zone |x| < c,  c = a sqrt(1 - Q/(mu P))
  q(x) = mu p0 sqrt(1 - x^2/a^2) - mu p0 (c/a) sqrt(1 - x^2/c^2)  (|x| < c),  mu p(x) in the slip zone
Checks (tests/suite/friction.rs): c within one element (h = {h:g}), q(x) against the formula.
hertz: P = 5.7449, Q = 0.8293 (Q/(mu P) = 0.481), a = 0.5160, c = 0.3717; stick zone half-width
0.3689; q(x) within 3.1 % of mu p0 (beyond one element from the cusp at +-c); 2 and 4 iterations.
Run:  cargo run --release -- run examples/cattaneo_mindlin.in
"""
    lines = header("cattaneo_mindlin.out", "Cattaneo-Mindlin: a cylinder pressed then sheared on a block (plane strain)", comment)
    sets = [
        f"Set 1 elementranges {{(1 {nb})}}",
        f"Set 2 elementranges {{({nb + 1} {len(m.elems)})}}",
        nodeset(3, bottom),
        nodeset(4, cap_top),
        f"Set 5 elementboundaries {2 * len(btop_elems)} " + " ".join(f"{e} 1" for e in btop_elems),
    ]
    bcs = [
        "BoundaryCondition 1 loadTimeFunction 1 dofs 2 1 2 values 2 0.0 0.0 set 3",
        f"BoundaryCondition 2 loadTimeFunction 1 dofs 1 2 values 1 {-delta:g} set 4",
        f"BoundaryCondition 3 loadTimeFunction 2 dofs 1 1 values 1 {DX_CM:g} set 4",
        f"n2spenaltycontact 4 loadTimeFunction 1 penalty {1e4 * E:g} friction {MU:g} nodeset {len(contact_nodes)} "
        + " ".join(map(str, contact_nodes)) + " segmentset 1 1",
    ]
    lines += common_records(
        m,
        ["SimpleCS 1 thick 1.0 material 1 set 1", "SimpleCS 2 thick 1.0 material 2 set 2"],
        [f"IsoLE 1 d 0. E {E:g} n {NU:g} tAlpha 0.", f"IsoLE 2 d 0. E {E:g} n {NU:g} tAlpha 0."],
        bcs, ["ConstantFunction 1 f(t) 1.0", "PiecewiseLinFunction 2 npoints 2 t 2 1 2 f(t) 2 0 1"], sets, 1,
        ["linear2delementedgecontactsegment 1 edgeset 5"],
        "StaticStructural nsteps 2 rtolf 1e-8 maxiter 30",
    )
    write("examples/cattaneo_mindlin.in", lines)


def hertz_mortar():
    """hertz_rigid_circle's problem with mortar contact: the block's top edges with x <= 3 are
    the slave segment, the rigid circle the master; multipliers (no penalty to choose)."""
    R, h, fine, W, H, delta = RIGID
    m, xs, ys, ids, eids, ref = rigid_block()
    top_elems = [col[-1] for i, col in enumerate(eids) if xs[i + 1] <= 3.0 + 1e-9]
    sym = [ids[0][j] for j in range(len(ys))]
    bottom = [col[0] for col in ids]
    comment = f"""
Hertz contact of a rigid cylinder on an elastic block with mortar contact: the problem of
hertz_rigid_circle.in (R = {R:g}, delta = {delta:g}, block {W:g} x {H:g}, E = {E:g}, nu = {NU:g}, plane strain,
half model x >= 0, h = {h:g} near the contact). The slave segment is the block's top edges with
x <= 3, the master the rigid circle (moving with node {ref}); Lagrange multipliers, one per slave
node: the nodal contact pressures, weighted over the slave edges (no tributary lengths).
Analytical solution (Hertz, rigid indenter, F per unit thickness of the full cylinder):
  E* = E/(1 - nu^2),  a = sqrt(4 F R/(pi E*)),  p0 = sqrt(F E*/(pi R)),  p(x) = p0 sqrt(1 - x^2/a^2)
F is twice the sum of the nodal contact forces (half model).
hertz: p0 and a within 1 % of Hertz, the pressure smooth (tests/suite/mortar.rs).
Run:  cargo run --release -- run examples/hertz_mortar.in
"""
    lines = header("hertz_mortar.out", "Hertz: rigid cylinder on an elastic block, mortar contact (plane strain)", comment)
    sets = [
        f"Set 1 elementranges {{(1 {len(m.elems)})}}",
        nodeset(2, sym),
        nodeset(3, bottom),
        nodeset(4, [ref]),
        f"Set 5 elementboundaries {2 * len(top_elems)} " + " ".join(f"{e} 1" for e in top_elems),
    ]
    bcs = [
        "BoundaryCondition 1 loadTimeFunction 1 dofs 1 1 values 1 0.0 set 2",
        "BoundaryCondition 2 loadTimeFunction 1 dofs 1 2 values 1 0.0 set 3",
        f"BoundaryCondition 3 loadTimeFunction 1 dofs 2 1 2 values 2 0.0 {-delta:g} set 4",
        "s2slagrangianmultipliercontact 4 loadTimeFunction 1 slavesegment 2 segmentset 1 1",
    ]
    lines += common_records(
        m, ["SimpleCS 1 thick 1.0 material 1 set 1"], [f"IsoLE 1 d 0. E {E:g} n {NU:g} tAlpha 0."], bcs,
        ["ConstantFunction 1 f(t) 1.0"], sets, 2,
        [f"circlecontactsegment 1 centerpoint 2 0 {R:g} radius {R:g} node {ref}",
         "linear2delementedgecontactsegment 2 edgeset 5"],
        "NonLinearStatic nsteps 1 controlmode 1 rtolf 1e-8 manrmsteps 1 maxiter 40",
    )
    write("examples/hertz_mortar.in", lines)


# The indentation: yield stress, hardening modulus, deepest indentation, steps down and up.
INDENT = (5.0, 0.0, 0.15, 10, 10)


def indentation():
    """hertz_rigid_circle's cylinder pressed into an elastic-perfectly plastic block (MisesMat on
    barred quadrilaterals) and lifted off again: a residual imprint."""
    R, h, fine, W, H, _ = RIGID
    sig0, hard, delta, down, up = INDENT
    m, xs, ys, ids, eids, ref = rigid_block()
    m.elems = [("Quad1PlaneStrainBB", n, extra) for (_, n, extra) in m.elems]
    comment = f"""
Elastoplastic indentation and its residual imprint, plane strain, half model (x >= 0): the rigid
cylinder of hertz_rigid_circle.in (R = {R:g}, circlecontactsegment moving with node {ref}) pushed
down by {delta:g} in {down} steps into a block {W:g} x {H:g} of von Mises steel-like material (E = {E:g},
nu = {NU:g}, sig0 = {sig0:g}, H = {hard:g}: perfectly plastic) on barred quadrilaterals (Quad1PlaneStrainBB:
plastic flow keeps the volume, plain ones lock), then lifted back to its start in {up} steps.
Node-to-segment penalty on the top nodes with x <= 3, h = {h:g} near the contact.
First yield (Johnson, von Mises, nu = 0.3): p0 = 1.79 sig0 at 0.70 a below the surface, at
F = pi R p0^2/E* = 2.3 here, within the first step; by the deepest step the plastic zone is wide and the mean pressure F/(2a)
nears the plane-strain limit of a rigid-plastic flat punch, (2 + pi) sig0/sqrt(3) = 2.97 sig0.
On lifting, the block springs back elastically, the contact opens before the cylinder is back,
and a residual imprint with residual stresses stays. hertz: 4 to 9 iterations a step loading, 1 or
2 unloading, no cut-back; at the deepest step F = 34.47, a = 1.48, mean pressure 2.33 sig0; the
contact opens between depths 0.105 and 0.090 and the imprint is 0.0945 deep on the axis
(tests/suite/indentation.rs).
Run:  cargo run --release -- run examples/indentation.in
      cargo run --release -- plot examples/indentation.out --step 10   (load-unload curve, pressure)
The .vtu files carry equivalent_plastic_strain and plastic_strain per element (ParaView).
"""
    lines = header("indentation.out", "Elastoplastic indentation by a rigid cylinder, load and unload (plane strain)", comment)
    sets, bcs = rigid_records(m, ids, ref, xs, delta, 2)
    lines += common_records(
        m, ["SimpleCS 1 thick 1.0 material 1 set 1"],
        [f"MisesMat 1 d 0. E {E:g} n {NU:g} sig0 {sig0:g} H {hard:g} tAlpha 0."], bcs,
        ["ConstantFunction 1 f(t) 1.0",
         f"PiecewiseLinFunction 2 t 3 0 {down} {down + up} f(t) 3 0 1 0"],
        sets, 1,
        [f"circlecontactsegment 1 centerpoint 2 0 {R:g} radius {R:g} node {ref}"],
        f"StaticStructural nsteps {down + up} rtolf 1e-8 maxiter 40",
    )
    write("examples/indentation.in", lines)


def hertz_sphere_axisymmetric():
    """hertz_rigid_circle's mesh on axisymmetric elements: the circle is a rigid sphere."""
    R, h, fine, W, H, delta = RIGID
    m, xs, ys, ids, eids, ref = rigid_block()
    m.elems = [("L4Axisymm", n, extra) for (_, n, extra) in m.elems]
    comment = f"""
Hertz contact of a rigid sphere on an elastic body of revolution, axisymmetric (x = r, y = z, per
radian): the mesh of hertz_rigid_circle.in on L4Axisymm elements, a cylinder of radius {W:g} and
height {H:g}, E = {E:g}, nu = {NU:g}; the rigid sphere R = {R:g} (circlecontactsegment moving with node
{ref}) pushed down by delta = {delta:g}; node-to-segment penalty contact on the top nodes with r <= 3
(h = {h:g} near the contact). u_r = 0 on the axis (x = 0), the bottom held.
Analytical solution (Hertz, rigid sphere; F the total force, 2 pi times the force per radian):
  E* = E/(1 - nu^2),  a = (3 F R/(4 E*))^(1/3),  p0 = 3 F/(2 pi a^2),  p(r) = p0 sqrt(1 - r^2/a^2)
hertz: F = 46.43 (per radian 7.389), p0 47.46 against Hertz's 47.69 (-0.49 %), the pressure
within 1.6 % of p0 inside 0.9 a, the last closed node at 0.675 (a = 0.682); the same with
multipliers and with the mesh's penalty (tests/suite/axisymmetry.rs).
Run:  cargo run --release -- run examples/hertz_sphere_axisymmetric.in
      cargo run --release -- plot examples/hertz_sphere_axisymmetric.out   (pressure along r)
"""
    lines = header("hertz_sphere_axisymmetric.out", "Hertz: rigid sphere on an elastic block (axisymmetric)", comment)
    sets, bcs = rigid_records(m, ids, ref, xs, delta, 1)
    lines += common_records(
        m, ["SimpleCS 1 material 1 set 1"], [f"IsoLE 1 d 0. E {E:g} n {NU:g} tAlpha 0."], bcs,
        ["ConstantFunction 1 f(t) 1.0"], sets, 1,
        [f"circlecontactsegment 1 centerpoint 2 0 {R:g} radius {R:g} node {ref}"],
        "NonLinearStatic nsteps 1 controlmode 1 rtolf 1e-8 manrmsteps 1 maxiter 40",
    )
    lines = [l.replace("domain PlaneStrain", "domain 2dPlaneStress") for l in lines]
    write("examples/hertz_sphere_axisymmetric.in", lines)


# cattaneo_mindlin's shear: the top's horizontal displacement in step 2.
DX_CM = 0.005

hertz_rigid()
hertz_cylinder()
flat_punch()
cattaneo_mindlin()
hertz_mortar()
indentation()
hertz_sphere_axisymmetric()

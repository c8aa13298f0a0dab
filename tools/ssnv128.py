"""Code_Aster's SSNV128 (validation manual V6.04.128, "plate with contact and friction on a rigid
plane", after a GRECO 2D case) as a hertz input: a square plate of side 40 mm (E = 1.3e11,
nu = 0.2) lying on a rigid plane (y = 0, Coulomb friction mu = 1), pressed by a pressure 5e7 on
its top face and pushed sideways by a pressure 15e7 on its face x = 0; u_x = 0 on the face
x = 40 mm (the problem's symmetry plane), u_y = 0 at the node (40 mm, 0, 0) against rigid
motion; in 3D one layer of --n x --n LSpace bricks --t thick with u_z = 0 on every node (the 2D
problem). The plate's bottom faces are a mortar slave against the plane.

    python3 tools/ssnv128.py --n 16 --law penalty --out ssnv128.in && hertz run -v ssnv128.in

Issue 50 item 6: the mortar penalty with friction failed here even in 32 substeps (the corner
node on the back face, held along x and z, had a friction multiplier that moved nothing free but
round-off shares); now 6 iterations at 16 x 16, 10 at 32 x 32 (multipliers 6 and 9). The same
plate in 2D and 3D, every law, is the test
`friction::a_plate_pushed_along_a_rigid_plane_ssnv128_converges_with_every_law`.
"""
import argparse

p = argparse.ArgumentParser()
p.add_argument('--n', type=int, default=16)
p.add_argument('--t', type=float, default=0.002)
p.add_argument('--law', default='penalty')  # penalty (from the mesh) or mult
p.add_argument('--steps', type=int, default=1)
p.add_argument('--out', default='ssnv128.in')
a = p.parse_args()
n, side = a.n, 0.04
idx, nodes = {}, []
for k in range(2):
    for j in range(n + 1):
        for i in range(n + 1):
            idx[(i, j, k)] = len(nodes) + 1
            nodes.append((side * i / n, side * j / n, a.t * k))
elements = []
for j in range(n):
    for i in range(n):
        lower = [idx[(i, j, 0)], idx[(i + 1, j, 0)], idx[(i + 1, j + 1, 0)], idx[(i, j + 1, 0)]]
        upper = [idx[(i, j, 1)], idx[(i + 1, j, 1)], idx[(i + 1, j + 1, 1)], idx[(i, j + 1, 1)]]
        elements.append(lower + upper)


def element(i, j):
    return j * n + i + 1


# LSpace faces: 3 the y = j side, 5 the y = j + 1 side, 6 the x = i side.
bottom = [f'{element(i, 0)} 3' for i in range(n)]
top = [f'{element(i, n - 1)} 5' for i in range(n)]
left = [f'{element(0, j)} 6' for j in range(n)]
symmetry = [idx[(n, j, k)] for j in range(n + 1) for k in range(2)]
kind = 's2spenaltycontact' if a.law == 'penalty' else 's2slagrangianmultipliercontact'
ramp = (f'PiecewiseLinFunction 2 npoints 2 t 2 0 {a.steps} f(t) 2 0 1' if a.steps > 1
        else 'ConstantFunction 2 f(t) 1.0')
L = [a.out.replace('.in', '.out'), 'SSNV128 (Code_Aster V6.04.128) in 3D, u_z = 0',
     f'NonLinearStatic nsteps {a.steps} controlmode 1 rtolf 1e-8 maxiter 30', 'domain 3d',
     'OutputManager',
     f'ndofman {len(nodes)} nelem {len(elements)} ncrosssect 1 nmat 1 nbc 6 nic 0 nltf 2 nset 7 '
     'ncontactseg 2']
L += [f'node {k + 1} coords 3 {x:.10g} {y:.10g} {z:.10g}' for k, (x, y, z) in enumerate(nodes)]
L += [f'LSpace {e + 1} nodes 8 ' + ' '.join(map(str, v)) + ' crossSect 1 mat 1'
      for e, v in enumerate(elements)]
L += ['linear3delementsurfacecontactsegment 1 boundaryset 1',
      'planecontactsegment 2 point 3 0 0 0 normal 3 0 1 0',
      'SimpleCS 1 material 1 set 7', 'IsoLE 1 d 0 E 1.3e11 n 0.2 tAlpha 0',
      'BoundaryCondition 1 loadTimeFunction 1 dofs 1 1 values 1 0 set 2',
      'BoundaryCondition 2 loadTimeFunction 1 dofs 1 2 values 1 0 set 3',
      'BoundaryCondition 3 loadTimeFunction 1 dofs 1 3 values 1 0 set 4',
      'ConstantSurfaceLoad 4 loadTimeFunction 2 dofs 3 1 2 3 components 3 0 -5e7 0 set 5',
      'ConstantSurfaceLoad 5 loadTimeFunction 2 dofs 3 1 2 3 components 3 15e7 0 0 set 6',
      f'{kind} 6 loadTimeFunction 1 friction 1.0 slavesegment 1 segmentset 1 2',
      'ConstantFunction 1 f(t) 1.0', ramp,
      f'Set 1 elementboundaries {2 * n} ' + ' '.join(bottom),
      f'Set 2 nodes {len(symmetry)} ' + ' '.join(map(str, symmetry)),
      f'Set 3 nodes 1 {idx[(n, 0, 0)]}',
      f'Set 4 nodes {len(nodes)} ' + ' '.join(map(str, range(1, len(nodes) + 1))),
      f'Set 5 elementboundaries {2 * n} ' + ' '.join(top),
      f'Set 6 elementboundaries {2 * n} ' + ' '.join(left),
      'Set 7 allelements']
with open(a.out, 'w') as f:
    f.write('\n'.join(L) + '\n')

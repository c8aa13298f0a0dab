"""A ring (bore --ri, outside --ro) crushed between two rigid plates, each moved --crush x ro:
the whole ring with its bore in self-contact (--model full), or its upper half, its bore
against a rigid plane on the symmetry line (--model half). Plane strain (q4, q8, bb: barred
quadrilaterals; --kg sets K/G), or --dim 3: --nz layers of LSpace bricks over a length --tz,
u_z = 0 at z = 0. Neo-Hookean, nlgeo 1, multipliers (--law penalty for the penalty); the
bore node-to-segment, or --bore mortar (its half model's plane then twice as stiff).
Used for BENCHMARKS.md's self-contact section, e.g.

    python3 tools/crushed_ring.py --model full --dim 3 --nt 48 --nr 3 --nz 10 --tz 1.0 \
        --crush 0.8 --steps 20 --out whole.in && hertz run -q whole.in
"""
import math, argparse
p = argparse.ArgumentParser()
p.add_argument('--ri', type=float, default=0.6)
p.add_argument('--ro', type=float, default=1.0)
p.add_argument('--nr', type=int, default=3)
p.add_argument('--nt', type=int, default=48)
p.add_argument('--crush', type=float, default=0.5)  # each plate's travel / ro
p.add_argument('--steps', type=int, default=10)
p.add_argument('--law', default='mult')
p.add_argument('--model', default='full')
p.add_argument('--el', default='q4')
p.add_argument('--mat', default='nh')
p.add_argument('--out', default='ring.in')
p.add_argument('--dim', type=int, default=2)
p.add_argument('--kg', type=float, default=0.0)  # K/G (0: nu = 0.3)
p.add_argument('--tz', type=float, default=0.2)
p.add_argument('--nz', type=int, default=1)
p.add_argument('--skew', type=float, default=0.0)
p.add_argument('--holdall', type=int, default=0)
p.add_argument('--bore', default='n2s')  # or mortar
a = p.parse_args()
nr, nt = a.nr, a.nt
q = 2 if a.el == 'q8' else 1
NT = nt * q
full = a.model == 'full'
# node grid: layers i = 0..q*nr, angles j = 0..NT-1 (full) or 0..NT/2 (half)
J = NT if full else NT // 2 + 1
ids = {}
nodes = []
for i in range(q * nr + 1):
    r = a.ri + (a.ro - a.ri) * i / (q * nr)
    for j in range(J):
        if q == 2 and i % 2 == 1 and j % 2 == 1:
            continue
        th = 2 * math.pi * j / NT
        if j > NT // 2: th += a.skew * 2 * math.pi / NT * math.sin(math.pi * (j - NT // 2) / (NT // 2))
        nodes.append((r * math.cos(th), r * math.sin(th)))
        ids[(i, j)] = len(nodes)
def nid(i, j): return ids[(i, j % NT if full else j)]
nte = nt if full else nt // 2
elems = []
for i in range(nr):
    for j in range(nte):
        if q == 2:
            I, Jj = 2 * i, 2 * j
            elems.append((nid(I, Jj), nid(I + 2, Jj), nid(I + 2, Jj + 2), nid(I, Jj + 2),
                          nid(I + 1, Jj), nid(I + 2, Jj + 1), nid(I + 1, Jj + 2), nid(I, Jj + 1)))
        else:
            elems.append((nid(i, j), nid(i + 1, j), nid(i + 1, j + 1), nid(i, j + 1)))
P = len(nodes) + 1; Q = P + 1
nodes.append((0.0, a.ro)); nodes.append((0.0, -a.ro))
bore_el = [j + 1 for j in range(nte)]  # the bore's layer of elements
bore_nodes = [nid(0, j) for j in range(J)] if full else [nid(0, j) for j in range(1, J - 1)]
outer = [nid(q * nr, j) for j in range(J)]
d = a.crush * a.ro
kw = {'q4': 'Quad1PlaneStrain', 'q8': 'QPlaneStrain', 'bb': 'Quad1PlaneStrainBB'}[a.el]
L = ['ring.out', f'ring {a.model}', f'NonLinearStatic nsteps {a.steps} controlmode 1 rtolf 1e-10 maxiter 30',
     'domain PlaneStrain', 'OutputManager tstep_all dofman_all']
recs = ['linear2delementedgecontactsegment 1 edgeset 1',
        f'planecontactsegment 2 point 2 0 {a.ro} normal 2 0 -1 node {P}',
        f'planecontactsegment 3 point 2 0 {-a.ro} normal 2 0 1 node {Q}' if full
        else 'planecontactsegment 3 point 2 0 0 normal 2 0 1']
bcs = [f'BoundaryCondition 1 loadTimeFunction 2 dofs 2 1 2 values 2 0 {-d} set 2']
if full:
    bcs.append(f'BoundaryCondition 2 loadTimeFunction 2 dofs 2 1 2 values 2 0 {d} set 3')
else:
    bcs.append('BoundaryCondition 2 loadTimeFunction 1 dofs 1 2 values 1 0 set 3')
bcs.append('BoundaryCondition 3 loadTimeFunction 1 dofs 1 1 values 1 0 set 4')
kind = 'n2spenaltycontact' if a.law == 'penalty' else 'n2slagrangianmultipliercontact'
# The plates against the outside; the bore against itself (full) or the symmetry plane (half).
bcs.append(f'{kind} 4 loadTimeFunction 1 slaveset 5 segmentset ' + ('2 2 3' if full else '1 2'))
if a.bore == 'mortar':
    # The half model's gap to its plane is half the walls' overlap: twice the penalty.
    law = '' if a.law != 'penalty' else f' penalty {1e5 if full else 2e5:g}'
    s2s = 's2spenaltycontact' if a.law == 'penalty' else 's2slagrangianmultipliercontact'
    bcs.append(f'{s2s} 5 loadTimeFunction 1{law} slavesegment 1 segmentset 1 ' + ('1' if full else '3'))
else:
    bcs.append(f'{kind} 5 loadTimeFunction 1 slaveset 6 segmentset 1 ' + ('1' if full else '3'))
L.append(f'ndofman {len(nodes)} nelem {len(elems)} ncrosssect 1 nmat 1 nbc {len(bcs)} nic 0 nltf 2 nset 6 ncontactseg 3')
for k, (x, y) in enumerate(nodes):
    L.append(f'node {k+1} coords 2 {x:.15g} {y:.15g}')
for k, e in enumerate(elems):
    L.append(f'{kw} {k+1} nodes {len(e)} ' + ' '.join(map(str, e)) + ' crossSect 1 mat 1 nlgeo 1')
L += recs
L.append('SimpleCS 1 thick 1.0')
E, nu = 1000.0, 0.3
G = E / (2 * (1 + nu)); K = E / (3 * (1 - 2 * nu))
if a.kg > 0: K = a.kg * G
L.append(f'mooneyrivlincompressiblemat 1 d 0 c1 {G/2} c2 0 k {K}')
L += bcs
L.append('ConstantFunction 1 f(t) 1.0')
L.append(f'PiecewiseLinFunction 2 npoints 2 t 2 0 {a.steps} f(t) 2 0 1')
L.append('Set 1 elementboundaries %d ' % (2 * len(bore_el)) + ' '.join(f'{e} 4' for e in bore_el))
if full:
    L.append(f'Set 2 nodes 1 {P}')
    L.append(f'Set 3 nodes 1 {Q}')
    if a.holdall:
        hold = [nid(i, NT//4) for i in range(q*nr+1)] + [nid(i, 3*NT//4) for i in range(q*nr+1)]
        L.append(f'Set 4 nodes {len(hold)} ' + ' '.join(map(str, hold)))
    else:
        L.append(f'Set 4 nodes 2 {nid(q*nr, NT//4)} {nid(q*nr, 3*NT//4)}')
else:
    L.append(f'Set 2 nodes 1 {P}')
    cut = [nid(i, 0) for i in range(q * nr + 1) if (i, 0) in ids] + [nid(i, J - 1) for i in range(q * nr + 1) if (i, J - 1) in ids]
    L.append(f'Set 3 nodes {len(cut)} ' + ' '.join(map(str, cut)))
    if a.holdall:
        hold = [nid(i, NT//4) for i in range(q*nr+1)]
        L.append(f'Set 4 nodes {len(hold)} ' + ' '.join(map(str, hold)))
    else:
        L.append(f'Set 4 nodes 1 {nid(q*nr, NT//4)}')
L.append(f'Set 5 nodes {len(outer)} ' + ' '.join(map(str, outer)))
L.append(f'Set 6 nodes {len(bore_nodes)} ' + ' '.join(map(str, bore_nodes)))
if a.dim == 3:
    import re as _re
    assert q == 1
    nz = a.nz
    nn = len(nodes) - 2
    lay = lambda v, z: v + z * nn
    out = []
    for l in L:
        w = l.split()
        if l.startswith('domain'):
            out.append('domain 3d'); continue
        if l.startswith('node '):
            k = int(w[1]); x, y = float(w[4]), float(w[5])
            if k > nn:
                out.append(f'node {k + nz*nn} coords 3 {x:.15g} {y:.15g} 0'); continue
            for z in range(nz + 1):
                out.append(f'node {lay(k, z)} coords 3 {x:.15g} {y:.15g} {a.tz * z / nz:.15g}')
            continue
        if l.startswith('Quad1PlaneStrain'):
            e = list(map(int, w[4:8])); k = int(w[1])
            for z in range(nz):
                out.append(f'LSpace {(k - 1) * nz + z + 1} nodes 8 ' + ' '.join(str(lay(v, z)) for v in e) + ' ' + ' '.join(str(lay(v, z + 1)) for v in e) + ' crossSect 1 mat 1 nlgeo 1')
            continue
        if l.startswith('ndofman'):
            w[1] = str((nz + 1) * nn + 2); i = w.index('nbc'); w[i+1] = str(int(w[i+1]) + 1)
            i = w.index('nelem'); w[i+1] = str(int(w[i+1]) * nz)
            out.append(' '.join(w)); continue
        if l.startswith('linear2delementedgecontactsegment'):
            out.append('linear3delementsurfacecontactsegment 1 edgeset 1'); continue
        if l.startswith('planecontactsegment'):
            i = w.index('point'); j = w.index('normal')
            rest = w[j+4:]
            rest = [r if r.isalpha() else str(int(r) + nz * nn) for r in rest]
            out.append(' '.join(w[:i] + ['point', '3', w[i+2], w[i+3], '0', 'normal', '3', w[j+2], w[j+3], '0'] + rest)); continue
        if l.startswith('BoundaryCondition'):
            out.append(_re.sub(r'dofs 2 1 2 values 2 0 (\S+)', r'dofs 3 1 2 3 values 3 0 \1 0', l)); continue
        if l.startswith('Set '):
            k = int(w[1])
            if w[2] == 'elementboundaries':
                m = int(w[3]); pairs = w[4:]
                els = [int(pairs[2*i]) for i in range(m // 2)]
                faces = [f'{(e - 1) * nz + z + 1} 6' for e in els for z in range(nz)]
                out.append(f'Set {k} elementboundaries {2 * len(faces)} ' + ' '.join(faces)); continue
            ids_ = list(map(int, w[4:]))
            if k == 2 or (k == 3 and a.model == 'full'):
                out.append(f'Set {k} nodes 1 {ids_[0] + nz * nn}'); continue
            both = [lay(v, z) for z in range(nz + 1) for v in ids_]
            out.append(f'Set {k} nodes {len(both)} ' + ' '.join(map(str, both))); continue
        out.append(l)
    i = [k for k, l in enumerate(out) if l.startswith('ConstantFunction')][0]
    nb = sum(1 for l in out if l.startswith(('BoundaryCondition', 'n2s', 's2s')))
    out.insert(i, f'BoundaryCondition {nb+1} loadTimeFunction 1 dofs 1 3 values 1 0 set 7')
    out.append('Set 7 nodes %d ' % nn + ' '.join(str(k) for k in range(1, nn + 1)))
    out = [l.replace('nset 6', 'nset 7') for l in out]
    L = out
open(a.out, 'w').write('\n'.join(L) + '\n')

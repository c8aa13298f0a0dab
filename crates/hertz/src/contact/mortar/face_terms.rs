//! What 3D mortar integrates pair by pair in large deformation ([`super::faces`]): a slave and
//! a master face's integrands in duals over their coordinates ([`PairTerms`], along the
//! slave's normal, through curved sub-faces, or along the mirror rays of self-contact), summed
//! into the slave face's moments over the face's unknowns ([`Moments`]), which each of its
//! nodes weighs with its dual function adapted to the overlaps; and the dual basis of the
//! reference segmentation of small deformation ([`overlap_dual_basis`]).

use super::curved;
use super::mirror::mirror_overlap;
use super::segment::{overlap, Point};
use super::{SlipForm, Weighted};
use crate::contact::dual::{DualN, Jet};
use crate::contact::geometry::faces::{Face, FaceKind, NodalNormal};
use std::collections::HashMap;

/// How a mirrored pair's nodal normals move with the face's unknowns: for each normal
/// component (of `nodes` in the pair's order, then x, y, z) the face unknowns (`at(node)` the
/// face node) and ∂n_i/∂x.
pub(super) fn normal_chain<'a>(
    nodes: impl Iterator<Item = &'a usize>,
    normals: &HashMap<usize, NodalNormal>,
    at: impl Fn(usize) -> usize,
) -> Vec<Vec<(usize, f64)>> {
    let mut chain = Vec::new();
    for n in nodes {
        let jac = &normals[n].jac;
        for i in 0..3 {
            chain.push(
                (jac.iter())
                    .flat_map(|(b, d)| {
                        let f = at(*b);
                        (0..3).map(move |j| (3 * f + j, d[i][j]))
                    })
                    .collect(),
            );
        }
    }
    chain
}

/// The dual basis of a slave face with `k` nodes biorthogonal over the integration points
/// `points` of its overlaps with the master (Popp et al. 2013): A = D M⁻¹ of M = Σ N_a N_b w and
/// D = Σ N_a w over them. Where the master covers the whole face it is the face's own basis
/// ([`super::segment::dual_basis`]); over a part of it, Φ_j still integrates a linear gap field
/// to its value at node j times ∫ N_j, where the whole face's basis can be negative over the
/// overlap and gives a node beside a master's end a false penetration.
pub(super) fn overlap_dual_basis<'a>(
    k: usize,
    points: impl Iterator<Item = &'a Point<f64>>,
) -> [[f64; 4]; 4] {
    let (mut m, mut d) = ([[0.0; 4]; 4], [0.0; 4]);
    for p in points {
        for a in 0..k {
            d[a] += p.slave[a] * p.weight;
            for b in 0..k {
                m[a][b] += p.slave[a] * p.slave[b] * p.weight;
            }
        }
    }
    super::segment::biorthogonal(&m, &d, k)
}

/// One slave face's integrals in large deformation, before its dual basis is known: for each
/// of its weight functions b (N_b, a quadratic face's N̂_b) the weighted gap, force direction,
/// slip shares and normal, and the face's M = ∫ N_b N_c and D = ∫ N_b over its overlaps with the
/// master — all over the face's unknowns (its nodes' and its candidate master faces'), since
/// the basis adapted to the overlaps moves with every master face under the slave face. Shared
/// by the face's nodes, each of which weighs them with its own dual function
/// ([`Moments::weigh`]): summed once per pair, not once per node, and over the face's unknowns,
/// not each slot's (which hold every face around the node).
pub(super) struct Moments {
    /// [b]: ∫ N_b g.
    gap: Vec<Jet>,
    /// [b][face unknown]: ∫ N_b s_q ν_i.
    b: Vec<Vec<Jet>>,
    /// [b][face node]: ∫ N_b s_q.
    share: Vec<Vec<Jet>>,
    /// [b]: ∫ N_b ν.
    normal: Vec<[Jet; 3]>,
    m: Vec<Vec<Jet>>,
    d: Vec<Jet>,
}

impl Moments {
    /// Zero moments of a face with `kn` nodes and `nodes` face nodes in all.
    pub(super) fn new(kn: usize, nodes: usize) -> Moments {
        let nu = 3 * nodes;
        let zero = || Jet::constant(0.0, nu);
        Moments {
            gap: (0..kn).map(|_| zero()).collect(),
            b: (0..kn).map(|_| (0..nu).map(|_| zero()).collect()).collect(),
            share: (0..kn)
                .map(|_| (0..nodes).map(|_| zero()).collect())
                .collect(),
            normal: (0..kn).map(|_| std::array::from_fn(|_| zero())).collect(),
            m: (0..kn).map(|_| (0..kn).map(|_| zero()).collect()).collect(),
            d: (0..kn).map(|_| zero()).collect(),
        }
    }

    /// A pair's integrands `t` (placed among the face's unknowns by `map`).
    pub(super) fn add<const N: usize, const S: usize, const Q: usize>(
        &mut self,
        map: &PairMap,
        t: &PairTerms<N, S, Q>,
    ) {
        let kn = self.d.len();
        let place = &map.place;
        for b in 0..kn {
            map.add(&mut self.gap[b], &t.gap[b]);
            for q in 0..t.nodes {
                for i in 0..3 {
                    map.add(&mut self.b[b][place[3 * q + i]], &t.b[b][q][i]);
                }
                map.add(&mut self.share[b][place[3 * q] / 3], &t.share[b][q]);
            }
            for i in 0..3 {
                map.add(&mut self.normal[b][i], &t.normal[b][i]);
            }
            map.add(&mut self.d[b], &t.nw[b]);
            for c in 0..kn {
                map.add(&mut self.m[b][c], &t.m[b][c]);
            }
        }
    }

    /// Add face node `a`'s integrals weighted by its adapted dual function Φ_a = Σ_b A_ab N_b,
    /// A = D M⁻¹ with its derivative dA = (dD − A dM) M⁻¹, to its slot's `w` (face unknown e is
    /// the slot's unknown `to_slot[e]`).
    pub(super) fn weigh(&self, a: usize, to_slot: &[usize], w: &mut Weighted) {
        let kn = self.d.len();
        let nu = to_slot.len();
        let m0: Vec<Vec<f64>> = (0..kn)
            .map(|b| (0..kn).map(|c| self.m[b][c].v).collect())
            .collect();
        let inv = curved::inverse(&m0);
        let row: Vec<f64> = (0..kn).map(|c| self.d[a].v * inv[a][c]).collect();
        let coeffs: Vec<Jet> = (0..kn)
            .map(|c| {
                let d = (0..nu)
                    .map(|t| {
                        (0..kn)
                            .map(|e| {
                                let r = if e == a { self.d[a].d[t] } else { 0.0 }
                                    - (0..kn).map(|f| row[f] * self.m[f][e].d[t]).sum::<f64>();
                                r * inv[e][c]
                            })
                            .sum()
                    })
                    .collect();
                Jet { v: row[c], d }
            })
            .collect();
        // D_j is ∫ N_a over the overlaps.
        let one = Jet::constant(1.0, nu);
        mapped_product(&mut w.area, &one, &self.d[a], to_slot);
        for (c, coeff) in coeffs.iter().enumerate() {
            mapped_product(&mut w.gap, coeff, &self.gap[c], to_slot);
            for (e, b) in self.b[c].iter().enumerate() {
                mapped_product(&mut w.b[to_slot[e]], coeff, b, to_slot);
            }
            if let Some(slip) = &mut w.slip {
                for (i, n) in self.normal[c].iter().enumerate() {
                    mapped_product(&mut slip.normal[i], coeff, n, to_slot);
                }
                for (node, share) in self.share[c].iter().enumerate() {
                    if share.v == 0.0 && share.d.iter().all(|&x| x == 0.0) {
                        continue;
                    }
                    let k = to_slot[3 * node] / 3;
                    mapped_product(slip.share_mut(k), coeff, share, to_slot);
                }
            }
        }
    }
}

/// Whether a face is quadratic (6- or 8-node).
pub(super) fn is_quadratic(f: &Face) -> bool {
    matches!(f.kind, FaceKind::Tri6 | FaceKind::Quad8)
}

/// The unknowns (x, y, z of each) of `nodes` in a numbering where node n is `index(n)`.
pub(super) fn unknowns(nodes: &[usize], index: impl Fn(usize) -> usize) -> Vec<usize> {
    nodes
        .iter()
        .flat_map(|&n| {
            let i = index(n);
            [3 * i, 3 * i + 1, 3 * i + 2]
        })
        .collect()
}

/// dst += a·b for `a` and `b` over the face's unknowns, `dst` over a slot's (face unknown e is
/// the slot's unknown `map[e]`); nothing to do where b is zero (its value and gradient).
pub(super) fn mapped_product(dst: &mut Jet, a: &Jet, b: &Jet, map: &[usize]) {
    if b.v == 0.0 && b.d.iter().all(|&x| x == 0.0) {
        return;
    }
    dst.v += a.v * b.v;
    for ((&t, x), y) in map.iter().zip(&a.d).zip(&b.d) {
        dst.d[t] += x * b.v + a.v * y;
    }
}

/// Where a pair's duals go among a face's unknowns: pair unknown i (a node's coordinate) is
/// the face's `place[i]`; the duals beyond them (a mirrored pair's nodal normals' components)
/// each move the face's unknowns `chain[k]` with their derivatives.
pub(super) struct PairMap<'a> {
    pub(super) place: Vec<usize>,
    pub(super) chain: &'a [Vec<(usize, f64)>],
}

impl PairMap<'_> {
    /// Add `v` (over the pair's duals) to `jet` (over the face's unknowns).
    fn add<const N: usize>(&self, jet: &mut Jet, v: &DualN<N>) {
        add_pair(jet, &self.place, v);
        let n = self.place.len();
        for (k, terms) in self.chain.iter().enumerate() {
            let x = v.d[n + k];
            if x != 0.0 {
                for &(t, c) in terms {
                    jet.d[t] += c * x;
                }
            }
        }
    }
}

/// Add `v` (over a pair's unknowns, pair unknown i being `map[i]`) to `jet`.
pub(super) fn add_pair<const N: usize>(jet: &mut Jet, map: &[usize], v: &DualN<N>) {
    jet.v += v.v;
    for (&t, &x) in map.iter().zip(&v.d[..map.len()]) {
        jet.d[t] += x;
    }
}

/// Add `v` (over a pair's unknowns, pair unknown i being the slot's `map[i]`) to the share of
/// local node `k` in `slip`.
pub(super) fn add_share<const N: usize>(
    slip: &mut SlipForm,
    k: usize,
    map: &[usize],
    v: &DualN<N>,
) {
    add_pair(slip.share_mut(k), map, v);
}

/// A pair of faces' integrands over the pair's unknowns (in duals of N: 24 for linear faces, 48
/// where one is quadratic), summed over its overlap points, for each slave face node b's weight
/// function (its shape N_b, a quadratic face's modified N̂_b) in place of the dual function (the
/// basis adapted to the overlaps is known only once every point is in): the same for every
/// node of the slave face, so they are computed once and added to each node's [`Moments`].
/// S bounds the slave face's nodes, Q the pair's.
pub(super) struct PairTerms<const N: usize, const S: usize, const Q: usize> {
    /// Slave and master face nodes.
    nodes: usize,
    /// Σ N_b w over the points (w a point's weight); the sums below likewise.
    nw: [DualN<N>; S],
    /// N_b w g, g = (x_S − x_M)·ν at a point.
    gap: [DualN<N>; S],
    /// N_b w s_q ν_i, s_q the shape of node q there (negative for the master's).
    b: [[[DualN<N>; 3]; Q]; S],
    /// N_b w s_q.
    share: [[DualN<N>; Q]; S],
    /// N_b w ν_i.
    normal: [[DualN<N>; 3]; S],
    /// N_b N_c w.
    m: [[DualN<N>; S]; S],
}

impl<const N: usize, const S: usize, const Q: usize> Default for PairTerms<N, S, Q> {
    fn default() -> Self {
        let zero = DualN::constant(0.0, 0);
        PairTerms {
            nodes: 0,
            nw: [zero; S],
            gap: [zero; S],
            b: [[[zero; 3]; Q]; S],
            share: [[zero; Q]; S],
            normal: [[zero; 3]; S],
            m: [[zero; S]; S],
        }
    }
}

impl<const N: usize, const S: usize, const Q: usize> PairTerms<N, S, Q> {
    /// The terms of slave face `sf` against master face `mf` at positions `pos`, in duals over
    /// their coordinates; false when they do not overlap. Quadratic faces are segmented through
    /// their flat sub-faces ([`curved`]), ν the curved slave's normal at each point.
    pub(super) fn fill(&mut self, sf: &Face, mf: &Face, pos: &dyn Fn(usize) -> [f64; 3]) -> bool {
        let (kn, mn) = (sf.nodes.len(), mf.nodes.len());
        let curved = is_quadratic(sf) || is_quadratic(mf);
        let xv: Vec<[f64; 3]> = sf.nodes.iter().chain(&mf.nodes).map(|&n| pos(n)).collect();
        // Most candidates do not overlap: found in plain numbers first (the same decision the
        // duals' values make), at a fiftieth of the cost.
        if !curved && overlap(sf.kind, &xv[..kn], sf.side, mf.kind, &xv[kn..]).is_empty() {
            return false;
        }
        let nv = 3 * (kn + mn);
        let x: Vec<[DualN<N>; 3]> = (xv.iter().enumerate())
            .map(|(b, p)| std::array::from_fn(|i| DualN::variable(p[i], 3 * b + i, nv)))
            .collect();
        let (xs, xm) = x.split_at(kn);
        self.clear(kn, kn + mn);
        if curved {
            let mut any = false;
            let (slave, master) = ((sf.kind, xs, sf.side), (mf.kind, xm, mf.side));
            curved::each_curved_point(slave, master, |p| {
                let nu = p.slave_normal.map(|v| -v);
                self.add_point(xs, xm, (&p.slave, &p.master, &p.modified), &nu, p.weight);
                any = true;
            });
            any
        } else {
            let points = overlap(sf.kind, xs, sf.side, mf.kind, xm);
            for p in &points {
                self.add_point(xs, xm, (&p.slave, &p.master, &p.slave), &p.nu, p.weight);
            }
            !points.is_empty()
        }
    }

    /// The terms of slave face `sf` against own master face `mf` along the mirror rays
    /// ([`mirror_overlap`]), in duals over their coordinates and then their nodal normals'
    /// components (`normals`; [`normal_chain`] carries their derivatives to the coordinates):
    /// whether they overlap, None (the terms untouched) when a master corner cannot be carried.
    pub(super) fn fill_mirror(
        &mut self,
        sf: &Face,
        mf: &Face,
        pos: &dyn Fn(usize) -> [f64; 3],
        normals: &HashMap<usize, NodalNormal>,
    ) -> Option<bool> {
        let (kn, nodes) = (sf.nodes.len(), sf.nodes.len() + mf.nodes.len());
        // Whether they overlap, in plain numbers first (see `fill`).
        let (xv, nnv): (Vec<[f64; 3]>, Vec<[f64; 3]>) = (sf.nodes.iter().chain(&mf.nodes))
            .map(|&n| (pos(n), normals[&n].n))
            .unzip();
        let values = (&xv[..kn], &nnv[..kn]);
        if mirror_overlap(sf.kind, values, mf.kind, (&xv[kn..], &nnv[kn..]))?.is_empty() {
            return Some(false);
        }
        let nv = 6 * nodes;
        let var = |p: &[f64; 3], first: usize| -> [DualN<N>; 3] {
            std::array::from_fn(|i| DualN::variable(p[i], first + i, nv))
        };
        let x: Vec<[DualN<N>; 3]> = (xv.iter().enumerate())
            .map(|(b, p)| var(p, 3 * b))
            .collect();
        let nn: Vec<[DualN<N>; 3]> = (nnv.iter().enumerate())
            .map(|(b, n)| var(n, 3 * (nodes + b)))
            .collect();
        let (xs, xm) = x.split_at(kn);
        let points = mirror_overlap(sf.kind, (xs, &nn[..kn]), mf.kind, (xm, &nn[kn..]))?;
        self.clear(kn, nodes);
        for p in &points {
            self.add_point(xs, xm, (&p.slave, &p.master, &p.slave), &p.nu, p.weight);
        }
        Some(!points.is_empty())
    }

    /// Zero the terms of a pair with `kn` slave and `nodes` nodes in all (in place: the terms
    /// are large in duals).
    fn clear(&mut self, kn: usize, nodes: usize) {
        let zero = DualN::constant(0.0, 0);
        for b in 0..kn {
            self.nw[b] = zero;
            self.gap[b] = zero;
            self.b[b][..nodes].fill([zero; 3]);
            self.share[b][..nodes].fill(zero);
            self.normal[b] = [zero; 3];
            self.m[b][..kn].fill(zero);
        }
        self.nodes = nodes;
    }

    /// Add the terms of a point of the faces at `xs` (slave) and `xm` (master): the slave's and
    /// the master's shape values there and the slave's weight functions (`shapes`), ν and the
    /// point's weight.
    fn add_point(
        &mut self,
        xs: &[[DualN<N>; 3]],
        xm: &[[DualN<N>; 3]],
        (slave, master, basis): (&[DualN<N>], &[DualN<N>], &[DualN<N>]),
        nu: &[DualN<N>; 3],
        weight: DualN<N>,
    ) {
        let zero = weight * 0.0;
        let (kn, nodes) = (xs.len(), xs.len() + xm.len());
        let mut g = zero;
        for i in 0..3 {
            let mut d = zero;
            for (b, x) in xs.iter().enumerate() {
                d = d + slave[b] * x[i];
            }
            for (l, y) in xm.iter().enumerate() {
                d = d - master[l] * y[i];
            }
            g = g + d * nu[i];
        }
        let mut s = [zero; Q];
        for (q, sq) in s.iter_mut().enumerate().take(nodes) {
            *sq = if q < kn { slave[q] } else { -master[q - kn] };
        }
        let mut snu = [[zero; 3]; Q];
        for q in 0..nodes {
            for i in 0..3 {
                snu[q][i] = s[q] * nu[i];
            }
        }
        let t = self;
        debug_assert_eq!(t.nodes, nodes);
        for b in 0..kn {
            let nw = basis[b] * weight;
            t.nw[b] = t.nw[b] + nw;
            t.gap[b].add_mul(&nw, &g);
            for q in 0..nodes {
                for i in 0..3 {
                    t.b[b][q][i].add_mul(&nw, &snu[q][i]);
                }
                t.share[b][q].add_mul(&nw, &s[q]);
            }
            for i in 0..3 {
                t.normal[b][i].add_mul(&nw, &nu[i]);
            }
            for c in 0..kn {
                t.m[b][c].add_mul(&nw, &basis[c]);
            }
        }
    }
}

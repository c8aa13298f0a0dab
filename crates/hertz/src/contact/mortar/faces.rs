//! Mortar contact in 3D: triangle and quadrilateral slave faces against master faces, segmented
//! pair by pair on the slave face's auxiliary plane ([`super::segment`]), and against rigid
//! planes and spheres, integrated over each whole slave face ([`super::segment::face_rule`]) with
//! the gap of each point its signed distance to the shape and ν the shape's normal there.
//!
//! The weighted gap and the force direction are weighted by the slave nodes' dual shape functions
//! Φ_j: a slave node's force is then its own multiplier times its support, not spread over its
//! neighbours, so the pressure does not oscillate from node to node. Against master faces Φ_j is
//! biorthogonal to N_j over the part of each slave face that the master covers (Popp et al.
//! 2013; [`overlap_dual_basis`], and [`Moments`] in large deformation, where it moves with the
//! master faces and its derivative is in the tangent): over a whole face it is the face's own
//! basis, over a part of it a linear gap field still gives each node its own gap, where the
//! whole face's basis turns negative and gave nodes beside a master's end a false penetration.
//! Against rigid shapes, integrated over the whole face, it is the whole face's
//! ([`super::segment::dual_basis`]). The support D_j is ∫ N_j dA over the overlaps.
//!
//! Small deformation: the segmentation, ν and the weights are those of the reference
//! configuration, ν the blend of the slave's and the master's face normals that the contact
//! interface takes ([`interface_weights`]: the slave's alone made two equal spheres pressed
//! together differ from one on a rigid plane by 0.7 %), so each slave node's weighted gap is a
//! fixed linear form of the current
//! positions, g̃_j = Σ_n c_jn·x_n with c_jn = B_j at node n (computed once). Large deformation:
//! each overlapping pair is segmented at the current state in duals over its two faces'
//! coordinates and its integrals are scattered into the constraints of the slave face's nodes.
//!
//! Self-contact (the slave segment among the master segments, linear faces): each own face
//! meets the parts of the surface that face it squarely ([`own`]), a node never the faces
//! through itself; where two walls are within a face's size a face meets all its own partners
//! along the rays that bisect the walls' nodal normals ([`super::mirror`]), so that each wall as
//! a slave is the mirror image of the other; pairs of nodes that meet each other's walls at one
//! place hold one constraint (`contact::repeated`).

use super::curved::{self, CurvedPoint};
use super::face_terms::{
    add_pair, add_share, is_quadratic, normal_chain, overlap_dual_basis, unknowns, Moments,
    PairMap, PairTerms,
};
use super::mirror::mirror_overlap;
use super::segment::{dual_basis, face_rule, overlap, Point};
use super::{
    nearest_sheet, own, rigid_node, search_limit, Facing, MortarLaw, SlipForm, Weighted, GRAZING,
};
use crate::contact::dual::{DualN, Jet};
use crate::contact::formulation::{
    interface_weights, Ctx, Formulation, Local, Partner, Search, SlotState,
};
use crate::contact::geometry::faces::{
    self, cross, dot, face_normal, shape, sub, Face, FaceSurface, NodalNormal,
};
use crate::contact::geometry::rigid;
use crate::contact::search::broad::BroadPhase;
use crate::contact::slot::SlotLinearization;
use crate::error::{Error, Result};
use crate::model::{ContactCondition, Model, Pairing, SegmentKind};
use std::collections::HashMap;

/// Duals over the coordinates of one slave and one master face (4 + 4 nodes).
type PairDual = DualN<24>;

/// A slave node's weighted gap as a linear form of the current positions (small deformation).
struct LinearSlot {
    /// D_j.
    area: f64,
    /// (node, c_jn): g̃_j = Σ c_jn·x_n, and B_j.
    coeffs: Vec<(usize, [f64; 3])>,
    partner: Partner,
    /// (node, w_jn) and ∫ Φ_j ν: the weighted relative position of friction ([`SlipForm`]).
    shares: Vec<(usize, f64)>,
    normal: [f64; 3],
    /// Self-contact: the nodes of the own faces the slot meets (sorted).
    met: Vec<usize>,
}

impl LinearSlot {
    /// Add one integration point against master face `mi`: Φ_j dA (`phi`), N_j dA (`support`),
    /// ν, and the shape values of the slave nodes and (negated) the master nodes there.
    fn add(
        &mut self,
        mi: usize,
        phi: f64,
        support: f64,
        nu: &[f64; 3],
        shapes: impl Iterator<Item = (usize, f64)>,
    ) {
        if self.partner == Partner::None {
            self.partner = Partner::Face(mi);
        }
        self.area += support;
        for i in 0..3 {
            self.normal[i] += phi * nu[i];
        }
        for (n, shape) in shapes {
            let k = match self.coeffs.iter().position(|(m, _)| *m == n) {
                Some(k) => k,
                None => {
                    self.coeffs.push((n, [0.0; 3]));
                    self.shares.push((n, 0.0));
                    self.coeffs.len() - 1
                }
            };
            for i in 0..3 {
                self.coeffs[k].1[i] += phi * shape * nu[i];
            }
            self.shares[k].1 += phi * shape;
        }
    }
}

pub struct FaceMortar {
    law: MortarLaw,
    slave: FaceSurface,
    master: FaceSurface,
    /// Slave nodes (the slots), and for each the slave faces it belongs to.
    slots: Vec<(usize, Vec<usize>)>,
    slot_of: HashMap<usize, usize>,
    /// Large deformation: the geometry follows the current state.
    nlgeo: bool,
    /// Small deformation: the slots' linear forms, from the reference segmentation.
    linear: Vec<LinearSlot>,
    /// Per slave face, the coefficients of its whole reference face's dual basis: against rigid
    /// shapes in small deformation (in large, the current face's, [`FaceMortar::add_rigid`]).
    dual: Vec<[[f64; 4]; 4]>,
    /// Rigid master shapes (planes, spheres; model segment indices) and the nodes they move with.
    rigid: Vec<usize>,
    rigid_nodes: Vec<usize>,
    /// How far the search for master faces goes.
    search_limit: f64,
    /// Self-contact (the slave segment among the master segments): per master face, the slave
    /// face it is, if it is one of the slave's own.
    own: Vec<Option<usize>>,
    /// Per own master face, its element's shape and nodes (what lies behind it).
    own_elements: Vec<Option<(crate::fem::Shape, Vec<usize>)>>,
}

impl FaceMortar {
    pub fn new(model: &Model, ci: usize) -> Result<FaceMortar> {
        let c = &model.contacts[ci];
        let Pairing::Mortar { slave, segments } = &c.pairing else {
            unreachable!("a mortar condition")
        };
        let (rigid, face_segments) = split_masters(model, c, *slave, segments)?;
        let self_contact = segments.contains(slave);
        let slave = FaceSurface::new(model, &[*slave]);
        let master = FaceSurface::new(model, &face_segments);
        let own = own_faces(&slave, &master, self_contact);
        let rigid_nodes = check_surfaces(model, c, (&slave, &master), &rigid, &own)?;
        let (slots, slot_of) = slots_of(&slave);
        // Without a penalty, h is the mean size (√area) of the node's slave faces.
        let nodes: Vec<usize> = slots.iter().map(|s| s.0).collect();
        let reference = |n: usize| model.nodes[n].coords;
        let size: Vec<f64> = slave
            .faces
            .iter()
            .map(|f| Facet::at(f, &reference).size)
            .collect();
        let law = MortarLaw::new(
            model,
            ci,
            &nodes,
            |j| {
                let faces = &slots[j].1;
                faces.iter().map(|&k| size[k]).sum::<f64>() / faces.len() as f64
            },
            full_supports(model, &slave, &slots, &size),
        );
        // Against rigid shapes only, where the slave faces are linear.
        let dual = slave
            .faces
            .iter()
            .map(|f| {
                let x: Vec<[f64; 3]> = f.nodes.iter().map(|&n| reference(n)).collect();
                if rigid.is_empty() {
                    [[0.0; 4]; 4]
                } else {
                    dual_basis(f.kind, &x)
                }
            })
            .collect();
        let nodes = slave
            .faces
            .iter()
            .chain(&master.faces)
            .flat_map(|f| f.nodes.iter().copied());
        let mut mortar = FaceMortar {
            search_limit: search_limit(model, nodes),
            dual,
            law,
            nlgeo: slave.faces.iter().any(|f| f.nlgeo),
            slots,
            slot_of,
            linear: Vec::new(),
            rigid,
            rigid_nodes,
            own_elements: (own.iter().zip(&master.faces))
                .map(|(o, f)| {
                    let e = &model.elements[f.element];
                    o.map(|_| (e.etype.shape(), e.nodes.clone()))
                })
                .collect(),
            own,
            slave,
            master,
        };
        if !mortar.nlgeo {
            mortar.linear = mortar.reference_forms(model);
        }
        Ok(mortar)
    }

    /// Master faces that can overlap slave face `k` at positions `pos`: facing it, their
    /// centres within reach of its projection, of the nearest sheet ([`nearest_sheet`]); in
    /// self-contact not the face itself, and its own surface only where it faces the face
    /// squarely ([`own::OWN_FACING`]) and lies in front of it or within reach behind it
    /// ([`FaceMortar::own_within_reach`]). `pos` holds the own master faces' elements' nodes.
    fn candidates(
        &self,
        masters: &MasterIndex,
        k: usize,
        pos: &dyn Fn(usize) -> [f64; 3],
    ) -> Vec<usize> {
        let f = Facet::at(&self.slave.faces[k], pos);
        let found = nearest_sheet(f.size, self.search_limit, |grow| {
            let lo = f.lo.map(|v| v - grow);
            let hi = f.hi.map(|v| v + grow);
            Ok(masters
                .boxes
                .intersecting(lo, hi)
                .into_iter()
                .filter_map(|mi| {
                    let m = &masters.facets[mi];
                    let own = self.own[mi].is_some();
                    if self.own[mi] == Some(k) {
                        return None;
                    }
                    let d = sub(&m.centre, &f.centre);
                    let dist = dot(&d, &f.normal);
                    let squarely = if own { own::OWN_FACING } else { GRAZING };
                    let facing = dot(&f.normal, &m.normal) < squarely;
                    // The centre's offset in the slave's plane against both faces' reach.
                    let offset = sub(&d, &f.normal.map(|v| v * dist));
                    let near = dot(&offset, &offset).sqrt() <= f.diameter + m.diameter;
                    let reach = || !own || self.own_within_reach((k, &f), (mi, m), pos);
                    (facing && near && reach()).then_some(Facing {
                        index: mi,
                        dist,
                        size: m.size,
                    })
                })
                .collect())
        });
        found.unwrap_or_default()
    }

    /// Self-contact: whether own master face `mi` (at `m`) lies in front of slave face `k` (at
    /// `f`), or behind it within reach ([`own::within_reach`]), judged by the master's corners
    /// off the slave face: a face sharing a side or a corner with it lies in front across a
    /// closing crease, behind round a convex edge.
    fn own_within_reach(
        &self,
        (k, f): (usize, &Facet),
        (mi, m): (usize, &Facet),
        pos: &dyn Fn(usize) -> [f64; 3],
    ) -> bool {
        let (sf, mf) = (&self.slave.faces[k], &self.master.faces[mi]);
        let off: Vec<[f64; 3]> = (mf.nodes.iter())
            .filter(|n| !sf.nodes.contains(n))
            .map(|&n| pos(n))
            .collect();
        let behind = -off
            .iter()
            .map(|y| dot(&sub(y, &f.centre), &f.normal))
            .sum::<f64>()
            / off.len() as f64;
        // The depth of the master's element behind its face.
        let Some((shape, element)) = &self.own_elements[mi] else {
            return true;
        };
        let x: Vec<[f64; 3]> = element.iter().map(|&e| pos(e)).collect();
        let depth = (x.iter())
            .map(|y| dot(&sub(&m.centre, y), &m.normal))
            .fold(0.0, f64::max);
        // The slave's corners off that element: a face of the same element (a thin slab's far
        // side) lies on its boundary without having crossed it.
        let corners: Vec<[f64; 3]> = (sf.nodes.iter())
            .filter(|n| !element.contains(n))
            .map(|&n| pos(n))
            .collect();
        own::within_reach(behind, f.size.min(m.size), depth) || own::crossed(*shape, &x, &corners)
    }

    /// The master faces at positions `pos`, for the search.
    fn master_index(&self, pos: &dyn Fn(usize) -> [f64; 3]) -> MasterIndex {
        let boxes: Vec<Vec<[f64; 3]>> = self
            .master
            .faces
            .iter()
            .map(|f| f.nodes.iter().map(|&n| pos(n)).collect())
            .collect();
        MasterIndex {
            boxes: BroadPhase::new(boxes.iter().map(|v| (&v[..], v.len() > 4))),
            facets: self
                .master
                .faces
                .iter()
                .map(|f| Facet::at(f, pos))
                .collect(),
        }
    }

    /// The slots' linear forms g̃_j = Σ c_jn·x_n from the reference segmentation.
    fn reference_forms(&self, model: &Model) -> Vec<LinearSlot> {
        let pos = |n: usize| model.nodes[n].coords;
        let masters = self.master_index(&pos);
        let normals = self.own_normals(&pos);
        let mut forms: Vec<LinearSlot> = (0..self.slots.len())
            .map(|_| LinearSlot {
                area: 0.0,
                coeffs: Vec::new(),
                partner: Partner::None,
                shares: Vec::new(),
                normal: [0.0; 3],
                met: Vec::new(),
            })
            .collect();
        for k in 0..self.slave.faces.len() {
            let sf = &self.slave.faces[k];
            let xs: Vec<[f64; 3]> = sf.nodes.iter().map(|&n| pos(n)).collect();
            let candidates = self.candidates(&masters, k, &pos);
            if is_quadratic(sf)
                || candidates
                    .iter()
                    .any(|&mi| is_quadratic(&self.master.faces[mi]))
            {
                self.curved_forms(model, k, &xs, &candidates, &mut forms);
                continue;
            }
            // Each candidate's points, along the mirror rays where self-contact's walls are
            // close (then ν is the rays' own, not a blend).
            let mirrored = self.mirrored(k, &candidates, &pos, &normals);
            let normal =
                |f: &Face| -> Vec<[f64; 3]> { (f.nodes.iter()).map(|n| normals[n].n).collect() };
            let pieces: Vec<(usize, bool, Vec<Point<f64>>)> = candidates
                .into_iter()
                .map(|mi| {
                    let mf = &self.master.faces[mi];
                    let xm: Vec<[f64; 3]> = mf.nodes.iter().map(|&n| pos(n)).collect();
                    match mirrored && self.own[mi].is_some() {
                        true => {
                            let (ns, nm) = (normal(sf), normal(mf));
                            // A corner the rays do not carry: a face far round the surface.
                            let points = mirror_overlap(sf.kind, (&xs, &ns), mf.kind, (&xm, &nm));
                            (mi, true, points.unwrap_or_default())
                        }
                        false => (mi, false, overlap(sf.kind, &xs, sf.side, mf.kind, &xm)),
                    }
                })
                .filter(|(_, _, points)| !points.is_empty())
                .collect();
            // Each face node with the pieces it meets (in self-contact no own face through
            // itself) and its dual function biorthogonal over them.
            for a in 0..sf.nodes.len() {
                let meets = |mi: usize| {
                    self.own[mi].is_none() || !self.master.faces[mi].nodes.contains(&sf.nodes[a])
                };
                let met = || pieces.iter().filter(|p| meets(p.0));
                let dual = overlap_dual_basis(sf.nodes.len(), met().flat_map(|p| &p.2));
                for (mi, mirrored, points) in met() {
                    let mf = &self.master.faces[*mi];
                    let xm: Vec<[f64; 3]> = mf.nodes.iter().map(|&n| pos(n)).collect();
                    let (cx, ce) = faces::centre(mf.kind);
                    let nm = face_normal(mf.kind, &xm, mf.side, cx, ce);
                    let (ws, wm) = interface_weights(model, sf.element, mf.element);
                    for p in points {
                        let nu: [f64; 3] = match mirrored {
                            true => p.nu,
                            false => std::array::from_fn(|i| ws * p.nu[i] + wm * nm[i]),
                        };
                        let len = dot(&nu, &nu).sqrt();
                        let nu = nu.map(|v| v / len);
                        let shapes = (&p.slave[..], &p.master[..], &p.slave[..]);
                        let dual = |a: usize, b: usize| dual[a][b];
                        let at = (k, *mi, a);
                        self.add_reference_point(&mut forms, at, shapes, &dual, &nu, p.weight);
                    }
                    if self.own[*mi].is_some() {
                        forms[self.slot_of[&sf.nodes[a]]].met.extend(&mf.nodes);
                    }
                }
            }
        }
        for f in &mut forms {
            f.met.sort_unstable();
            f.met.dedup();
        }
        forms
    }

    /// Add slave face `k`'s integrals (nodes at `xs`) to the slots' linear forms when it or one
    /// of its `candidates` is quadratic: segmented through flat sub-faces, weighted with the dual
    /// basis of the modified shape functions ([`curved`]).
    fn curved_forms(
        &self,
        model: &Model,
        k: usize,
        xs: &[[f64; 3]],
        candidates: &[usize],
        forms: &mut [LinearSlot],
    ) {
        let sf = &self.slave.faces[k];
        let pieces: Vec<(usize, Vec<CurvedPoint>)> = candidates
            .iter()
            .map(|&mi| {
                let mf = &self.master.faces[mi];
                let xm: Vec<[f64; 3]> = mf.nodes.iter().map(|&n| model.nodes[n].coords).collect();
                let points =
                    curved::overlap_curved((sf.kind, xs, sf.side), (mf.kind, &xm, mf.side));
                (mi, points)
            })
            .filter(|(_, points)| !points.is_empty())
            .collect();
        let kn = sf.nodes.len();
        let dual = curved::dual_coefficients(kn, pieces.iter().flat_map(|p| &p.1));
        for (mi, points) in pieces {
            let mf = &self.master.faces[mi];
            let (ws, wm) = interface_weights(model, sf.element, mf.element);
            for p in points {
                // Towards the slave body: the blend of the two surfaces' normals there.
                let nu: [f64; 3] =
                    std::array::from_fn(|i| -ws * p.slave_normal[i] + wm * p.master_normal[i]);
                let len = dot(&nu, &nu).sqrt();
                let nu = nu.map(|v| v / len);
                let shapes = (&p.slave[..], &p.master[..], &p.modified[..]);
                let dual = |a: usize, b: usize| dual[a][b];
                for a in 0..sf.nodes.len() {
                    self.add_reference_point(forms, (k, mi, a), shapes, &dual, &nu, p.weight);
                }
            }
        }
    }

    /// Add one point of the reference segmentation of slave face `k` against master face `mi` to
    /// the slot of the slave face's node `a`: the slave's and the master's shape values there
    /// and the slave's weight functions (`shapes`: N, or a quadratic face's N̂), the coefficients
    /// `dual(a, b)` of node a's dual function over the weight functions, ν and the point's weight.
    fn add_reference_point(
        &self,
        forms: &mut [LinearSlot],
        (k, mi, a): (usize, usize, usize),
        (slave, master, basis): (&[f64], &[f64], &[f64]),
        dual: &dyn Fn(usize, usize) -> f64,
        nu: &[f64; 3],
        weight: f64,
    ) {
        let (sf, mf) = (&self.slave.faces[k], &self.master.faces[mi]);
        let kn = sf.nodes.len();
        let phi: f64 = (0..kn).map(|b| dual(a, b) * basis[b]).sum();
        let shapes = sf
            .nodes
            .iter()
            .copied()
            .zip(slave.iter().copied())
            .chain(mf.nodes.iter().copied().zip(master.iter().map(|v| -v)));
        forms[self.slot_of[&sf.nodes[a]]].add(mi, phi * weight, basis[a] * weight, nu, shapes);
    }

    /// Slot `j` in small deformation: its linear form at the current positions.
    fn linear_slot(&self, ctx: &Ctx, j: usize) -> Result<(Local, Weighted)> {
        let form = &self.linear[j];
        let mut local = Local::new(3);
        local.add(ctx, self.slots[j].0)?;
        for &(n, _) in &form.coeffs {
            local.add(ctx, n)?;
        }
        for &k in &self.slots[j].1 {
            for &n in self.rigid_face_nodes(k) {
                local.add(ctx, n)?;
            }
        }
        for &n in &self.rigid_nodes {
            local.add(ctx, n)?;
        }
        let m = local.m();
        let mut w = Weighted {
            gap: Jet::constant(0.0, m),
            area: Jet::constant(form.area, m),
            b: vec![Jet::constant(0.0, m); m],
            partner: form.partner,
            slip: Some(SlipForm {
                shares: form
                    .shares
                    .iter()
                    .map(|&(n, w)| (local.index(n), Jet::constant(w, m)))
                    .collect(),
                normal: form.normal.map(|v| Jet::constant(v, m)),
            }),
        };
        for &(n, c) in &form.coeffs {
            let k = local.index(n);
            for i in 0..3 {
                w.gap.v += c[i] * local.values()[3 * k + i];
                w.gap.d[3 * k + i] = c[i];
                w.b[3 * k + i].v = c[i];
            }
        }
        self.add_rigid(ctx, j, &local, &mut w)?;
        Ok((local, w))
    }

    /// The nodes of slave face `k` and the rigid shapes' nodes, when the condition has rigid
    /// shapes (none otherwise).
    fn rigid_face_nodes(&self, k: usize) -> &[usize] {
        if self.rigid.is_empty() {
            &[]
        } else {
            &self.slave.faces[k].nodes
        }
    }

    /// Add slot `j`'s integrals against the rigid shapes over its whole slave faces to `w` (over
    /// the unknowns of `local`): at each point of a face's rule the gap is the smallest signed
    /// distance to a shape, ν its normal there, and a shape moving with a node gives that node
    /// the reaction. Geometry (the area element) of the reference configuration in small
    /// deformation, current in large.
    fn add_rigid(&self, ctx: &Ctx, j: usize, local: &Local, w: &mut Weighted) -> Result<()> {
        if self.rigid.is_empty() {
            return Ok(());
        }
        let node = self.slots[j].0;
        for &k in &self.slots[j].1 {
            let face = &self.slave.faces[k];
            let a = face
                .nodes
                .iter()
                .position(|&n| n == node)
                .expect("the slot's node");
            let nodes: Vec<usize> = face
                .nodes
                .iter()
                .chain(&self.rigid_nodes)
                .copied()
                .collect();
            let nv = 3 * nodes.len();
            let mut x: Vec<[PairDual; 3]> = Vec::with_capacity(nodes.len());
            for (b, &n) in nodes.iter().enumerate() {
                let p = ctx.position(n)?.0;
                x.push(std::array::from_fn(|i| {
                    PairDual::variable(p[i], 3 * b + i, nv)
                }));
            }
            let geometry: Vec<[PairDual; 3]> = face
                .nodes
                .iter()
                .enumerate()
                .map(|(b, &n)| {
                    if self.nlgeo {
                        x[b]
                    } else {
                        ctx.model.nodes[n].coords.map(|v| PairDual::constant(v, nv))
                    }
                })
                .collect();
            let map = unknowns(&nodes, |n| local.index(n));
            let nf = face.nodes.len();
            // The face's dual basis: the reference face's in small deformation, the current
            // one's in large (with its derivative), as against element faces, where it is
            // biorthogonal over the current overlaps ([`Moments`]): a fold in self-contact then
            // equals its half model on a rigid plane.
            let coef = match self.nlgeo {
                true => dual_basis(face.kind, &geometry),
                false => self.dual[k].map(|r| r.map(|v| PairDual::constant(v, nv))),
            };
            for (xi, eta, wq) in face_rule(face.kind) {
                let (n, dxi, deta) = shape(face.kind, xi, eta);
                let mut t1 = [PairDual::constant(0.0, nv); 3];
                let mut t2 = t1;
                let mut xp = t1;
                for b in 0..nf {
                    for i in 0..3 {
                        t1[i] = t1[i] + geometry[b][i] * dxi[b];
                        t2[i] = t2[i] + geometry[b][i] * deta[b];
                        xp[i] = xp[i] + x[b][i] * n[b];
                    }
                }
                let c = cross(&t1, &t2);
                let da = dot(&c, &c).sqrt() * wq;
                let (g, nu, moving, shape) = self.rigid_gap(ctx, &nodes, &x, &xp);
                let phi = (0..4).fold(PairDual::constant(0.0, nv), |acc, b| {
                    acc + coef[a][b] * n[b]
                });
                let na = da * phi;
                let add = |jet: &mut Jet, v: PairDual| add_pair(jet, &map, &v);
                add(&mut w.gap, na * g);
                add(&mut w.area, da * n[a]);
                for b in 0..nf {
                    for i in 0..3 {
                        add(&mut w.b[map[3 * b + i]], na * n[b] * nu[i]);
                    }
                }
                if let Some(r) = moving {
                    for i in 0..3 {
                        add(&mut w.b[map[3 * r + i]], -(na * nu[i]));
                    }
                }
                if w.partner == Partner::None {
                    w.partner = Partner::Rigid(shape);
                }
                if let Some(slip) = &mut w.slip {
                    for b in 0..nf {
                        add_share(slip, local.index(nodes[b]), &map, &(na * n[b]));
                    }
                    if let Some(r) = moving {
                        add_share(slip, local.index(nodes[r]), &map, &-na);
                    }
                    for i in 0..3 {
                        add(&mut slip.normal[i], na * nu[i]);
                    }
                }
            }
        }
        Ok(())
    }

    /// The smallest signed distance from `xp` to the rigid shapes, their outward normal there,
    /// the position in `nodes` of the node the nearest shape moves with, if any (`x` the
    /// positions of `nodes`), and that shape (a model segment index).
    fn rigid_gap(
        &self,
        ctx: &Ctx,
        nodes: &[usize],
        x: &[[PairDual; 3]],
        xp: &[PairDual; 3],
    ) -> (PairDual, [PairDual; 3], Option<usize>, usize) {
        let nv = xp[0].n;
        let mut best: Option<(PairDual, [PairDual; 3], Option<usize>, usize)> = None;
        for &g in &self.rigid {
            let node = rigid_node(ctx.model, g);
            let r = node.map(|n| nodes.iter().position(|&m| m == n).expect("a rigid node"));
            // A reference point moved with the shape's node.
            let origin = |p: [f64; 3]| -> [PairDual; 3] {
                std::array::from_fn(|i| match (node, r) {
                    (Some(n), Some(r)) => x[r][i] + (p[i] - ctx.model.nodes[n].coords[i]),
                    _ => PairDual::constant(p[i], nv),
                })
            };
            let (gap, n) = match &ctx.model.segments[g].kind {
                SegmentKind::Circle {
                    center,
                    radius,
                    cavity,
                    ..
                } => rigid::circle(&xp[..], &origin(*center), *radius, *cavity),
                SegmentKind::Plane { point, normal, .. } => {
                    rigid::plane(&xp[..], &origin(*point), &normal[..])
                }
                _ => unreachable!("rigid planes and spheres"),
            };
            if best.as_ref().is_none_or(|b| gap.v < b.0.v) {
                best = Some((gap, [n[0], n[1], n[2]], r, g));
            }
        }
        best.expect("a rigid shape")
    }

    /// Every slot in large deformation: the current segmentation of each slave face against its
    /// candidates, each pair's integrals scattered into the slots of the slave face's nodes;
    /// per slot the nodes of the own faces it meets (self-contact) and the seconds spent
    /// finding the candidates.
    fn current_slots(&self, ctx: &Ctx) -> Result<CurrentSlots> {
        let start = std::time::Instant::now();
        let mut positions = HashMap::new();
        let own_elements = self.own_elements.iter().flatten().flat_map(|e| &e.1);
        for &n in (self.slave.faces.iter().chain(&self.master.faces))
            .flat_map(|f| &f.nodes)
            .chain(own_elements)
        {
            if let std::collections::hash_map::Entry::Vacant(e) = positions.entry(n) {
                e.insert(ctx.position(n)?.0);
            }
        }
        let pos = |n: usize| positions[&n];
        let masters = self.master_index(&pos);
        let candidates: Vec<Vec<usize>> = (0..self.slave.faces.len())
            .map(|k| self.candidates(&masters, k, &pos))
            .collect();
        let normals = self.own_normals(&pos);
        // Per slave face: its own candidates cut along the mirror rays.
        let mirrored: Vec<bool> = (candidates.iter().enumerate())
            .map(|(k, c)| self.mirrored(k, c, &pos, &normals))
            .collect();
        let searching = start.elapsed().as_secs_f64();
        // Each face's unknowns: its nodes, its candidates', and those the nodal normals of its
        // mirrored pairs move with.
        let face_nodes: Vec<Vec<usize>> = (self.slave.faces.iter().enumerate())
            .map(|(k, sf)| {
                let mut nodes: Vec<usize> = sf.nodes.clone();
                let mut add = |n: usize| {
                    if !nodes.contains(&n) {
                        nodes.push(n);
                    }
                };
                for &mi in &candidates[k] {
                    let mf = &self.master.faces[mi];
                    mf.nodes.iter().for_each(|&n| add(n));
                    if mirrored[k] && self.own[mi].is_some() {
                        for n in sf.nodes.iter().chain(&mf.nodes) {
                            normals[n].jac.iter().for_each(|&(b, _)| add(b));
                        }
                    }
                }
                nodes
            })
            .collect();
        let mut out = Vec::with_capacity(self.slots.len());
        for (node, faces) in &self.slots {
            let mut local = Local::new(3);
            local.add(ctx, *node)?;
            for &k in faces {
                for &n in face_nodes[k].iter().chain(self.rigid_face_nodes(k)) {
                    local.add(ctx, n)?;
                }
            }
            for &n in &self.rigid_nodes {
                local.add(ctx, n)?;
            }
            let m = local.m();
            let w = Weighted {
                gap: Jet::constant(0.0, m),
                area: Jet::constant(0.0, m),
                b: vec![Jet::constant(0.0, m); m],
                partner: Partner::None,
                slip: Some(SlipForm {
                    shares: Vec::new(),
                    normal: std::array::from_fn(|_| Jet::constant(0.0, m)),
                }),
            };
            out.push((local, w));
        }
        let mut met = vec![Vec::new(); self.slots.len()];
        let mut terms = Box::<PairTerms<24, 4, 8>>::default();
        let mut curved_terms: Option<Box<PairTerms<48, 8, 16>>> = None;
        let mut mirror_terms: Option<Box<PairTerms<48, 4, 8>>> = None;
        for (k, sf) in self.slave.faces.iter().enumerate() {
            let kn = sf.nodes.len();
            let face_nodes = &face_nodes[k];
            let at = |n: usize| {
                face_nodes
                    .iter()
                    .position(|&m| m == n)
                    .expect("a face node")
            };
            // The face's nodes in groups that meet the same candidates (in self-contact a node
            // meets no own face through itself), each group with its integrals weighted by
            // each N_b and its M and D over its overlaps (the dual basis adapted to them), over
            // the face's unknowns.
            let meets = |a: usize, mi: usize| {
                self.own[mi].is_none() || !self.master.faces[mi].nodes.contains(&sf.nodes[a])
            };
            let mut groups: Vec<(Vec<bool>, Vec<usize>, Option<Moments>)> = Vec::new();
            for a in 0..kn {
                let key: Vec<bool> = candidates[k].iter().map(|&mi| meets(a, mi)).collect();
                match groups.iter_mut().find(|g| g.0 == key) {
                    Some(g) => g.1.push(a),
                    None => groups.push((key, vec![a], None)),
                }
            }
            for (c, &mi) in candidates[k].iter().enumerate() {
                if !groups.iter().any(|g| g.0[c]) {
                    continue;
                }
                let mf = &self.master.faces[mi];
                // The integrands are linear in the points' terms: summed over the pair's points
                // first, then added to the face's moments once.
                let mirror = match mirrored[k] && self.own[mi].is_some() {
                    true => {
                        let t = mirror_terms.get_or_insert_with(Default::default);
                        // A corner the rays do not carry: a face far round the surface.
                        Some(t.fill_mirror(sf, mf, &pos, &normals).unwrap_or(false))
                    }
                    false => None,
                };
                let curved = is_quadratic(sf) || is_quadratic(mf);
                let overlapping = match mirror {
                    Some(overlapping) => overlapping,
                    None if curved => curved_terms
                        .get_or_insert_with(Default::default)
                        .fill(sf, mf, &pos),
                    None => terms.fill(sf, mf, &pos),
                };
                if !overlapping {
                    continue;
                }
                // Pair unknown p is the face's unknown map[p], the nodal normals' beyond them
                // chained to the face's unknowns.
                let chain = match mirror {
                    Some(_) => normal_chain(sf.nodes.iter().chain(&mf.nodes), &normals, at),
                    None => Vec::new(),
                };
                let pair: Vec<usize> = sf.nodes.iter().chain(&mf.nodes).copied().collect();
                let map = PairMap {
                    place: unknowns(&pair, at),
                    chain: &chain,
                };
                for group in groups.iter_mut().filter(|g| g.0[c]) {
                    for &a in &group.1 {
                        let j = self.slot_of[&sf.nodes[a]];
                        if out[j].1.partner == Partner::None {
                            out[j].1.partner = Partner::Face(mi);
                        }
                        if self.own[mi].is_some() {
                            met[j].extend_from_slice(&mf.nodes);
                        }
                    }
                    let mo = (group.2).get_or_insert_with(|| Moments::new(kn, face_nodes.len()));
                    match (&mirror, &mirror_terms, &curved_terms, curved) {
                        (Some(_), Some(t), _, _) => mo.add(&map, t),
                        (None, _, Some(t), true) => mo.add(&map, t),
                        _ => mo.add(&map, &terms),
                    }
                }
            }
            for (_, nodes, moments) in groups {
                let Some(mo) = moments else {
                    continue;
                };
                for a in nodes {
                    let (local, w) = &mut out[self.slot_of[&sf.nodes[a]]];
                    // Face unknown e is the slot's unknown to_slot[e].
                    let to_slot = unknowns(face_nodes, |n| local.index(n));
                    mo.weigh(a, &to_slot, w);
                }
            }
        }
        for (j, (local, w)) in out.iter_mut().enumerate() {
            self.add_rigid(ctx, j, local, w)?;
        }
        for m in &mut met {
            m.sort_unstable();
            m.dedup();
        }
        Ok(CurrentSlots {
            slots: out,
            met,
            searching,
        })
    }

    /// Self-contact: the nodal normals of the slave surface's nodes at positions `pos`, with
    /// their derivatives (none without self-contact).
    fn own_normals(&self, pos: &dyn Fn(usize) -> [f64; 3]) -> HashMap<usize, NodalNormal> {
        if self.own.iter().all(Option::is_none) {
            return HashMap::new();
        }
        (self.slots.iter())
            .map(|(n, _)| (*n, self.slave.nodal_normal_jacobian(*n, pos)))
            .collect()
    }

    /// Self-contact: whether slave face `k` meets its own surface among `candidates` along the
    /// mirror rays ([`mirror_overlap`]): one own candidate within the face's size ([`close`]),
    /// every nodal normal of the face and of its own candidates defined (not the tip of a crease
    /// folded flat, as in 2D: the faces' normals there cancel). One way for all of a face's own
    /// candidates: their parts tile the face only if all are cut along the same rays.
    fn mirrored(
        &self,
        k: usize,
        candidates: &[usize],
        pos: &dyn Fn(usize) -> [f64; 3],
        normals: &HashMap<usize, NodalNormal>,
    ) -> bool {
        let sf = &self.slave.faces[k];
        let own: Vec<&Face> = (candidates.iter())
            .filter(|&&mi| self.own[mi].is_some())
            .map(|&mi| &self.master.faces[mi])
            .collect();
        if own.is_empty() {
            return false;
        }
        let defined = (sf.nodes.iter())
            .chain(own.iter().flat_map(|f| &f.nodes))
            .all(|n| normals[n].agreement > 5e-4);
        let corners = |f: &Face| f.nodes.iter().map(|&n| pos(n)).collect::<Vec<_>>();
        let size = Facet::at(sf, pos).size;
        defined && own.iter().any(|mf| close(&corners(sf), &corners(mf), size))
    }
}

/// What [`FaceMortar::current_slots`] gives: every slot's integrals over its local unknowns,
/// per slot the nodes of the own faces it meets (sorted), the seconds spent searching.
struct CurrentSlots {
    slots: Vec<(Local, Weighted)>,
    met: Vec<Vec<usize>>,
    searching: f64,
}

/// The master faces at some positions: their broad phase and their shapes.
struct MasterIndex {
    boxes: BroadPhase,
    facets: Vec<Facet>,
}

/// What the search needs of a face at some positions.
struct Facet {
    centre: [f64; 3],
    /// Unit outward normal at the parametric centre.
    normal: [f64; 3],
    /// The square root of its area.
    size: f64,
    /// The largest distance between two of its nodes.
    diameter: f64,
    /// Its bounding box.
    lo: [f64; 3],
    hi: [f64; 3],
}

impl Facet {
    fn at(face: &Face, pos: &dyn Fn(usize) -> [f64; 3]) -> Facet {
        let x: Vec<[f64; 3]> = face.nodes.iter().map(|&n| pos(n)).collect();
        let k = x.len() as f64;
        let centre = x.iter().fold([0.0; 3], |c, p| {
            [c[0] + p[0] / k, c[1] + p[1] / k, c[2] + p[2] / k]
        });
        let (cx, ce) = faces::centre(face.kind);
        // The area from the diagonals' (a triangle's sides') cross product, on the corners.
        let (d1, d2) = if face.kind.corners() == 4 {
            (sub(&x[2], &x[0]), sub(&x[3], &x[1]))
        } else {
            (sub(&x[1], &x[0]), sub(&x[2], &x[0]))
        };
        let c = cross(&d1, &d2);
        let mut diameter = 0.0f64;
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for (i, a) in x.iter().enumerate() {
            for b in &x[i + 1..] {
                let v = sub(a, b);
                diameter = diameter.max(dot(&v, &v).sqrt());
            }
            for j in 0..3 {
                lo[j] = lo[j].min(a[j]);
                hi[j] = hi[j].max(a[j]);
            }
        }
        Facet {
            centre,
            normal: face_normal(face.kind, &x, face.side, cx, ce),
            size: (0.5 * dot(&c, &c).sqrt()).sqrt(),
            diameter,
            lo,
            hi,
        }
    }
}

impl Formulation for FaceMortar {
    fn n_slots(&self) -> usize {
        self.slots.len()
    }

    fn n_multipliers(&self) -> usize {
        self.law.n_multipliers(self.slots.len())
    }

    fn nodes_needing_dofs(&self) -> Vec<usize> {
        let mut out: Vec<usize> = self.slots.iter().map(|s| s.0).collect();
        out.extend(&self.rigid_nodes);
        out
    }

    fn candidate_nodes(&self, _ctx: &Ctx) -> Result<Vec<usize>> {
        let mut out = self.nodes_needing_dofs();
        out.extend(
            self.master
                .faces
                .iter()
                .flat_map(|f| f.nodes.iter().copied()),
        );
        out.sort_unstable();
        out.dedup();
        Ok(out)
    }

    fn penalties(&self) -> Option<(usize, f64, f64)> {
        self.law.penalties()
    }

    fn symmetric(&self) -> bool {
        // B = ∇g̃ in small deformation against faces, but for a self-contact pair's merged
        // constraint.
        !self.nlgeo
            && self.rigid.is_empty()
            && self.law.symmetric()
            && self.own.iter().all(Option::is_none)
    }

    fn partner_nodes(&self, partner: Partner) -> &[usize] {
        match partner {
            Partner::Face(k) => &self.master.faces[k].nodes,
            _ => &[],
        }
    }

    fn slave_transform(&self) -> Vec<(usize, usize, f64)> {
        if self.law.n_multipliers(1) == 0 {
            return Vec::new();
        }
        curved::transform_rows(self.slave.faces.iter().map(|f| (f.kind, &f.nodes[..])))
    }

    fn evaluate(
        &self,
        ctx: &Ctx,
        first_lambda: usize,
        _search: Search,
        history: Option<&[SlotState]>,
        points: &mut Vec<SlotLinearization>,
        states: &mut Vec<SlotState>,
    ) -> Result<f64> {
        let (slots, met, searching) = if self.nlgeo {
            let current = self.current_slots(ctx)?;
            (current.slots, current.met, current.searching)
        } else {
            let slots = (0..self.slots.len())
                .map(|j| self.linear_slot(ctx, j))
                .collect::<Result<Vec<_>>>()?;
            let met = self.linear.iter().map(|f| f.met.clone()).collect();
            (slots, met, 0.0)
        };
        let nodes: Vec<usize> = self.slots.iter().map(|s| s.0).collect();
        // Self-contact: pairs that repeat one contact hold it by one constraint.
        let pairs = match self.own.iter().any(Option::is_some) {
            true => {
                let pos = |n: usize| ctx.position(n).map(|p| p.0);
                // The shortest side of a slot's slave faces.
                let spacing = |j: usize| -> Result<f64> {
                    let mut spacing = f64::INFINITY;
                    for &k in &self.slots[j].1 {
                        let f = &self.slave.faces[k];
                        let nc = f.kind.corners();
                        for a in 0..nc {
                            let d = sub(&pos(f.nodes[a])?, &pos(f.nodes[(a + 1) % nc])?);
                            spacing = spacing.min(dot(&d, &d).sqrt());
                        }
                    }
                    Ok(spacing)
                };
                let supported = |j: usize| self.law.supported(j, slots[j].1.area.v);
                own::repeated_pairs(ctx, &nodes, &met, &supported, &spacing, history)?
            }
            false => Vec::new(),
        };
        self.law.evaluate_slots(
            ctx,
            first_lambda,
            &nodes,
            slots,
            &pairs,
            history,
            points,
            states,
        )?;
        Ok(searching)
    }
}

/// The input error of condition `c`.
fn input_error(c: &ContactCondition, msg: &str) -> Error {
    Error::Input {
        span: c.span.clone(),
        msg: msg.into(),
    }
}

/// A 3D mortar condition's masters split into rigid shapes and face segments (model segment
/// indices): element faces meet element faces, rigid planes and spheres.
fn split_masters(
    model: &Model,
    c: &ContactCondition,
    slave: usize,
    segments: &[usize],
) -> Result<(Vec<usize>, Vec<usize>)> {
    if !matches!(model.segments[slave].kind, SegmentKind::Faces { .. }) {
        return Err(input_error(
            c,
            "in 3D the slave segment of a mortar condition must be element faces",
        ));
    }
    if segments.iter().any(|&g| {
        matches!(
            model.segments[g].kind,
            SegmentKind::Polynomial { .. } | SegmentKind::Edges { .. }
        )
    }) {
        return Err(input_error(
            c,
            "mortar contact in 3D meets element faces, rigid planes and spheres (a polynomial \
             curve or element edges are 2D masters)",
        ));
    }
    let rigid: Vec<usize> = segments
        .iter()
        .copied()
        .filter(|&g| !matches!(model.segments[g].kind, SegmentKind::Faces { .. }))
        .collect();
    let faces = segments
        .iter()
        .copied()
        .filter(|g| !rigid.contains(g))
        .collect();
    Ok((rigid, faces))
}

/// What the slave and master surfaces of a 3D mortar condition may be: not empty, faces or
/// rigid shapes (at most 4 moving with nodes, whose nodes are returned) but not both, no nodes
/// shared but with the slave's own faces (self-contact, `own`), quadratic slave faces against
/// faces only (they are segmented through flat sub-faces, [`super::curved`]) and not in
/// self-contact.
fn check_surfaces(
    model: &Model,
    c: &ContactCondition,
    (slave, master): (&FaceSurface, &FaceSurface),
    rigid: &[usize],
    own: &[Option<usize>],
) -> Result<Vec<usize>> {
    if slave.faces.is_empty() || (master.faces.is_empty() && rigid.is_empty()) {
        return Err(input_error(
            c,
            "the slave or master segment has no element faces",
        ));
    }
    if !master.faces.is_empty() && !rigid.is_empty() {
        return Err(input_error(
            c,
            "a 3D mortar condition meets element faces or rigid shapes, not both: give \
             each its own condition",
        ));
    }
    let rigid_nodes: Vec<usize> = rigid.iter().filter_map(|&g| rigid_node(model, g)).collect();
    if rigid_nodes.len() > 4 {
        return Err(input_error(
            c,
            "a 3D mortar condition meets at most 4 rigid shapes that move with nodes",
        ));
    }
    let self_contact = own.iter().any(Option::is_some);
    if self_contact && slave.faces.iter().chain(&master.faces).any(is_quadratic) {
        return Err(input_error(
            c,
            "mortar self-contact takes linear (3- and 4-node) faces: a node-to-segment \
             condition (`n2s...`) whose `slaveset` holds the segment's nodes is self-contact on \
             quadratic ones",
        ));
    }
    let others = (master.faces.iter().zip(own))
        .filter(|(_, o)| o.is_none())
        .flat_map(|(f, _)| &f.nodes);
    if others.into_iter().any(|n| slave.at_node.contains_key(n)) {
        return Err(input_error(
            c,
            "the slave and master segments share nodes: a surface cannot contact itself",
        ));
    }
    if slave.faces.iter().any(is_quadratic) && !rigid.is_empty() {
        return Err(input_error(
            c,
            "mortar contact of quadratic (6- and 8-node) slave faces meets element faces, \
             not rigid shapes; use node-to-segment contact (n2s...) against a rigid shape",
        ));
    }
    Ok(rigid_nodes)
}

/// Self-contact (`self_contact`: the slave segment among the masters): per master face, the
/// slave face it is, if it is one of the slave's own.
fn own_faces(slave: &FaceSurface, master: &FaceSurface, self_contact: bool) -> Vec<Option<usize>> {
    let key = |f: &Face| {
        let mut nodes = f.nodes.clone();
        nodes.sort_unstable();
        (f.element, nodes)
    };
    let index: HashMap<_, usize> = (slave.faces.iter().enumerate())
        .map(|(k, f)| (key(f), k))
        .collect();
    (master.faces.iter())
        .map(|f| index.get(&key(f)).copied().filter(|_| self_contact))
        .collect()
}

/// The distance from `p` to the triangle `t`.
fn to_triangle(p: &[f64; 3], t: &[[f64; 3]; 3]) -> f64 {
    let to_segment = |a: &[f64; 3], b: &[f64; 3]| {
        let (ab, ap) = (sub(b, a), sub(p, a));
        let s = (dot(&ap, &ab) / dot(&ab, &ab)).clamp(0.0, 1.0);
        let r = sub(&ap, &ab.map(|v| v * s));
        dot(&r, &r).sqrt()
    };
    let n = cross(&sub(&t[1], &t[0]), &sub(&t[2], &t[0]));
    let len = dot(&n, &n).sqrt();
    let r = sub(p, &t[0]);
    // Inside the prism over the triangle: its plane's distance.
    let inside = (0..3).all(|i| {
        let (a, b) = (&t[i], &t[(i + 1) % 3]);
        dot(&cross(&sub(b, a), &sub(p, a)), &n) >= 0.0
    });
    if inside && len > 0.0 {
        return (dot(&r, &n) / len).abs();
    }
    (0..3)
        .map(|i| to_segment(&t[i], &t[(i + 1) % 3]))
        .fold(f64::INFINITY, f64::min)
}

/// Whether two faces (corners `xs`, `xm`) are within `size` of each other: self-contact's walls
/// close enough to meet along the mirror rays ([`super::mirror`]). Farther apart the rays are
/// along the slave's normal: on the walls of an open bore the bisectors of the normals join
/// points far round it, and their parts and gaps are ill-posed; an open gap exerts no force, so
/// the switch changes nothing a step converges to.
fn close(xs: &[[f64; 3]], xm: &[[f64; 3]], size: f64) -> bool {
    let triangles = |x: &[[f64; 3]]| match x.len() {
        4 => vec![[x[0], x[1], x[2]], [x[0], x[2], x[3]]],
        _ => vec![[x[0], x[1], x[2]]],
    };
    let apart = |a: &[[f64; 3]], b: &[[f64; 3]]| {
        let tb = triangles(b);
        (a.iter())
            .flat_map(|p| tb.iter().map(move |t| to_triangle(p, t)))
            .fold(f64::INFINITY, f64::min)
    };
    apart(xs, xm).min(apart(xm, xs)) < size
}

/// The slots of the slave surface: each node with its faces, and each node's slot.
#[allow(clippy::type_complexity)]
fn slots_of(slave: &FaceSurface) -> (Vec<(usize, Vec<usize>)>, HashMap<usize, usize>) {
    let mut slots: Vec<(usize, Vec<usize>)> = Vec::new();
    let mut slot_of = HashMap::new();
    for (k, f) in slave.faces.iter().enumerate() {
        for &n in &f.nodes {
            let j = *slot_of.entry(n).or_insert_with(|| {
                slots.push((n, Vec::new()));
                slots.len() - 1
            });
            slots[j].1.push(k);
        }
    }
    (slots, slot_of)
}

/// Every slot's full support (`MortarLaw::full_support`): ∫ N_j over its flat faces (their
/// areas over their corner counts, `size` their √area), ∫ N̂_j over curved ones.
fn full_supports(
    model: &Model,
    slave: &FaceSurface,
    slots: &[(usize, Vec<usize>)],
    size: &[f64],
) -> Vec<f64> {
    let reference = |n: usize| model.nodes[n].coords;
    let curved_supports: Vec<Option<Vec<f64>>> = slave
        .faces
        .iter()
        .map(|f| {
            is_quadratic(f).then(|| {
                let x: Vec<[f64; 3]> = f.nodes.iter().map(|&n| reference(n)).collect();
                curved::supports(f.kind, &x)
            })
        })
        .collect();
    slots
        .iter()
        .map(|(node, faces)| {
            faces
                .iter()
                .map(|&k| match &curved_supports[k] {
                    Some(s) => s[slave.faces[k].nodes.iter().position(|n| n == node).unwrap()],
                    None => size[k].powi(2) / slave.faces[k].nodes.len() as f64,
                })
                .sum()
        })
        .collect()
}

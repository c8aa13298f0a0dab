//! A node against a face of a 3D master surface (see [`crate::contact::geometry::faces`]).
//!
//! Unknowns: the node and the face's nodes (its corners, and a quadratic face's mid-sides), and
//! in large deformation the nodes of every face around them (the current nodal normals average
//! those faces' normals). The kinematics are evaluated in duals over the node, the face's nodes
//! and their nodal normals (at most 27 numbers on a linear face, 51 on an 8-node one); each
//! nodal normal carries its own derivatives with respect to the nodes around it
//! ([`NodalNormal`]), and the chain rule takes the result to the local unknowns ([`Jet::chain`]).
//! So a pair never differentiates with respect to more variables than that, whatever the
//! valence of the mesh. On a quadratic face the contact point is the curved face's: the ray
//! along ñ meets the face's quadratic map, found by Newton.

use super::ISOLATED_RAMP;
use super::{extents, Current, EndWeight, NodeToSegment, Slot, HYSTERESIS_BAND, INSIDE_TOL};
use crate::contact::dual::{self, Dual, Jet};
use crate::contact::formulation::{Anchor, Ctx, Local, Partner};
use crate::contact::geometry::faces::{edge_excess, FaceGeometry, NodalNormal};
use crate::contact::geometry::scalar::Scalar;
use crate::contact::law::SlotKinematics;
use crate::contact::search::Candidate;
use crate::error::Result;
use crate::model::Model;

impl NodeToSegment {
    /// Whether the nodal normals of face `k` follow the deformation (large deformation, no
    /// prescribed normal).
    fn moving_normals(&self, k: usize) -> bool {
        self.faces.faces[k].nlgeo && self.normal.is_none()
    }

    /// Nodal normals of face `k` at the current state: prescribed, reference (small deformation)
    /// or current (large deformation).
    fn face_normals(&self, k: usize, cur: &Current) -> Vec<[f64; 3]> {
        let face = &self.faces.faces[k];
        face.nodes
            .iter()
            .map(|&a| match self.normal {
                Some(n) => n,
                None if face.nlgeo => cur.normals[&a].n,
                None => self.faces.reference_normal(a),
            })
            .collect()
    }

    pub(super) fn face_geometry_f64(&self, k: usize, cur: &Current) -> FaceGeometry<f64> {
        let face = &self.faces.faces[k];
        FaceGeometry {
            kind: face.kind,
            x: face.nodes.iter().map(|n| cur.x[n]).collect(),
            n: self.face_normals(k, cur),
        }
    }

    /// Tributary extents (behind, ahead) of a slot's node across open edge `e` of face `k`, from
    /// the reference configuration.
    fn face_ramp(&self, model: &Model, slot: &Slot, k: usize, e: usize) -> (f64, f64) {
        let face = &self.faces.faces[k];
        let x: Vec<[f64; 3]> = face.nodes.iter().map(|&n| model.nodes[n].coords).collect();
        let (p, q) = (x[e], x[(e + 1) % face.kind.corners()]);
        let len = (0..3).map(|i| (q[i] - p[i]).powi(2)).sum::<f64>().sqrt();
        let geom = FaceGeometry {
            kind: face.kind,
            n: x.clone(),
            x,
        };
        let (out, _) = geom.edge_outward(e);
        extents(
            slot,
            model.nodes[slot.node].coords,
            out,
            ISOLATED_RAMP * len,
        )
    }

    /// Boundary weight of a node at `xs` against face `k`: 1 unless the face has an open edge it
    /// nears (a product over its open edges).
    fn face_weight<T: Scalar>(
        &self,
        model: &Model,
        slot: &Slot,
        k: usize,
        geom: &FaceGeometry<T>,
        xs: &[T; 3],
    ) -> EndWeight<T> {
        let face = &self.faces.faces[k];
        let mut w = EndWeight::new(xs[0].cst(1.0));
        for e in 0..face.kind.corners() {
            if face.open[e] {
                w.boundary(geom.past_edge(xs, e), self.face_ramp(model, slot, k, e));
            }
        }
        w
    }

    /// Face `k` as a partner of a node at `xs`, if the node projects on it (or within the band
    /// that keeps a previous partner, or past an open edge within its ramp).
    pub(super) fn face_candidate(
        &self,
        model: &Model,
        slot: &Slot,
        xs: [f64; 3],
        cur: &Current,
        k: usize,
    ) -> Option<Candidate> {
        let face = &self.faces.faces[k];
        let geom = self.face_geometry_f64(k, cur);
        let (xi, eta) = geom.project(xs)?;
        let excess = edge_excess(face.kind, xi, eta);
        let (mut past_open, mut past_shared) = (false, f64::NEG_INFINITY);
        for (e, &d) in excess.iter().take(face.kind.corners()).enumerate() {
            if face.open[e] {
                past_open |= d > INSIDE_TOL;
            } else {
                past_shared = past_shared.max(d);
            }
        }
        // Past a shared edge, the neighbouring face is the surface (but a previous partner is
        // kept within the band); past an open edge, the node counts while its weight does.
        if past_shared > HYSTERESIS_BAND
            || (past_open
                && !self
                    .face_weight(model, slot, k, &geom, &xs)
                    .counts(self.multipliers(slot)))
        {
            return None;
        }
        let (gap, _) = geom.gap(&xs, xi, eta);
        Some(Candidate {
            partner: Partner::Face(k),
            xi: [xi, eta],
            gap,
            inside: past_shared <= INSIDE_TOL,
        })
    }

    /// Kinematics against face `k` with the contact point converged at `xi0`, with the friction
    /// of a node anchored at `anchor`, `held` its friction force (the next anchor is returned).
    pub(super) fn face_kinematics(
        &self,
        ctx: &Ctx,
        slot: &Slot,
        k: usize,
        xi0: [f64; 2],
        cur: &Current,
        (anchor, held): (Option<&Anchor>, [f64; 3]),
    ) -> Result<(Local, SlotKinematics, Option<Anchor>)> {
        let face = &self.faces.faces[k];
        let nc = face.nodes.len();
        let moving = self.moving_normals(k);
        let friction_law = slot.friction;
        let anchor_face = anchor
            .filter(|_| friction_law.is_some())
            .and_then(|a| match a.partner {
                Partner::Face(ka) => Some((ka, a.xi)),
                _ => None,
            });
        let normals: Vec<&NodalNormal> = if moving {
            face.nodes.iter().map(|a| &cur.normals[a]).collect()
        } else {
            Vec::new()
        };
        let local = self.face_local(ctx, slot, k, anchor_face.map(|a| a.0), &normals)?;
        let m = local.m();
        // Dual variables z: the node and corner positions (the first local unknowns), then the
        // corners' nodal normals when they move.
        let npos = 3 * (1 + nc);
        // Anchor corners that are not corners of face k get variables of their own.
        let extra: Vec<usize> = anchor_face
            .map(|(ka, _)| {
                self.faces.faces[ka]
                    .nodes
                    .iter()
                    .copied()
                    .filter(|n| !face.nodes.contains(n))
                    .collect()
            })
            .unwrap_or_default();
        let (z, zanchor, geom) =
            self.dual_face(ctx, (slot, k), cur, &local, (npos, &normals, &extra))?;
        let nz = z.len();
        let xs = [z[0], z[1], z[2]];
        let jac = self
            .face_geometry_f64(k, cur)
            .jacobian(cur_point(&local), xi0[0], xi0[1]);
        let [xi, eta] = geom.project_dual(&xs, xi0, jac);
        let (gap, nh) = geom.gap(&xs, xi, eta);
        let dir = match self.normal {
            Some(v) => v.map(|c| Dual::constant(c, nz)),
            None => nh,
        };
        let c = geom.coefficients(xi, eta);
        let mut b: Vec<Dual> = dir.to_vec();
        for ca in c.iter().take(nc) {
            b.extend(dir.iter().map(|&d| -(*ca * d)));
        }
        let end = self.face_weight(ctx.model, slot, k, &geom, &xs);
        let dz = dual_map(&local, npos, &normals, &extra);
        let chain = |x: &Dual| Jet::chain(x, &dz, m);
        let mut bj: Vec<Jet> = b.iter().map(chain).collect();
        bj.resize(m, Jet::constant(0.0, m));
        let mut kin = SlotKinematics {
            gap: chain(&gap),
            weight: chain(&end.w),
            b: bj,
            area: crate::contact::formulation::law_area(slot.area, ctx.model),
            past_end: end.past.as_ref().map(|(e, _)| chain(e)),
            slip: None,
        };
        let mut next = None;
        if let Some(law) = friction_law {
            let at_point = Anchor {
                partner: Partner::Face(k),
                xi: [xi.v, eta.v],
                offset: [0.0; 3],
            };
            next = Some(at_point);
            if let Some((ka, xia)) = anchor_face {
                let xa = self.anchor_point(k, (ka, xia), &z, (&extra, zanchor));
                next = Some(self.point_friction(
                    slot,
                    law,
                    [xs, xa, dir],
                    (anchor.expect("an anchor"), at_point),
                    held,
                    |p| {
                        self.face_geometry_f64(k, cur)
                            .project(p)
                            .map_or(at_point, |(a, b)| Anchor {
                                xi: [a, b],
                                ..at_point
                            })
                    },
                    // Distributed like the normal force: the node, and −c_a on the face's
                    // corners.
                    |v| {
                        let mut r: Vec<Dual> = v.to_vec();
                        for ca in c.iter().take(nc) {
                            r.extend(v.iter().map(|&d| -(*ca * d)));
                        }
                        let mut residual: Vec<Jet> = r.iter().map(chain).collect();
                        residual.resize(m, Jet::constant(0.0, m));
                        residual
                    },
                    chain,
                    &mut kin,
                ));
            }
        }
        Ok((local, kin, next))
    }

    /// A node's pair with face `k` in dual variables z (see [`dual_values`]): z, where the
    /// anchor's own corners begin in it, and the face's geometry in them (its nodal normals
    /// moving with their corners in large deformation, else fixed).
    #[allow(clippy::type_complexity)]
    fn dual_face(
        &self,
        ctx: &Ctx,
        (slot, k): (&Slot, usize),
        cur: &Current,
        local: &Local,
        (npos, normals, extra): (usize, &[&NodalNormal], &[usize]),
    ) -> Result<(Vec<Dual>, usize, FaceGeometry<Dual>)> {
        let face = &self.faces.faces[k];
        let nc = face.nodes.len();
        let (zvals, zanchor) = dual_values(local, npos, normals, extra);
        let nz = zvals.len();
        if nz > dual::MAXV {
            return Err(crate::error::Error::Solve(format!(
                "contact node {} with friction: {nz} variables for one pair, at most {}",
                ctx.model.nodes[slot.node].label,
                dual::MAXV
            )));
        }
        let z = dual::seed(&zvals, nz);
        let v3 = |i: usize| [z[3 * i], z[3 * i + 1], z[3 * i + 2]];
        let x: Vec<[Dual; 3]> = (1..=nc).map(v3).collect();
        let n: Vec<[Dual; 3]> = if !normals.is_empty() {
            (1..=nc).map(|a| v3(nc + a)).collect()
        } else {
            self.face_normals(k, cur)
                .iter()
                .map(|v| v.map(|c| Dual::constant(c, nz)))
                .collect()
        };
        let geom = FaceGeometry {
            kind: face.kind,
            x,
            n,
        };
        Ok((z, zanchor, geom))
    }

    /// The local unknowns of a node against face `k`: the node, the face's corners, those of
    /// the face `anchor` its friction is anchored to (it moves the anchor), and the nodes the
    /// corners' moving `normals` depend on.
    fn face_local(
        &self,
        ctx: &Ctx,
        slot: &Slot,
        k: usize,
        anchor: Option<usize>,
        normals: &[&NodalNormal],
    ) -> Result<Local> {
        let mut local = Local::new(3);
        local.add(ctx, slot.node)?;
        for &n in &self.faces.faces[k].nodes {
            local.add(ctx, n)?;
        }
        if let Some(ka) = anchor {
            for &n in &self.faces.faces[ka].nodes {
                local.add(ctx, n)?;
            }
        }
        for nn in normals {
            for &(b, _) in &nn.jac {
                local.add(ctx, b)?;
            }
        }
        Ok(local)
    }

    /// The anchor's material point (partner face `ka` at `xia`) in the dual variables `z` of
    /// face `k`'s kinematics: a corner shared with face `k` takes that corner's variables, any
    /// other (in `extra`) its own from `zanchor` on.
    fn anchor_point(
        &self,
        k: usize,
        (ka, xia): (usize, [f64; 2]),
        z: &[Dual],
        (extra, zanchor): (&[usize], usize),
    ) -> [Dual; 3] {
        let (face, fa) = (&self.faces.faces[k], &self.faces.faces[ka]);
        let nz = z.len();
        let ya: Vec<[Dual; 3]> = fa
            .nodes
            .iter()
            .map(|n| {
                let first = match face.nodes.iter().position(|m| m == n) {
                    Some(a) => 3 * (1 + a),
                    None => {
                        let e = extra.iter().position(|m| m == n).expect("an extra corner");
                        zanchor + 3 * e
                    }
                };
                std::array::from_fn(|i| z[first + i])
            })
            .collect();
        let ga = FaceGeometry {
            kind: fa.kind,
            n: ya.clone(),
            x: ya,
        };
        let ca = ga.coefficients(Dual::constant(xia[0], nz), Dual::constant(xia[1], nz));
        let mut xa = [Dual::constant(0.0, nz); 3];
        for (a, y) in ga.x.iter().enumerate() {
            for i in 0..3 {
                xa[i] = xa[i] + ca[a] * y[i];
            }
        }
        xa
    }
}

/// The current position of the first local node (the contact node).
fn cur_point(local: &Local) -> [f64; 3] {
    let v = local.values();
    [v[0], v[1], v[2]]
}

/// ∂z/∂q of a face pair's dual variables z over its local unknowns q: the identity on the first
/// `npos` (the node's and the corners' positions), the moving corners' nodal normals'
/// derivatives after them, then the identity on the anchor's `extra` corners.
fn dual_map(
    local: &Local,
    npos: usize,
    normals: &[&NodalNormal],
    extra: &[usize],
) -> Vec<Vec<(usize, f64)>> {
    let mut dz: Vec<Vec<(usize, f64)>> = (0..npos).map(|i| vec![(i, 1.0)]).collect();
    for nn in normals {
        for i in 0..3 {
            let mut row = Vec::with_capacity(3 * nn.jac.len());
            for (node, d) in &nn.jac {
                let base = 3 * local.index(*node);
                row.extend((0..3).map(|j| (base + j, d[i][j])));
            }
            dz.push(row);
        }
    }
    for &n in extra {
        let base = 3 * local.index(n);
        dz.extend((0..3).map(|j| vec![(base + j, 1.0)]));
    }
    dz
}

/// The values of a face pair's dual variables z (see [`dual_map`]): the positions, the moving
/// corners' nodal normals, the anchor's `extra` corners; and where the last begin.
fn dual_values(
    local: &Local,
    npos: usize,
    normals: &[&NodalNormal],
    extra: &[usize],
) -> (Vec<f64>, usize) {
    let mut zvals = local.values()[..npos].to_vec();
    for nn in normals {
        zvals.extend_from_slice(&nn.n);
    }
    let zanchor = zvals.len();
    for &n in extra {
        let i = 3 * local.index(n);
        zvals.extend_from_slice(&local.values()[i..i + 3]);
    }
    (zvals, zanchor)
}

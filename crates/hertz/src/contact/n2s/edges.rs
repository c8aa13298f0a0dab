//! A node against an edge of a 2D master surface (see [`crate::contact::geometry::edges`]).

use super::{
    extents, Current, EndWeight, NodeToSegment, Slot, HYSTERESIS_BAND, INSIDE_TOL, ISOLATED_RAMP,
};
use crate::contact::dual::{self, DVec, Dual};
use crate::contact::formulation::{Anchor, Ctx, Local, Partner};
use crate::contact::geometry::edges::{edge_normal, EdgeGeometry, EdgeSurface};
use crate::contact::geometry::scalar::Scalar;
use crate::contact::law::SlotKinematics;
use crate::contact::search::Candidate;
use crate::error::{Error, Result};
use crate::model::Model;

/// The unknowns of a pair — the node and the edge's support (with the edges meeting it at its
/// ends in large deformation, whose normals are averaged) — must fit the duals.
pub(super) fn check_support(model: &Model, surface: &EdgeSurface) -> Result<()> {
    for (k, e) in surface.edges.iter().enumerate() {
        let m = 2 * (1 + surface.support(k).len());
        if m > dual::MAXV {
            return Err(Error::Input {
                span: model.segments[e.segment].span.clone(),
                msg: format!(
                    "the edge of element {} meets too many other edges of the contact surface \
                     at its ends ({m} unknowns for one contact pair, at most {})",
                    model.elements[e.element].label,
                    dual::MAXV
                ),
            });
        }
    }
    Ok(())
}

impl NodeToSegment {
    /// Nodal normals of edge `k` in the mode of its element, from positions `pos(e, i)` of node i
    /// of edge e (current ones matter only in large deformation).
    fn edge_normals<T: Scalar>(
        &self,
        k: usize,
        x: &[[T; 2]],
        pos: &dyn Fn(usize, usize) -> [T; 2],
    ) -> Vec<[T; 2]> {
        let edge = &self.edges.edges[k];
        let z = x[0][0];
        if let Some(n) = self.normal {
            return vec![[z.cst(n[0]), z.cst(n[1])]; x.len()];
        }
        edge.nodes
            .iter()
            .enumerate()
            .map(|(i, &a)| {
                if !edge.nlgeo {
                    let n = self.edges.reference_normal(a);
                    [z.cst(n[0]), z.cst(n[1])]
                } else if i == 2 {
                    edge_normal(x, edge.side, z.cst(0.5))
                } else {
                    self.edges.nodal_normal(k, a, pos)
                }
            })
            .collect()
    }

    /// Whether the surface is open beyond each end of edge `k`.
    pub(super) fn open_ends(&self, k: usize) -> [bool; 2] {
        let edge = &self.edges.edges[k];
        [
            self.edges.is_open_end(edge.nodes[0]),
            self.edges.is_open_end(edge.nodes[1]),
        ]
    }

    pub(super) fn edge_geometry_f64(&self, k: usize, cur: &Current) -> EdgeGeometry<f64> {
        let xy = |n: &usize| {
            let p = cur.x[n];
            [p[0], p[1]]
        };
        let x: Vec<[f64; 2]> = self.edges.edges[k].nodes.iter().map(xy).collect();
        let pos = |e: usize, i: usize| xy(&self.edges.edges[e].nodes[i]);
        EdgeGeometry {
            n: self.edge_normals(k, &x, &pos),
            x,
            open: self.open_ends(k),
        }
    }

    /// Tributary extents (behind, ahead) of a slot's node along the outward direction of end `e`
    /// of edge `k`, from the reference configuration.
    fn edge_ramp(&self, model: &Model, slot: &Slot, k: usize, e: usize) -> (f64, f64) {
        let x: Vec<[f64; 2]> = self.edges.edges[k]
            .nodes
            .iter()
            .map(|&n| {
                let c = model.nodes[n].coords;
                [c[0], c[1]]
            })
            .collect();
        let geom = EdgeGeometry {
            n: x.clone(),
            x,
            open: [false; 2],
        };
        let (out, _) = geom.end_direction(e);
        let (x0, x1) = (geom.x[0], geom.x[1]);
        let isolated = ISOLATED_RAMP * ((x1[0] - x0[0]).powi(2) + (x1[1] - x0[1]).powi(2)).sqrt();
        if self.covered.contains(&self.edges.edges[k].nodes[e]) {
            return (isolated, 0.0);
        }
        extents(
            slot,
            model.nodes[slot.node].coords,
            [out[0], out[1], 0.0],
            isolated,
        )
    }

    /// End weight of a node at `xs` against edge `k`: 1 unless the edge has an open end it nears.
    fn edge_weight<T: Scalar>(
        &self,
        model: &Model,
        slot: &Slot,
        k: usize,
        geom: &EdgeGeometry<T>,
        xs: [T; 2],
    ) -> EndWeight<T> {
        let mut w = EndWeight::new(xs[0].cst(1.0));
        for e in 0..2 {
            if !geom.open[e] {
                continue;
            }
            let (out, xe) = geom.end_direction(e);
            let d = (xs[0] - xe[0]) * out[0] + (xs[1] - xe[1]) * out[1];
            w.boundary(d, self.edge_ramp(model, slot, k, e));
        }
        w
    }

    /// Edge `k` as a partner of a node at `xs`, if the node projects on it (or within the band
    /// that keeps a previous partner, or past an open end within its ramp).
    pub(super) fn edge_candidate(
        &self,
        model: &Model,
        slot: &Slot,
        xs: [f64; 3],
        cur: &Current,
        k: usize,
    ) -> Option<Candidate> {
        let xs2 = [xs[0], xs[1]];
        let geom = self.edge_geometry_f64(k, cur);
        let s = geom.project(xs2)?;
        let past_open = (s < 0.0 && geom.open[0]) || (s > 1.0 && geom.open[1]);
        let inside = if past_open {
            self.edge_weight(model, slot, k, &geom, xs2)
                .counts(self.multipliers(slot))
        } else {
            (-INSIDE_TOL..=1.0 + INSIDE_TOL).contains(&s)
        };
        if !inside && (past_open || !(-HYSTERESIS_BAND..=1.0 + HYSTERESIS_BAND).contains(&s)) {
            return None;
        }
        let (gap, _) = geom.gap(xs2, s);
        Some(Candidate {
            partner: Partner::Edge(k),
            xi: [s, 0.0],
            gap,
            inside,
        })
    }

    /// Kinematics against edge `k` with the contact point converged at `s0`, with the friction
    /// of a node anchored at `anchor`, `held` its friction force (the next anchor is returned).
    pub(super) fn edge_kinematics(
        &self,
        ctx: &Ctx,
        slot: &Slot,
        k: usize,
        s0: f64,
        (anchor, held): (Option<&Anchor>, [f64; 3]),
    ) -> Result<(Local, SlotKinematics, Option<Anchor>)> {
        let edge = &self.edges.edges[k];
        let mut local = Local::new(2);
        local.add(ctx, slot.node)?;
        for n in self.edges.support(k) {
            local.add(ctx, n)?;
        }
        // The anchor's edge moves the anchor: its nodes are unknowns of the pair too.
        let anchor_edge = anchor.and_then(|a| match a.partner {
            Partner::Edge(ka) => Some((ka, a.xi[0])),
            _ => None,
        });
        if let Some((ka, _)) = anchor_edge {
            for &n in &self.edges.edges[ka].nodes {
                local.add(ctx, n)?;
            }
        }
        let q = local.seed();
        let xy = |n: usize| {
            let v = q[local.index(n)];
            [v[0], v[1]]
        };
        let x: Vec<[Dual; 2]> = edge.nodes.iter().map(|&n| xy(n)).collect();
        let pos = |e: usize, i: usize| xy(self.edges.edges[e].nodes[i]);
        let geom = EdgeGeometry {
            n: self.edge_normals(k, &x, &pos),
            x,
            open: self.open_ends(k),
        };
        let xs = [q[0][0], q[0][1]];
        let s = geom.project_dual(xs, s0);
        let (gap, nh) = geom.gap(xs, s);
        let m = local.m();
        let dir: DVec = match self.normal {
            Some(n) => dual::constant_vec(&n[..2], m),
            None => [nh[0], nh[1], Dual::constant(0.0, m)],
        };
        let (c, _, _) = geom.coefficients(s);
        let mut coeffs = vec![(0, Dual::constant(1.0, m))];
        for (a, &n) in edge.nodes.iter().enumerate() {
            coeffs.push((local.index(n), -c[a]));
        }
        let b = local.distribute(&coeffs, &dir);
        let end = self.edge_weight(ctx.model, slot, k, &geom, xs);
        let area = crate::contact::formulation::law_area(slot.area, ctx.model);
        let mut kin = SlotKinematics::from_duals(gap, end.w, &b, area);
        kin.past_end = end.past.map(|(e, _)| e.into());
        let mut next = None;
        if let Some(law) = slot.friction {
            let xs3 = [xs[0], xs[1], Dual::constant(0.0, m)];
            // Anchor: its material point on its edge; none yet: the contact point (no force).
            let xa3 = match anchor_edge {
                Some((ka, sa)) => {
                    let xa: Vec<[Dual; 2]> =
                        self.edges.edges[ka].nodes.iter().map(|&n| xy(n)).collect();
                    let ga = EdgeGeometry {
                        n: xa.clone(),
                        x: xa,
                        open: self.open_ends(ka),
                    };
                    let (c, _, _) = ga.coefficients(Dual::constant(sa, m));
                    let mut p = [Dual::constant(0.0, m); 3];
                    for (a, &n) in self.edges.edges[ka].nodes.iter().enumerate() {
                        let x = xy(n);
                        p[0] = p[0] + c[a] * x[0];
                        p[1] = p[1] + c[a] * x[1];
                    }
                    Some(p)
                }
                None => None,
            };
            let at_point = Anchor {
                partner: Partner::Edge(k),
                xi: [s.v, 0.0],
                offset: [0.0; 3],
            };
            next = Some(at_point);
            if let (Some(xa3), Some(anchor)) = (xa3, anchor) {
                let geom_f = EdgeGeometry {
                    n: geom.n.iter().map(|v| [v[0].v, v[1].v]).collect(),
                    x: geom.x.iter().map(|v| [v[0].v, v[1].v]).collect(),
                    open: geom.open,
                };
                next = Some(self.point_friction(
                    slot,
                    law,
                    [xs3, xa3, dir],
                    (anchor, at_point),
                    held,
                    |p| {
                        geom_f.project([p[0], p[1]]).map_or(at_point, |sa| Anchor {
                            xi: [sa, 0.0],
                            ..at_point
                        })
                    },
                    |v| local.distribute_jets(&coeffs, v),
                    |&d| d.into(),
                    &mut kin,
                ));
            }
        }
        Ok((local, kin, next))
    }
}

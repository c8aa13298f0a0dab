//! A node against a rigid analytical segment (see [`crate::contact::geometry::rigid`]).

use super::{NodeToSegment, Slot};
use crate::contact::dual::{self, DVec, Dual};
use crate::contact::formulation::{Anchor, Ctx, Local, Partner};
use crate::contact::geometry::rigid;
use crate::contact::geometry::scalar::Scalar;
use crate::contact::law::SlotKinematics;
use crate::contact::search::Candidate;
use crate::error::Result;
use crate::model::{Model, SegmentKind};

impl NodeToSegment {
    /// Origin of a rigid segment: its reference point moved with its node, if any.
    fn rigid_origin<T: Scalar>(
        &self,
        model: &Model,
        p: [f64; 3],
        node: Option<usize>,
        x_node: Option<&[T]>,
        like: T,
    ) -> Vec<T> {
        (0..self.dim)
            .map(|i| match (node, x_node) {
                (Some(n), Some(x)) => x[i] + (p[i] - model.nodes[n].coords[i]),
                _ => like.cst(p[i]),
            })
            .collect()
    }

    /// The rigid partners of a node at `xs` (each is a candidate wherever the node is).
    pub(super) fn rigid_candidates(
        &self,
        ctx: &Ctx,
        xs: [f64; 3],
        out: &mut Vec<Candidate>,
    ) -> Result<()> {
        let model = ctx.model;
        let xv = &xs[..self.dim];
        for &seg in &self.rigid {
            let (gap, xi) = match &model.segments[seg].kind {
                SegmentKind::Circle {
                    center,
                    radius,
                    node,
                    cavity,
                } => {
                    let xn = node.map(|n| ctx.position(n)).transpose()?.map(|p| p.0);
                    let c =
                        self.rigid_origin(model, *center, *node, xn.as_ref().map(|x| &x[..]), 0.0);
                    let r: f64 = xv
                        .iter()
                        .zip(&c)
                        .map(|(a, b)| (a - b).powi(2))
                        .sum::<f64>()
                        .sqrt();
                    if !(r > 0.0) {
                        continue;
                    }
                    (rigid::circle(xv, &c, *radius, *cavity).0, 0.0)
                }
                SegmentKind::Plane {
                    point,
                    normal,
                    node,
                } => {
                    let xn = node.map(|n| ctx.position(n)).transpose()?.map(|p| p.0);
                    let p =
                        self.rigid_origin(model, *point, *node, xn.as_ref().map(|x| &x[..]), 0.0);
                    (rigid::plane(xv, &p, &normal[..self.dim]).0, 0.0)
                }
                SegmentKind::Polynomial { coeffs, body_above } => {
                    let Some(t) = rigid::project_on_poly(coeffs, [xs[0], xs[1]]) else {
                        continue;
                    };
                    (rigid::polynomial(coeffs, xv, t, *body_above).0, t)
                }
                SegmentKind::Edges { .. } | SegmentKind::Faces { .. } => {
                    unreachable!("rigid segments only")
                }
            };
            out.push(Candidate {
                partner: Partner::Rigid(seg),
                xi: [xi, 0.0],
                gap,
                inside: true,
            });
        }
        Ok(())
    }

    /// The contact parameter of a kept rigid partner at `xs` (the polynomial's abscissa; the
    /// others have none).
    pub(super) fn rigid_reproject(&self, ctx: &Ctx, seg: usize, xs: [f64; 3]) -> Option<f64> {
        match &ctx.model.segments[seg].kind {
            SegmentKind::Polynomial { coeffs, .. } => {
                rigid::project_on_poly(coeffs, [xs[0], xs[1]])
            }
            _ => Some(0.0),
        }
    }

    /// The node a rigid segment moves with, and its reference point (origin of the anchors).
    fn rigid_frame(model: &Model, seg: usize) -> (Option<usize>, [f64; 3]) {
        match &model.segments[seg].kind {
            SegmentKind::Circle { node, center, .. } => (*node, *center),
            SegmentKind::Plane { node, point, .. } => (*node, *point),
            _ => (None, [0.0; 3]),
        }
    }

    /// Kinematics against rigid segment `seg`, with the polynomial's contact abscissa `t0`, and
    /// the friction of a node anchored at `anchor`, `held` its friction force (the next anchor is returned).
    pub(super) fn rigid_kinematics(
        &self,
        ctx: &Ctx,
        slot: &Slot,
        seg: usize,
        t0: f64,
        (anchor, held): (Option<&Anchor>, [f64; 3]),
    ) -> Result<(Local, SlotKinematics, Option<Anchor>)> {
        let model = ctx.model;
        let dim = self.dim;
        let mut local = Local::new(dim);
        local.add(ctx, slot.node)?;
        let (node, _) = Self::rigid_frame(model, seg);
        if let Some(n) = node {
            local.add(ctx, n)?;
        }
        // The anchor moves with its segment's node.
        let anchor_frame = anchor.and_then(|a| match a.partner {
            Partner::Rigid(g) => Some((Self::rigid_frame(model, g), a.offset)),
            _ => None,
        });
        if let Some(((Some(n), _), _)) = anchor_frame {
            local.add(ctx, n)?;
        }
        let q = local.seed();
        let m = local.m();
        let xs = &q[0][..dim];
        let zero = Dual::constant(0.0, m);
        let xn = node.map(|_| &q[1][..dim]);
        let (gap, n) = match &model.segments[seg].kind {
            SegmentKind::Circle {
                center,
                radius,
                cavity,
                ..
            } => {
                let c = self.rigid_origin(model, *center, node, xn, zero);
                rigid::circle(xs, &c, *radius, *cavity)
            }
            SegmentKind::Plane { point, normal, .. } => {
                let p = self.rigid_origin(model, *point, node, xn, zero);
                rigid::plane(xs, &p, &normal[..dim])
            }
            SegmentKind::Polynomial { coeffs, body_above } => {
                rigid::polynomial(coeffs, xs, t0, *body_above)
            }
            SegmentKind::Edges { .. } | SegmentKind::Faces { .. } => {
                unreachable!("rigid segments only")
            }
        };
        let dir: DVec = match self.normal {
            Some(nf) => dual::constant_vec(&nf[..dim], m),
            None => {
                let mut v = [zero; 3];
                v[..dim].copy_from_slice(&n);
                v
            }
        };
        let mut coeffs = vec![(0, Dual::constant(1.0, m))];
        if let Some(n) = node {
            coeffs.push((local.index(n), Dual::constant(-1.0, m)));
        }
        let b = local.distribute(&coeffs, &dir);
        let area = crate::contact::formulation::law_area(slot.area, model);
        let mut kin = SlotKinematics::from_duals(gap, Dual::constant(1.0, m), &b, area);
        let mut next = None;
        if let Some(law) = slot.friction {
            // Anchors are points in the frame of their segment: its origin moved with its node.
            let origin = |g: usize, q: &[crate::contact::dual::DVec]| -> DVec {
                let (n, p) = Self::rigid_frame(model, g);
                let xn = n.map(|n| &q[local.index(n)][..dim]);
                let o = self.rigid_origin(model, p, n, xn, zero);
                let mut v = [zero; 3];
                v[..dim].copy_from_slice(&o);
                v
            };
            let mut xs3 = [zero; 3];
            xs3[..dim].copy_from_slice(xs);
            let here = origin(seg, &q);
            let at_point = Anchor {
                partner: Partner::Rigid(seg),
                xi: [0.0; 2],
                // The contact point: the node moved back along the normal by the gap.
                offset: std::array::from_fn(|i| {
                    if i < dim {
                        xs3[i].v - gap.v * dir[i].v - here[i].v
                    } else {
                        0.0
                    }
                }),
            };
            next = Some(at_point);
            if let (Some((_, offset)), Some(anchor)) = (anchor_frame, anchor) {
                let Partner::Rigid(g) = anchor.partner else {
                    unreachable!("a rigid anchor")
                };
                let o = origin(g, &q);
                let xa3: DVec = std::array::from_fn(|i| o[i] + offset[i]);
                next = Some(self.point_friction(
                    slot,
                    law,
                    [xs3, xa3, dir],
                    (anchor, at_point),
                    held,
                    |p| Anchor {
                        offset: std::array::from_fn(|i| p[i] - here[i].v),
                        ..at_point
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

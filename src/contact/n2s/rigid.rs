//! A node against a rigid analytical segment (see [`crate::contact::geometry::rigid`]).

use super::{NodeToSegment, Slot};
use crate::contact::dual::{self, DVec, Dual};
use crate::contact::geometry::rigid;
use crate::contact::geometry::scalar::Scalar;
use crate::contact::law::PointKinematics;
use crate::contact::search::Candidate;
use crate::contact::{Ctx, Local, Partner};
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

    /// Kinematics against rigid segment `seg`, with the polynomial's contact abscissa `t0`.
    pub(super) fn rigid_kinematics(
        &self,
        ctx: &Ctx,
        slot: &Slot,
        seg: usize,
        t0: f64,
    ) -> Result<(Local, PointKinematics)> {
        let model = ctx.model;
        let dim = self.dim;
        let mut local = Local::new(dim);
        local.add(ctx, slot.node)?;
        let node = match &model.segments[seg].kind {
            SegmentKind::Circle { node, .. } | SegmentKind::Plane { node, .. } => *node,
            _ => None,
        };
        if let Some(n) = node {
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
        if node.is_some() {
            coeffs.push((1, Dual::constant(-1.0, m)));
        }
        let b = local.distribute(&coeffs, &dir);
        let area = crate::contact::law_area(slot.area, model);
        Ok((
            local,
            PointKinematics::from_duals(gap, Dual::constant(1.0, m), &b, area),
        ))
    }
}

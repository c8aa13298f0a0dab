//! Warnings about the initial configuration: contact nodes that start inside a rigid segment or
//! deep inside a deformable master.

use super::formulation::{Partner, SlotState};
use crate::model::queries::model_size;
use crate::model::{Model, SegmentKind};

/// Warnings about the initial configuration, from the contact states at u = 0: nodes that start
/// inside a rigid segment's body (they are pushed out: a rigid segment's side is fixed by its
/// definition, not by where a node starts, as it is in OOFEM).
pub fn initial_warnings(model: &Model, states: &[SlotState]) -> Vec<String> {
    use std::collections::BTreeMap;
    let tol = 1e-9 * model_size(model);
    let mut inside: BTreeMap<(usize, usize), (usize, f64)> = BTreeMap::new();
    for s in states {
        if let Partner::Rigid(g) = s.partner {
            // The node's own distance to the shape, not the state's gap: a mortar slot's is a
            // weighted mean over its faces, which the dual basis can make negative where a
            // convex tool first touches the surface without any node inside it.
            let gap = rigid_distance(model, g, s.x).unwrap_or(s.gap);
            if gap < -tol {
                let e = inside.entry((s.condition, g)).or_insert((0, 0.0));
                e.0 += 1;
                e.1 = e.1.max(-gap);
            }
        }
    }
    let mut out: Vec<String> = deep_starts(model, states);
    out.extend(inside
        .into_iter()
        .map(|((cond, g), (n, depth))| {
            let seg = &model.segments[g];
            let hint = match seg.kind {
                SegmentKind::Circle { cavity: false, .. } => " (if they belong inside the circle, add `cavity`)",
                SegmentKind::Polynomial { body_above: false, .. } => " (if the body is above the curve, add `bodyabove`)",
                SegmentKind::Plane { .. } => " (the plane's normal points out of the rigid body)",
                _ => "",
            };
            format!(
                "{n} node(s) of contact condition {cond} start inside rigid segment {} (by up to {depth:.3e}) and will be pushed out{hint}",
                seg.number
            )
        }));
    out
}

/// Warnings for contact nodes that start inside a deformable master by more than half the size
/// of their own elements: not a faceting overlap of curved surfaces but bodies placed into each
/// other, which the first step pushes apart with forces far above the load's.
fn deep_starts(model: &Model, states: &[SlotState]) -> Vec<String> {
    use std::collections::BTreeMap;
    let deep: Vec<&SlotState> = states
        .iter()
        .filter(|s| matches!(s.partner, Partner::Edge(_) | Partner::Face(_)) && s.gap < 0.0)
        .collect();
    if deep.is_empty() {
        return Vec::new();
    }
    // Each node's shortest distance to a node of its own elements.
    let mut size: std::collections::HashMap<usize, f64> =
        deep.iter().map(|s| (s.node, f64::INFINITY)).collect();
    for el in &model.elements {
        for &n in &el.nodes {
            let Some(h) = size.get(&n).copied() else {
                continue;
            };
            let x = model.nodes[n].coords;
            let near = el
                .nodes
                .iter()
                .filter(|&&m| m != n)
                .map(|&m| {
                    let y = model.nodes[m].coords;
                    (0..3).map(|i| (y[i] - x[i]).powi(2)).sum::<f64>().sqrt()
                })
                .fold(h, f64::min);
            size.insert(n, near);
        }
    }
    // condition -> (count, depth, node of the deepest)
    let mut found: BTreeMap<usize, (usize, f64, usize)> = BTreeMap::new();
    for s in deep {
        let h = size[&s.node];
        if h.is_finite() && -s.gap > 0.5 * h {
            let e = found.entry(s.condition).or_insert((0, 0.0, s.node));
            e.0 += 1;
            if -s.gap > e.1 {
                (e.1, e.2) = (-s.gap, s.node);
            }
        }
    }
    found
        .into_iter()
        .map(|(cond, (n, depth, node))| {
            format!(
                "{n} node(s) of contact condition {cond} start inside their master surface by more \
                 than half their elements' size, up to {depth:.3e} (node {}): the first step pushes \
                 the bodies apart with forces far above the load's; move them apart (or check the \
                 mesh and which side is the master)",
                model.nodes[node].label
            )
        })
        .collect()
}

/// The signed distance of the point `x` to rigid segment `g` in its reference position (< 0:
/// inside its body), if `x` projects onto it.
fn rigid_distance(model: &Model, g: usize, x: [f64; 3]) -> Option<f64> {
    use super::geometry::rigid;
    let dim = model.domain.nsd();
    let x = &x[..dim];
    Some(match &model.segments[g].kind {
        SegmentKind::Circle {
            center,
            radius,
            cavity,
            ..
        } => rigid::circle(x, &center[..dim], *radius, *cavity).0,
        SegmentKind::Plane { point, normal, .. } => {
            rigid::plane(x, &point[..dim], &normal[..dim]).0
        }
        SegmentKind::Polynomial { coeffs, body_above } => {
            let t = rigid::project_on_poly(coeffs, [x[0], x[1]])?;
            rigid::polynomial(coeffs, x, t, *body_above).0
        }
        _ => return None,
    })
}

/// A warning for the active contact nodes that carry a force but stand for no length or area
/// on their surface (a mid-side node whose tributary edges are all excluded, a node of faces
/// left out): their pressure is undefined, NaN in the CSV and 0 in the VTU files, while their
/// force is in the reactions.
pub fn pressure_warning(model: &Model, states: &[SlotState]) -> Option<String> {
    let nodes: Vec<usize> = states
        .iter()
        .filter(|s| s.active && s.force != 0.0 && s.pressure.is_nan())
        .map(|s| model.nodes[s.node].label)
        .collect();
    let (first, more) = (nodes.iter().take(6), nodes.len().saturating_sub(6));
    (!nodes.is_empty()).then(|| {
        let list: Vec<String> = first.map(|n| n.to_string()).collect();
        let more = if more > 0 {
            format!(" and {more} more")
        } else {
            String::new()
        };
        format!(
            "contact node(s) {}{more} carry a contact force but stand for no length or area of \
             their surface (their tributary edges or faces are excluded): their pressure is \
             undefined (NaN in the contact CSV, 0 in the VTU files); their force is in the \
             reactions",
            list.join(", ")
        )
    })
}

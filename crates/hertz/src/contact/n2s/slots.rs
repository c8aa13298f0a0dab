//! The contact nodes of a node-to-segment condition: the checks a node must pass and what each
//! one carries (its tributary area and neighbours, its law and friction, the stiffness of the
//! elements under it).

use crate::contact::formulation::Partner;
use crate::contact::geometry::edges::EdgeSurface;
use crate::contact::geometry::faces::FaceSurface;
use crate::contact::law::{SlotFriction, SlotLaw};
use crate::error::{Error, Result};
use crate::model::queries::{master_young, model_size, stiffest_young};
use crate::model::{ContactCondition, Model, Pairing};

/// A contact node of the condition.
pub(super) struct Slot {
    pub(super) node: usize,
    pub(super) area: f64,
    /// Reference positions of the node's neighbours on its own surface.
    pub(super) neighbors: Vec<[f64; 3]>,
    /// Half the distance to the farthest neighbour: how far past an open boundary the node can
    /// still meet the master.
    pub(super) reach: f64,
    /// The condition's law at this node, its penalty resolved (given, times the node's weight in
    /// upstream OOFEM input, its number of slave elements; or from the mesh, times its tributary
    /// area).
    pub(super) law: SlotLaw,
    /// The condition's friction at this node.
    pub(super) friction: Option<SlotFriction>,
    /// E·A/h of the elements under the node with the master's E in series (E their Young's
    /// modulus, see [`crate::contact::friction_modulus`]; A its tributary area, h the distance to its
    /// neighbours): c_T of the friction multipliers.
    pub(super) stiffness: f64,
    /// Self-contact: the node lies on its condition's own master surface.
    pub(super) own: Option<OwnSurface>,
}

/// Where a self-contact node sits on its own master surface (see `NodeToSegment::admits`).
pub(super) struct OwnSurface {
    /// The master's edges or faces the node belongs to: its current normal averages theirs.
    /// Never the node's partners.
    pub(super) items: Vec<Partner>,
    /// Their immediate neighbours (the other items sharing a node with them): the node's
    /// partners only from in front, where the surface folds onto itself (a crease closing).
    pub(super) neighbours: Vec<Partner>,
    /// Its mean distance to its neighbours.
    pub(super) spacing: f64,
}

/// The master's edges and faces at each of their nodes (corners and mid-sides).
fn items_at_nodes(
    edges: &EdgeSurface,
    faces: &FaceSurface,
) -> std::collections::HashMap<usize, Vec<Partner>> {
    let mut at: std::collections::HashMap<usize, Vec<Partner>> = Default::default();
    for (k, e) in edges.edges.iter().enumerate() {
        for &n in &e.nodes {
            at.entry(n).or_default().push(Partner::Edge(k));
        }
    }
    for (k, f) in faces.faces.iter().enumerate() {
        for &n in &f.nodes {
            at.entry(n).or_default().push(Partner::Face(k));
        }
    }
    at
}

/// The node's own surface if it lies on the master (`at`: the items at each node, `h` its
/// mean distance to its neighbours).
fn own_surface(
    node: usize,
    at: &std::collections::HashMap<usize, Vec<Partner>>,
    edges: &EdgeSurface,
    faces: &FaceSurface,
    h: f64,
) -> Option<OwnSurface> {
    let items = at.get(&node)?.clone();
    let mut neighbours = Vec::new();
    for &item in &items {
        let nodes = match item {
            Partner::Edge(k) => &edges.edges[k].nodes,
            Partner::Face(k) => &faces.faces[k].nodes,
            _ => continue,
        };
        for n in nodes {
            for &other in &at[n] {
                if !items.contains(&other) && !neighbours.contains(&other) {
                    neighbours.push(other);
                }
            }
        }
    }
    Some(OwnSurface {
        items,
        neighbours,
        spacing: h,
    })
}

/// Every contact node of condition `c` once (a node on the condition's own master is in
/// self-contact, see [`OwnSurface`]), none the node of an 8-node
/// face (QSpace): under a uniform pressure an 8-node face's consistent nodal forces pull on its
/// corners (−1/12 of its area each), so a corner held to the master by a node-to-face
/// constraint would need tension: it opens and sinks in (a Hertz contact's every corner node
/// inside the contact zone opened).
pub(super) fn check_nodes(model: &Model, c: &ContactCondition, nodes: &[usize]) -> Result<()> {
    let err = |msg: String| Error::Input {
        span: c.span.clone(),
        msg,
    };
    let mut seen = std::collections::HashSet::new();
    for &n in nodes {
        let label = model.nodes[n].label;
        if !seen.insert(n) {
            return Err(err(format!("node {label} is listed twice in `nodeset`")));
        }
    }
    if let Some(f) = super::super::tributary::facets(model, nodes)
        .iter()
        .find(|f| f.nodes.len() == 8)
    {
        return Err(err(format!(
            "the contact nodes include the nodes of an 8-node face (of a QSpace element, \
             nodes {}): node-to-segment contact cannot hold its corners, which a uniform \
             pressure pulls on; use QTRSpace, LSpace or LTRSpace elements on the slave side, \
             or make the QSpace surface the master",
            f.nodes
                .iter()
                .map(|&n| model.nodes[n].label.to_string())
                .collect::<Vec<_>>()
                .join(" ")
        )));
    }
    Ok(())
}

/// The slots of condition `c`'s contact `nodes` against the master `segments`.
pub(super) fn slots(
    model: &Model,
    c: &ContactCondition,
    nodes: &[usize],
    segments: &[usize],
    (edges, faces): (&EdgeSurface, &FaceSurface),
) -> Vec<Slot> {
    let at = items_at_nodes(edges, faces);
    let tribs = super::super::tributary::tributaries(model, nodes);
    let young = stiffest_young(model);
    let stiffest = young.values().copied().fold(0.0, f64::max);
    let master = master_young(model, segments);
    nodes
        .iter()
        .zip(tribs)
        .enumerate()
        .map(|(k, (&node, t))| {
            let x = model.nodes[node].coords;
            let distance = |m: usize| {
                let y = model.nodes[m].coords;
                (0..3).map(|i| (y[i] - x[i]).powi(2)).sum::<f64>().sqrt()
            };
            let neighbors: Vec<[f64; 3]> = if c.tributary_ramp {
                t.neighbors.iter().map(|&m| model.nodes[m].coords).collect()
            } else {
                Vec::new()
            };
            let reach = neighbors
                .iter()
                .map(|y| 0.5 * (0..3).map(|i| (y[i] - x[i]).powi(2)).sum::<f64>().sqrt())
                .fold(0.0, f64::max);
            let h = if t.neighbors.is_empty() {
                0.1 * model_size(model)
            } else {
                t.neighbors.iter().map(|&m| distance(m)).sum::<f64>() / t.neighbors.len() as f64
            };
            // A node on no element (a rigid body's) gets the model's stiffest modulus.
            let e = young.get(&node).copied().unwrap_or(stiffest);
            let per_modulus = crate::contact::formulation::law_area(t.measure, model) / h;
            let weight = c.node_weights.as_ref().map_or(1.0, |w| w[k]);
            use super::super::law::penalty;
            let mesh = penalty::from_mesh(e, master, per_modulus, penalty::mesh_factor(model));
            let law = SlotLaw::resolve(c.enforcement, mesh, weight);
            let stiffness = crate::contact::formulation::friction_modulus(e, master) * per_modulus;
            Slot {
                node,
                area: t.measure,
                neighbors,
                reach,
                law,
                friction: c.friction.map(|f| law.friction(f, weight)),
                stiffness,
                own: own_surface(node, &at, edges, faces, h),
            }
        })
        .collect()
}

/// The contact nodes of the model's other node-to-segment conditions than `ci` (see
/// `NodeToSegment::covered`).
pub(super) fn covered(model: &Model, ci: usize) -> std::collections::HashSet<usize> {
    model
        .contacts
        .iter()
        .enumerate()
        .filter(|&(k, _)| k != ci)
        .filter_map(|(_, c)| match &c.pairing {
            Pairing::NodeToSegment { nodes, .. } => Some(nodes.iter().copied()),
            _ => None,
        })
        .flatten()
        .collect()
}

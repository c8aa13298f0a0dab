//! Contact records: segments (block `ncontactseg`) and conditions (in the BC block), resolved
//! against the sets once those are read.

use super::record::Record;
use crate::error::{Error, Result, Span};
use crate::model::{
    ContactCondition, ContactSegment, Element, Enforcement, Friction, Node, Pairing, PenaltySource,
    SegmentKind, Set,
};
use std::collections::{HashMap, HashSet};

/// Contact condition record keywords.
pub const CONDITION_KEYWORDS: [&str; 6] = [
    "n2npenaltycontact",
    "n2nlagrangianmultipliercontact",
    "n2spenaltycontact",
    "n2slagrangianmultipliercontact",
    "s2spenaltycontact",
    "s2slagrangianmultipliercontact",
];

/// Contact segment record keywords.
pub const SEGMENTS: [&str; 6] = [
    "linear2delementedgecontactsegment",
    "qelementedgecontactsegment",
    "linear3delementsurfacecontactsegment",
    "circlecontactsegment",
    "polynomialcontactsegment",
    "planecontactsegment",
];

/// A segment whose edge set is not resolved yet.
pub struct PendingSegment {
    number: usize,
    kind: Option<SegmentKind>,
    /// The set of element boundaries, and whether they are faces (3D) rather than edges.
    boundary_set: Option<(usize, bool)>,
    span: Span,
}

/// A condition whose sets are not resolved yet.
pub struct PendingCondition {
    number: usize,
    enforcement: Enforcement,
    friction: Option<Friction>,
    sets: Option<(usize, usize)>,
    nodes: Vec<usize>,
    /// hertz's `slaveset k` on a node-to-segment condition: the contact nodes are set k's.
    node_set: Option<usize>,
    /// Mortar (`s2s...`): the slave segment.
    slave_segment: Option<usize>,
    segments: Vec<usize>,
    normal: Option<[f64; 3]>,
    span: Span,
}

fn node_ref(r: &Record, nodes: &HashMap<usize, usize>, label: i64, what: &str) -> Result<usize> {
    (label > 0)
        .then(|| nodes.get(&(label as usize)).copied())
        .flatten()
        .ok_or_else(|| {
            r.error(format!(
                "{what} refers to node {label}, which does not exist"
            ))
        })
}

fn point(r: &Record, key: &str, nsd: usize) -> Result<[f64; 3]> {
    let v = r.float_array(key)?;
    if v.len() != nsd {
        return Err(r.error(format!(
            "`{key}` needs {nsd} components in this {nsd}D domain, found {}",
            v.len()
        )));
    }
    let mut p = [0.0; 3];
    p[..nsd].copy_from_slice(&v);
    Ok(p)
}

fn unit(r: &Record, key: &str, v: [f64; 3]) -> Result<[f64; 3]> {
    let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if !(len > 1e-12) {
        return Err(r.error(format!("`{key}` must not be the zero vector")));
    }
    // OOFEM truncates the norm to an int before normalizing (spec §2.10 item 4); hertz always
    // normalizes.
    Ok([v[0] / len, v[1] / len, v[2] / len])
}

/// Read one record of the `ncontactseg` block.
pub fn read_segment(
    r: &Record,
    nodes: &HashMap<usize, usize>,
    nsd: usize,
    nset: usize,
) -> Result<PendingSegment> {
    let kw = r.keyword().to_string();
    let number = r.number()?;
    r.opt_int("normmode")?;
    let ref_node = |r: &Record| -> Result<Option<usize>> {
        r.opt_int("node")?
            .map(|l| node_ref(r, nodes, l, "the segment"))
            .transpose()
    };
    let mut seg = PendingSegment {
        number,
        kind: None,
        boundary_set: None,
        span: r.span(),
    };
    match kw.as_str() {
        "linear2delementedgecontactsegment"
        | "qelementedgecontactsegment"
        | "linear3delementsurfacecontactsegment" => {
            let faces = kw == "linear3delementsurfacecontactsegment";
            if nsd != if faces { 3 } else { 2 } {
                return Err(r.error(format!(
                    "`{kw}` needs a {}D domain",
                    if faces { 3 } else { 2 }
                )));
            }
            // `edgeset` in the OOFEM versions the tests were written for, `boundaryset` later.
            let set = match r.opt_usize("boundaryset")? {
                Some(s) => s,
                None => r
                    .opt_usize("edgeset")?
                    .ok_or_else(|| r.error("missing `edgeset` (or `boundaryset`)"))?,
            };
            if set == 0 || set > nset {
                return Err(r.error(format!(
                    "set {set} does not exist (the counts record declares {nset})"
                )));
            }
            match r.opt_int("pairupdatemode")? {
                None | Some(0..=2) => {}
                Some(v) => {
                    return Err(r.error(format!("`pairupdatemode` must be 0, 1 or 2, found {v}")))
                }
            }
            seg.boundary_set = Some((set, faces));
        }
        "circlecontactsegment" => {
            let center = point(r, "centerpoint", nsd)?;
            let radius = r.float("radius")?;
            if !(radius > 0.0) {
                return Err(r.error(format!("`radius` must be positive, found {radius}")));
            }
            seg.kind = Some(SegmentKind::Circle {
                center,
                radius,
                node: ref_node(r)?,
                cavity: r.flag("cavity"),
            });
        }
        "polynomialcontactsegment" => {
            if nsd != 2 {
                return Err(r.error("`polynomialcontactsegment` needs a 2D domain"));
            }
            let coeffs = r.float_array("coeffs")?;
            if coeffs.is_empty() {
                return Err(r.error("`coeffs` needs at least one coefficient"));
            }
            seg.kind = Some(SegmentKind::Polynomial {
                coeffs,
                body_above: r.flag("bodyabove"),
            });
        }
        "planecontactsegment" => {
            let p = point(r, "point", nsd)?;
            let n = unit(r, "normal", point(r, "normal", nsd)?)?;
            seg.kind = Some(SegmentKind::Plane {
                point: p,
                normal: n,
                node: ref_node(r)?,
            });
        }
        _ => {
            return Err(r.error(format!(
                "unsupported contact segment `{kw}`; supported: {}",
                SEGMENTS.join(", ")
            )));
        }
    }
    Ok(seg)
}

/// `friction μ [pt ε_T]` of a node-to-segment or mortar penalty condition (hertz extension; `pt` as in
/// upstream OOFEM's `structuralpenaltycontactbc`, by default the normal `penalty`), or `friction μ`
/// of a condition with Lagrange multipliers (no penalty: the friction force is a multiplier too).
fn read_friction(r: &Record, kw: &str, enforcement: Enforcement) -> Result<Option<Friction>> {
    let Some(mu) = r.opt_float("friction")? else {
        if r.opt_float("pt")?.is_some() {
            return Err(r.error("`pt` (the tangential penalty) needs `friction`"));
        }
        return Ok(None);
    };
    if !(mu >= 0.0 && mu.is_finite()) {
        return Err(r.error(format!("`friction` must be a coefficient >= 0, found {mu}")));
    }
    if kw.starts_with("n2n") {
        return Err(r.error(
            "friction is supported on node-to-segment and mortar conditions \
             (n2s... and s2s... conditions), not node-to-node",
        ));
    }
    let pt = r.opt_float("pt")?;
    match (enforcement, pt) {
        (Enforcement::Multipliers, Some(_)) => Err(r.error(
            "`pt` is a tangential penalty: friction with Lagrange multipliers has none \
             (the friction force is a multiplier); drop `pt`, or use a penalty condition",
        )),
        (Enforcement::Penalty(PenaltySource::FromMesh), Some(_)) => Err(r.error(
            "`pt` without `penalty`: give both, or neither (both are then chosen from the mesh)",
        )),
        (_, Some(pt)) if !(pt > 0.0 && pt.is_finite()) => {
            Err(r.error(format!("`pt` must be positive, found {pt}")))
        }
        (_, pt) => Ok(Some(Friction { mu, penalty: pt })),
    }
}

/// Read a contact condition record of the BC block.
pub fn read_condition(
    r: &Record,
    nodes: &HashMap<usize, usize>,
    nsd: usize,
    nset: usize,
    nseg: usize,
) -> Result<PendingCondition> {
    let kw = r.keyword().to_string();
    let number = r.number()?;
    // Without `penalty` (hertz extension; node-to-segment and mortar) a penalty is chosen from
    // the stiffness of the elements under each contact node (`DEFAULT_PENALTY_FACTOR`).
    let from_mesh =
        kw.contains("penalty") && !kw.starts_with("n2n") && r.opt_float("penalty")?.is_none();
    let enforcement = if from_mesh {
        Enforcement::Penalty(PenaltySource::FromMesh)
    } else if kw.contains("penalty") {
        let p = r.float("penalty")?;
        if !(p > 0.0) {
            return Err(r.error(format!("`penalty` must be positive, found {p}")));
        }
        Enforcement::Penalty(PenaltySource::Given(p))
    } else {
        Enforcement::Multipliers
    };
    // The tangent is always the exact one; `usetangent` is accepted for compatibility.
    r.flag("usetangent");
    let friction = read_friction(r, &kw, enforcement)?;
    let normal = match r.opt_float_array("normal")? {
        None => None,
        Some(v) if v.len() == nsd => {
            let mut p = [0.0; 3];
            p[..nsd].copy_from_slice(&v);
            Some(unit(r, "normal", p)?)
        }
        Some(v) => {
            return Err(r.error(format!(
                "`normal` needs {nsd} components, found {}",
                v.len()
            )))
        }
    };
    let mut c = PendingCondition {
        number,
        enforcement,
        friction,
        sets: None,
        nodes: vec![],
        node_set: None,
        slave_segment: None,
        segments: vec![],
        normal,
        span: r.span(),
    };
    if kw.starts_with("n2n") {
        let m = r.usize("masterset")?;
        let s = r.usize("slaveset")?;
        for v in [m, s] {
            if v == 0 || v > nset {
                return Err(r.error(format!(
                    "set {v} does not exist (the counts record declares {nset})"
                )));
            }
        }
        c.sets = Some((m, s));
    } else if kw.starts_with("s2s") {
        // Mortar (hertz extension): a slave contact segment against master segments.
        let g = r.usize("slavesegment")?;
        if g == 0 || g > nseg {
            return Err(r.error(format!(
                "contact segment {g} does not exist (ncontactseg {nseg})"
            )));
        }
        c.slave_segment = Some(g - 1);
        c.segments = segment_list(r, nseg)?;
        if c.segments.is_empty() {
            return Err(r.error("`segmentset` must not be empty"));
        }
    } else {
        // OOFEM uses these numbers as raw node indices (spec §2.10 item 11); hertz maps labels.
        // hertz also takes `slaveset k` (the nodes of set k: meshes imported from Gmsh).
        c.node_set = r.opt_usize("slaveset")?;
        match (c.node_set, r.opt_int_array("nodeset")?) {
            (Some(_), Some(_)) => {
                return Err(
                    r.error("give the contact nodes by `nodeset` or by `slaveset`, not both")
                )
            }
            (Some(v), None) if v == 0 || v > nset => {
                return Err(r.error(format!(
                    "set {v} does not exist (the counts record declares {nset})"
                )))
            }
            (Some(_), None) => {}
            (None, list) => {
                c.nodes = list
                    .ok_or_else(|| r.error("missing required keyword `nodeset` (or `slaveset`)"))?
                    .into_iter()
                    .map(|l| node_ref(r, nodes, l, "`nodeset`"))
                    .collect::<Result<_>>()?;
            }
        }
        c.segments = segment_list(r, nseg)?;
        if (c.nodes.is_empty() && c.node_set.is_none()) || c.segments.is_empty() {
            return Err(r.error("`nodeset` and `segmentset` must not be empty"));
        }
    }
    Ok(c)
}

/// `segmentset m g1..gm`: model segment indices.
fn segment_list(r: &Record, nseg: usize) -> Result<Vec<usize>> {
    r.int_array("segmentset")?
        .into_iter()
        .map(|s| {
            if s < 1 || s as usize > nseg {
                Err(r.error(format!(
                    "contact segment {s} does not exist (ncontactseg {nseg})"
                )))
            } else {
                Ok(s as usize - 1)
            }
        })
        .collect()
}

fn err(span: &Span, msg: String) -> Error {
    Error::Input {
        span: span.clone(),
        msg,
    }
}

/// Resolve sets into segments' edges and node-to-node pairs.
pub fn resolve(
    segs: Vec<PendingSegment>,
    conds: Vec<PendingCondition>,
    sets: &[Set],
    nodes: &[Node],
    elements: &[Element],
) -> Result<(Vec<ContactSegment>, Vec<ContactCondition>)> {
    let mut segments = Vec::with_capacity(segs.len());
    for s in segs {
        let kind = match (s.kind, s.boundary_set) {
            (Some(k), _) => k,
            (None, Some((set, faces))) => {
                let st = &sets[set - 1];
                let list: Vec<(usize, usize)> = if faces {
                    st.boundaries.iter().chain(&st.surfaces).copied().collect()
                } else {
                    st.boundaries.iter().chain(&st.edges).copied().collect()
                };
                if list.is_empty() {
                    return Err(err(
                        &s.span,
                        format!("set {set} lists no `elementboundaries` for the segment"),
                    ));
                }
                let dim = if faces { 3 } else { 2 };
                for &(e, _) in &list {
                    if elements[e].etype.shape().dim() != dim {
                        return Err(err(
                            &s.span,
                            format!(
                                "element {} of set {set} has no {}",
                                elements[e].label,
                                if faces { "3D faces" } else { "2D edges" }
                            ),
                        ));
                    }
                }
                if faces {
                    SegmentKind::Faces { faces: list }
                } else {
                    SegmentKind::Edges { edges: list }
                }
            }
            (None, None) => unreachable!("segments have a kind or an edge set"),
        };
        segments.push(ContactSegment {
            number: s.number,
            kind,
            span: s.span,
        });
    }
    let contacts = conds
        .into_iter()
        .map(|c| {
            let pairing = pairing(&c, &segments, sets, nodes)?;
            Ok(ContactCondition {
                number: c.number,
                enforcement: c.enforcement,
                friction: c.friction,
                pairing,
                normal: c.normal,
                node_weights: None,
                tributary_ramp: true,
                span: c.span,
            })
        })
        .collect::<Result<_>>()?;
    Ok((segments, contacts))
}

/// Which nodes a condition `c` pairs with what: mortar's slave segment, node-to-node's sets, or
/// node-to-segment's nodes (`nodeset`, or `slaveset`'s set).
fn pairing(
    c: &PendingCondition,
    segments: &[ContactSegment],
    sets: &[Set],
    nodes: &[Node],
) -> Result<Pairing> {
    Ok(match (c.sets, c.slave_segment) {
        (_, Some(slave)) => {
            if !matches!(
                segments[slave].kind,
                SegmentKind::Edges { .. } | SegmentKind::Faces { .. }
            ) {
                return Err(err(
                    &c.span,
                    format!(
                        "the slave segment {} of a mortar condition must be element edges \
                         (2D) or faces (3D)",
                        segments[slave].number
                    ),
                ));
            }
            Pairing::Mortar {
                slave,
                segments: c.segments.clone(),
            }
        }
        (Some((m, s)), None) => {
            let (mn, sn) = (&sets[m - 1].nodes, &sets[s - 1].nodes);
            if mn.len() != sn.len() || mn.is_empty() {
                return Err(err(
                    &c.span,
                    format!("master set {m} has {} nodes and slave set {s} has {}: they pair one to one", mn.len(), sn.len()),
                ));
            }
            Pairing::NodeToNode {
                pairs: mn.iter().copied().zip(sn.iter().copied()).collect(),
            }
        }
        (None, None) => {
            let nodes = match c.node_set {
                Some(k) if sets[k - 1].nodes.is_empty() => {
                    return Err(err(&c.span, format!("set {k} (`slaveset`) has no nodes")))
                }
                // A node the set gives twice, as one listed twice in `nodeset`.
                Some(k) if !sets[k - 1].repeated.is_empty() => {
                    return Err(err(
                        &c.span,
                        format!(
                            "node {} is listed twice in set {k} (`slaveset`)",
                            nodes[sets[k - 1].repeated[0]].label
                        ),
                    ))
                }
                Some(k) => sets[k - 1].nodes.clone(),
                None => c.nodes.clone(),
            };
            Pairing::NodeToSegment {
                nodes,
                segments: c.segments.clone(),
            }
        }
    })
}

/// What a contact node is held against: a rigid segment, an element side (by its sorted nodes,
/// whichever element or segment names it), or a node-to-node partner.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
enum Master {
    Rigid(usize),
    Side(Vec<usize>),
    Node(usize),
}

/// The element sides (sorted node lists) of an edge or face segment, none for a rigid one.
fn sides(segment: &ContactSegment, elements: &[Element]) -> Vec<Vec<usize>> {
    let (list, edges) = match &segment.kind {
        SegmentKind::Edges { edges } => (edges, true),
        SegmentKind::Faces { faces } => (faces, false),
        _ => return Vec::new(),
    };
    list.iter()
        .map(|&(e, b)| {
            let el = &elements[e];
            let shape = el.etype.shape();
            let local = if edges && shape.dim() == 3 {
                shape.edges()[b - 1]
            } else {
                shape.boundaries()[b - 1]
            };
            let mut n: Vec<usize> = local.iter().map(|&a| el.nodes[a]).collect();
            n.sort_unstable();
            n
        })
        .collect()
}

/// A node may be a contact node of two conditions only against different masters (a corner
/// against a floor and a wall): two that hold it against the same element side, rigid segment
/// or partner node repeat one constraint and split its force between them, each reporting a
/// part. That is an input error naming the node and both records.
pub fn check_one_condition_per_node(
    nodes: &[Node],
    elements: &[Element],
    segments: &[ContactSegment],
    contacts: &[ContactCondition],
) -> Result<()> {
    let masters_of = |list: &[usize]| -> HashSet<Master> {
        list.iter()
            .flat_map(|&g| {
                let s = sides(&segments[g], elements);
                if s.is_empty() {
                    vec![Master::Rigid(g)]
                } else {
                    s.into_iter().map(Master::Side).collect()
                }
            })
            .collect()
    };
    // Per condition: each contact node with the masters it can meet.
    let held: Vec<HashMap<usize, HashSet<Master>>> = contacts
        .iter()
        .map(|c| match &c.pairing {
            Pairing::NodeToNode { pairs } => pairs
                .iter()
                .map(|&(m, s)| (s, HashSet::from([Master::Node(m)])))
                .collect(),
            Pairing::NodeToSegment { nodes, segments } => {
                let masters = masters_of(segments);
                nodes.iter().map(|&n| (n, masters.clone())).collect()
            }
            Pairing::Mortar {
                slave,
                segments: list,
            } => {
                let masters = masters_of(list);
                sides(&segments[*slave], elements)
                    .into_iter()
                    .flatten()
                    .map(|n| (n, masters.clone()))
                    .collect()
            }
        })
        .collect();
    for (j, later) in contacts.iter().enumerate() {
        for (i, earlier) in contacts[..j].iter().enumerate() {
            let mut shared: Vec<(usize, &Master)> = held[j]
                .iter()
                .filter_map(|(n, mj)| {
                    let mi = held[i].get(n)?;
                    mj.iter().find(|m| mi.contains(m)).map(|m| (*n, m))
                })
                .collect();
            shared.sort_by_key(|&(n, _)| nodes[n].label);
            let Some(&(n, master)) = shared.first() else {
                continue;
            };
            let what = match master {
                Master::Rigid(g) => format!("rigid segment {}", segments[*g].number),
                Master::Side(side) => format!(
                    "the element side of nodes {}",
                    side.iter()
                        .map(|&a| nodes[a].label.to_string())
                        .collect::<Vec<_>>()
                        .join(" ")
                ),
                Master::Node(m) => format!("node {}", nodes[*m].label),
            };
            return Err(err(
                &later.span,
                format!(
                    "node {} is a contact node of conditions {} and {}{}, which both hold it \
                     against {what}: its contact force would be split between them, each \
                     reporting a part; keep it in one of them",
                    nodes[n].label,
                    earlier.number,
                    later.number,
                    if shared.len() > 1 {
                        format!(" (and {} more nodes)", shared.len() - 1)
                    } else {
                        String::new()
                    }
                ),
            ));
        }
    }
    Ok(())
}

//! Today's upstream OOFEM contact input (`../shared/spec/oofem-upstream-contact.md`): contact
//! elements (`StructuralContactElement_LineLin`, `_QuadLin`, `_TrLin`) that name boundaries of
//! bulk elements, `StructuralFEContactSurface` records grouping them, and
//! `StructuralPenaltyContactBC` pairing a slave surface with a master surface.
//!
//! They are solved by hertz's node-to-segment contact: the slave points are the slave elements'
//! Lobatto points, which with the default `nip` are their nodes, and — as upstream — every slave
//! element contributes its own point, unweighted (`dA = 1`): a node shared by k slave elements
//! acts with k·pn (and k·pt). The master is the bulk elements' boundaries the master contact
//! elements lie on. Where upstream is wrong, hertz does the right thing (spec §3):
//! * the master's outward normal comes from the bulk element, not from the contact element's node
//!   order (QUIRK: reversed elements give no contact at all upstream);
//! * triangles (`_TrLin`) work (QUIRK 15: a crash upstream);
//! * friction acts from the first step (QUIRK 3), with the stick law of the right sign (QUIRK 4),
//!   history reset on separation (QUIRK 8), an exact tangent (QUIRK 5);
//! * a step that does not converge is cut back or the run stops (QUIRK 20);
//! * `loadTimeFunction` is checked but, as upstream, never evaluated.

use super::record::Record;
use crate::error::{Error, Result, Span};
use crate::model::{
    ContactCondition, ContactSegment, Element, Enforcement, Friction, Pairing, PenaltySource,
    SegmentKind, Set,
};
use std::collections::HashMap;

/// Contact element keywords and (nodes, spatial dimension).
pub const CONTACT_ELEMENTS: [(&str, usize, usize); 3] = [
    ("structuralcontactelement_linelin", 2, 2),
    ("structuralcontactelement_quadlin", 4, 3),
    ("structuralcontactelement_trlin", 3, 3),
];

/// A contact element as read: its label, nodes (model indices) and record.
#[derive(Debug, Clone)]
pub struct ContactElement {
    pub label: usize,
    pub nodes: Vec<usize>,
    pub span: Span,
}

/// Read a contact element record (among the elements, counted in `nelem`).
pub fn read_contact_element(
    r: &Record,
    node_index: &HashMap<usize, usize>,
    nsd: usize,
) -> Result<ContactElement> {
    let kw = r.keyword().to_string();
    let &(_, n, dim) = CONTACT_ELEMENTS
        .iter()
        .find(|(k, _, _)| *k == kw)
        .expect("a contact element keyword");
    if dim != nsd {
        return Err(r.error(format!(
            "{kw} is a {dim}D contact element in a {nsd}D domain"
        )));
    }
    let label = r.number()?;
    let labels = r.int_array("nodes")?;
    if labels.len() != n {
        return Err(r.error(format!(
            "{kw} needs {n} nodes, `nodes` lists {}",
            labels.len()
        )));
    }
    let nodes = labels
        .iter()
        .map(|&l| {
            (l > 0)
                .then(|| node_index.get(&(l as usize)).copied())
                .flatten()
                .ok_or_else(|| {
                    r.error(format!(
                        "element {label} refers to node {l}, which does not exist"
                    ))
                })
        })
        .collect::<Result<Vec<usize>>>()?;
    r.usize("crosssect")?;
    r.opt_usize("mat")?;
    // The Lobatto points of the default rule are the nodes; others are not nodes.
    let default_nip = n;
    if let Some(nip) = r.opt_usize("nip")? {
        if nip != default_nip {
            return Err(r.error(format!(
                "{kw} with nip {nip}: hertz takes the default nip {default_nip}, whose Lobatto \
                 points are the element's nodes"
            )));
        }
    }
    Ok(ContactElement {
        label,
        nodes,
        span: r.span(),
    })
}

/// `StructuralFEContactSurface n ce_set s`: the number and its set.
pub fn read_surface(r: &Record, nset: usize) -> Result<usize> {
    if r.keyword() != "structuralfecontactsurface" {
        return Err(r.error(format!(
            "expected a StructuralFEContactSurface record, found `{}`",
            r.keyword()
        )));
    }
    let s = r.usize("ce_set")?;
    if s == 0 || s > nset {
        return Err(r.error(format!(
            "set {s} does not exist (the counts record declares {nset})"
        )));
    }
    Ok(s)
}

/// A `StructuralPenaltyContactBC` before its surfaces are resolved.
pub struct PendingPenaltyBc {
    number: usize,
    pn: f64,
    pt: f64,
    mu: f64,
    master: usize,
    slave: usize,
    span: Span,
}

/// Read a `StructuralPenaltyContactBC` record (in the BC block).
pub fn read_penalty_bc(r: &Record, nsd: usize, nsurf: usize) -> Result<PendingPenaltyBc> {
    let number = r.number()?;
    let dofs = r.int_array("dofs")?;
    let want: Vec<i64> = (1..=nsd as i64).collect();
    if dofs != want {
        return Err(r.error(format!(
            "`dofs` must list the displacements {want:?} of the {nsd}D domain, found {dofs:?}"
        )));
    }
    let given_nsd = r.usize("nsd")?;
    if given_nsd != nsd {
        return Err(r.error(format!("`nsd {given_nsd}` in a {nsd}D domain")));
    }
    r.opt_int("algo")?;
    let positive = |key: &str| -> Result<f64> {
        let v = r.float(key)?;
        if v > 0.0 && v.is_finite() {
            Ok(v)
        } else {
            Err(r.error(format!("`{key}` must be positive, found {v}")))
        }
    };
    let (pn, pt) = (positive("pn")?, positive("pt")?);
    let mu = r.float("friction")?;
    if !(mu >= 0.0 && mu.is_finite()) {
        return Err(r.error(format!("`friction` must be a coefficient >= 0, found {mu}")));
    }
    let surface = |key: &str| -> Result<usize> {
        let s = r.usize(key)?;
        if s == 0 || s > nsurf {
            return Err(r.error(format!(
                "contact surface {s} does not exist (ncontactsurf {nsurf})"
            )));
        }
        Ok(s)
    };
    let (master, slave) = (surface("mastersurface")?, surface("slavesurface")?);
    if master == slave {
        return Err(r.error("`mastersurface` and `slavesurface` must differ"));
    }
    Ok(PendingPenaltyBc {
        number,
        pn,
        pt,
        mu,
        master,
        slave,
        span: r.span(),
    })
}

/// Node-to-segment conditions (and the segments of their masters) for the penalty BCs.
/// `surfaces[k]` is the set of surface k + 1; `first_segment` numbers the new segments.
pub fn resolve(
    bcs: Vec<PendingPenaltyBc>,
    surfaces: &[usize],
    sets: &[Set],
    contact_elements: &[ContactElement],
    elements: &[Element],
    first_segment: usize,
) -> Result<(Vec<ContactSegment>, Vec<ContactCondition>)> {
    let err = |span: &Span, msg: String| Error::Input {
        span: span.clone(),
        msg,
    };
    // Bulk element boundaries by their sorted nodes.
    let mut boundary_of: HashMap<Vec<usize>, (usize, usize)> = HashMap::new();
    for (e, el) in elements.iter().enumerate() {
        for (b, local) in el.etype.shape().boundaries().iter().enumerate() {
            let mut key: Vec<usize> = local.iter().map(|&a| el.nodes[a]).collect();
            key.sort_unstable();
            boundary_of.entry(key).or_insert((e, b + 1));
        }
    }
    let members = |surface: usize, span: &Span| -> Result<&[usize]> {
        let set = &sets[surfaces[surface - 1] - 1];
        if set.contact_elements.is_empty() {
            return Err(err(
                span,
                format!(
                    "contact surface {surface} (set {}) lists no contact elements",
                    surfaces[surface - 1]
                ),
            ));
        }
        Ok(&set.contact_elements)
    };
    let mut segments = Vec::new();
    let mut conditions = Vec::new();
    for bc in bcs {
        let mut boundaries = Vec::new();
        for &ce in members(bc.master, &bc.span)? {
            let c = &contact_elements[ce];
            let mut key = c.nodes.clone();
            key.sort_unstable();
            let found = boundary_of.get(&key).ok_or_else(|| {
                err(
                    &c.span,
                    format!(
                        "contact element {} lies on no boundary of a bulk element",
                        c.label
                    ),
                )
            })?;
            boundaries.push(*found);
        }
        let faces = elements[boundaries[0].0].etype.shape().dim() == 3;
        let seg = first_segment + segments.len();
        segments.push(ContactSegment {
            number: seg + 1,
            kind: if faces {
                SegmentKind::Faces { faces: boundaries }
            } else {
                SegmentKind::Edges { edges: boundaries }
            },
            span: bc.span.clone(),
        });
        // Slave points: each slave element's nodes, a node once per element it is in.
        let mut nodes: Vec<usize> = Vec::new();
        let mut count: Vec<f64> = Vec::new();
        for &ce in members(bc.slave, &bc.span)? {
            for &n in &contact_elements[ce].nodes {
                match nodes.iter().position(|&m| m == n) {
                    Some(k) => count[k] += 1.0,
                    None => {
                        nodes.push(n);
                        count.push(1.0);
                    }
                }
            }
        }
        conditions.push(ContactCondition {
            number: bc.number,
            enforcement: Enforcement::Penalty(PenaltySource::Given(bc.pn)),
            friction: (bc.mu > 0.0).then_some(Friction {
                mu: bc.mu,
                penalty: Some(bc.pt),
            }),
            pairing: Pairing::NodeToSegment {
                nodes,
                segments: vec![seg],
            },
            normal: None,
            node_weights: Some(count),
            tributary_ramp: false,
            span: bc.span,
        });
    }
    Ok((segments, conditions))
}

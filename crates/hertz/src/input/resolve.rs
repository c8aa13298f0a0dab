//! Checks across blocks once everything is read: elements' sections and materials, loads that
//! act, geometry, and warnings (a load inside a body, a function before its first point).

use super::elements::ElementBlock;
use super::header::Counts;
use crate::error::{Error, Result};
use crate::model::*;
use std::collections::HashMap;

/// Each element's cross section and material (from its record or a cross section's set),
/// checked against each other.
pub(super) fn resolve_elements(
    block: ElementBlock,
    n: &Counts,
    cross_sections: &[CrossSection],
    materials: &[Material],
    sets: &[Set],
    warnings: &mut Vec<String>,
) -> Result<Vec<Element>> {
    let mut model_elements = block.elements;
    let mut elem_cs = block.elem_cs;
    let elem_mat = block.elem_mat;
    let (ncs, nmat) = (n.ncs, n.nmat);
    for (ci, cs) in cross_sections.iter().enumerate() {
        if let Some(s) = cs.set {
            for &e in &sets[s - 1].elements {
                elem_cs[e] = Some(ci + 1);
            }
        }
    }
    for (i, e) in model_elements.iter_mut().enumerate() {
        let span_err = |msg: String| Error::Input {
            span: e.span.clone(),
            msg,
        };
        let csn = elem_cs[i].ok_or_else(|| {
            span_err(format!(
                "element {} has no cross section (`crossSect` or a SimpleCS with `set`)",
                e.label
            ))
        })?;
        if csn == 0 || csn > ncs {
            return Err(span_err(format!(
                "element {} refers to cross section {csn}, which does not exist",
                e.label
            )));
        }
        let csr = &cross_sections[csn - 1];
        let mat = csr.material.or(elem_mat[i]).ok_or_else(|| {
            span_err(format!(
                "element {} has no material (`mat` or the cross section's `material`)",
                e.label
            ))
        })?;
        if mat == 0 || mat > nmat {
            return Err(span_err(format!(
                "element {} refers to material {mat}, which does not exist",
                e.label
            )));
        }
        if let MaterialLaw::Mises(m) = &materials[mat - 1].law {
            if e.nlgeo && m.kinematic != 0.0 && !e.etype.is_truss() {
                return Err(span_err(format!(
                    "element {} has `nlgeo 1` and material {mat}, a MisesMat with kinematic \
                     hardening `hk`: in large deformation hertz has isotropic hardening only \
                     (use `nlgeo 0`, or drop `hk`)",
                    e.label
                )));
            }
        }
        if matches!(materials[mat - 1].law, MaterialLaw::Dummy) {
            return Err(span_err(format!(
                "element {} has material {mat}, a DummyMat (for contact elements only)",
                e.label
            )));
        }
        if e.etype.mode() == StressMode::PlaneStress && csr.thick.is_none() {
            return Err(span_err(format!(
                "element {} is a plane-stress element but cross section {csn} has no `thick`",
                e.label
            )));
        }
        if e.etype.is_truss() && csr.area == 0.0 {
            warnings.push(format!(
                "{}:{}: bar element {} has no cross-section area (cross section {csn} gives no \
                 `area`): it carries no force",
                e.span.file.display(),
                e.span.line,
                e.label
            ));
        }
        e.cross_section = csn - 1;
        e.material = mat - 1;
    }
    Ok(model_elements)
}

/// A load or condition whose set gives it nothing to act on.
pub(super) fn check_loads_act(
    loads: &[Load],
    dirichlet: &[Dirichlet],
    sets: &[Set],
    elements: &[Element],
) -> Result<()> {
    // A load or condition that would act on nothing is an input error, never a silent no-op.
    for l in loads {
        let s = &sets[l.set - 1];
        let why = match l.boundaries(s, elements) {
            Err(msg) => Some(msg),
            Ok(b) => l.acts_on_nothing(s, &b),
        };
        if let Some(msg) = why {
            return Err(Error::Input {
                span: l.span.clone(),
                msg,
            });
        }
    }
    for d in dirichlet {
        if let Some(s) = d.set.filter(|&s| sets[s - 1].nodes.is_empty()) {
            return Err(Error::Input {
                span: d.span.clone(),
                msg: format!(
                    "BoundaryCondition {} acts on set {s}, which has no nodes: it would prescribe nothing",
                    d.number
                ),
            });
        }
    }

    Ok(())
}

/// Warn of time functions evaluated before their first point.
pub(super) fn warn_early_function_times(model: &Model, warnings: &mut Vec<String>) {
    // Earliest time a function is evaluated at: the first step, or one Δt before it for the
    // incremental loads of NonLinearStatic `refloadmode 1`.
    let a = &model.analysis;
    let mut first_t = model.step_times().first().copied().unwrap_or(0.0);
    if a.kind == AnalysisKind::NonLinearStatic && a.refloadmode == 1 {
        first_t -= a.deltat;
    }
    for (i, f) in model.functions.iter().enumerate() {
        if f.first_time().is_some_and(|t0| first_t < t0) {
            warnings.push(format!(
                "time function {} is evaluated before its first point (t = {first_t}); hertz uses the first value \
                 (OOFEM would return the first time instead)",
                i + 1
            ));
        }
    }
}

pub(super) fn elements_ref_nodes(nodes: &[Node]) -> Vec<[f64; 3]> {
    nodes.iter().map(|n| n.coords).collect()
}

/// Every element must have a non-degenerate reference geometry whose Jacobian keeps one sign
/// (OOFEM integrates with |det J|, so a consistently clockwise element is fine).
/// Warnings for loads and contact segments on element boundaries that are interior to the mesh
/// (shared by two elements, e.g. between two glued parts): a traction or a contact surface
/// there acts inside the body, which is rarely meant.
pub(super) fn interior_boundary_warnings(
    elements: &[Element],
    loads: &[Load],
    segments: &[crate::model::ContactSegment],
    sets: &[Set],
) -> Vec<String> {
    use crate::model::SegmentKind;
    // What each load and contact segment lies on: (record, what it is, its boundaries).
    type Named<'a> = (
        &'a crate::error::Span,
        String,
        Vec<(usize, &'static [usize])>,
    );
    let mut named: Vec<Named> = Vec::new();
    for l in loads {
        if let Ok(list) = l.boundaries(&sets[l.set - 1], elements) {
            let what = format!("{} {}", l.kind.record_name(), l.number);
            named.push((&l.span, what, list));
        }
    }
    for g in segments {
        if let SegmentKind::Edges { edges: b } | SegmentKind::Faces { faces: b } = &g.kind {
            let list = b
                .iter()
                .map(|&(e, k)| (e, elements[e].etype.shape().boundaries()[k - 1]))
                .collect();
            named.push((&g.span, format!("contact segment {}", g.number), list));
        }
    }
    named.retain(|(_, _, list)| !list.is_empty());
    if named.is_empty() {
        return Vec::new();
    }
    let key = |e: usize, local: &[usize]| {
        let el = &elements[e];
        let mut k: Vec<usize> = local.iter().map(|&a| el.nodes[a]).collect();
        k.sort_unstable();
        k
    };
    // How many elements have each of those boundaries.
    let mut uses: HashMap<Vec<usize>, usize> = named
        .iter()
        .flat_map(|(_, _, list)| list.iter().map(|&(e, local)| (key(e, local), 0)))
        .collect();
    for (e, el) in elements.iter().enumerate() {
        if el.etype.is_truss() {
            continue;
        }
        for local in el.etype.shape().boundaries() {
            if let Some(n) = uses.get_mut(&key(e, local)) {
                *n += 1;
            }
        }
    }
    named
        .into_iter()
        .filter_map(|(span, what, list)| {
            let labels: Vec<usize> = list
                .iter()
                .filter(|(e, local)| uses.get(&key(*e, local)).is_some_and(|&n| n > 1))
                .map(|(e, _)| elements[*e].label)
                .collect();
            if labels.is_empty() {
                return None;
            }
            let shown: Vec<String> = labels.iter().take(5).map(|l| l.to_string()).collect();
            Some(format!(
                "{}:{}: {what} lies on {} element {} shared by two elements (inside the mesh: \
                 glued parts?), of element(s) {}{}",
                span.file.display(),
                span.line,
                labels.len(),
                if labels.len() == 1 {
                    "boundary"
                } else {
                    "boundaries"
                },
                shown.join(" "),
                if labels.len() > 5 { " .." } else { "" }
            ))
        })
        .collect()
}

pub(super) fn check_geometry(coords: &[[f64; 3]], elements: &[Element]) -> Result<()> {
    for el in elements {
        let x: Vec<[f64; 3]> = el.nodes.iter().map(|&n| coords[n]).collect();
        let size = x
            .iter()
            .flat_map(|a| {
                x.iter()
                    .map(move |b| (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>())
            })
            .fold(0.0f64, f64::max)
            .sqrt();
        let err = |msg: String| Error::Input {
            span: el.span.clone(),
            msg,
        };
        if size == 0.0 {
            return Err(err(format!(
                "element {} has all its nodes at one point",
                el.label
            )));
        }
        if el.etype.is_truss() {
            continue;
        }
        if let Some(k) = x
            .iter()
            .position(|p| p[0] < 0.0)
            .filter(|_| el.etype.is_axisymmetric())
        {
            return Err(err(format!(
                "{} {} has a node at x = {}: x is the radius of an axisymmetric element, never \
                 negative (the axis is x = 0)",
                el.etype.name(),
                el.label,
                x[k][0]
            )));
        }
        let shape = el.etype.shape();
        let nip = el.nip.unwrap_or(el.etype.default_nip());
        let rule = crate::fem::rule(shape, nip).expect("nip validated");
        let dets = crate::fem::geometry::jacobian_dets(shape, &x, &rule);
        let tiny = 1e-10 * size.powi(shape.dim() as i32);
        if let Some(g) = dets.iter().position(|d| d.abs() <= tiny) {
            return Err(err(format!(
                "element {} has a degenerate geometry (det J = 0 at integration point {}): check its node coordinates and order",
                el.label,
                g + 1
            )));
        }
        if dets.iter().any(|d| *d > 0.0) && dets.iter().any(|d| *d < 0.0) {
            return Err(err(format!(
                "element {} is folded (det J changes sign between integration points): check its node order",
                el.label
            )));
        }
    }
    Ok(())
}

/// Edge and surface loads named by elements' `BoundaryLoads` (OOFEM's legacy form: pairs of a
/// load number and a boundary number on the element record) act on a set of their own, appended
/// to `sets`; a load named so must have no `set`, a load with neither is an error.
pub(super) fn attach_boundary_loads(
    loads: &mut [Load],
    sets: &mut Vec<Set>,
    named: &[(usize, usize, usize, crate::error::Span)],
) -> Result<()> {
    for (_, number, _, span) in named {
        let Some(load) = loads.iter().find(|l| l.number == *number) else {
            return Err(Error::Input {
                span: span.clone(),
                msg: format!(
                    "`BoundaryLoads` names load {number}, which is no edge or surface load"
                ),
            });
        };
        if load.set != 0 || !matches!(load.kind, LoadKind::Edge | LoadKind::Surface) {
            return Err(Error::Input {
                span: span.clone(),
                msg: format!(
                    "`BoundaryLoads` names {} {number}, which {}",
                    load.kind.record_name(),
                    if load.set != 0 {
                        "has a `set` already: give its boundaries one way"
                    } else {
                        "acts on no element boundary"
                    }
                ),
            });
        }
    }
    for load in loads.iter_mut().filter(|l| l.set == 0) {
        let boundaries: Vec<(usize, usize)> = named
            .iter()
            .filter(|(_, n, _, _)| *n == load.number)
            .map(|&(e, _, b, _)| (e, b))
            .collect();
        if boundaries.is_empty() {
            return Err(Error::Input {
                span: load.span.clone(),
                msg: format!(
                    "{} {} needs `set`, or elements that name it in `BoundaryLoads`",
                    load.kind.record_name(),
                    load.number
                ),
            });
        }
        sets.push(Set {
            boundaries,
            ..Default::default()
        });
        load.set = sets.len();
    }
    Ok(())
}

/// An axisymmetric model is axisymmetric throughout: its elements all axisymmetric (per radian)
/// or none.
/// A follower load needs large deformation (`nlgeo 1`) on the elements it acts on, and a
/// nonlinear analysis: in small strain the configuration never changes.
pub(super) fn check_follower_loads(model: &Model) -> Result<()> {
    for load in model.loads.iter().filter(|l| l.follower) {
        let error = |msg: String| Error::Input {
            span: load.span.clone(),
            msg,
        };
        if model.analysis.kind != crate::model::AnalysisKind::NonLinearStatic {
            return Err(error(format!(
                "follower load {} needs NonLinearStatic: a follower traction changes with the \
                 state",
                load.number
            )));
        }
        let boundaries = load.boundaries(&model.sets[load.set - 1], &model.elements);
        for (e, _) in boundaries.map_err(&error)? {
            let el = &model.elements[e];
            if !el.nlgeo {
                return Err(error(format!(
                    "follower load {} acts on {} {}, which is small strain: a follower \
                     traction acts on the current boundary, give the element `nlgeo 1` (or drop \
                     `follower` for a traction on the reference boundary)",
                    load.number,
                    el.etype.name(),
                    el.label
                )));
            }
        }
    }
    Ok(())
}

pub(super) fn check_axisymmetry(model: &Model) -> Result<()> {
    let axi = |e: &&Element| e.etype.is_axisymmetric();
    let Some(first) = model.elements.iter().find(axi) else {
        return Ok(());
    };
    if let Some(other) = model.elements.iter().find(|e| !e.etype.is_axisymmetric()) {
        return Err(Error::Input {
            span: other.span.clone(),
            msg: format!(
                "{} {} in a model with axisymmetric elements ({} {}): an axisymmetric model is \
                 per radian throughout, give every element an axisymmetric type",
                other.etype.name(),
                other.label,
                first.etype.name(),
                first.label
            ),
        });
    }
    Ok(())
}

//! The element block and the cross sections.

use super::cursor::{check_ref, Block, Cursor, Numbered};
use super::header::Counts;
use super::record::Record;
use crate::error::Result;
use crate::model::*;
use std::collections::HashMap;

/// The element records: bulk elements (their cross section and material numbers as given,
/// resolved later) and upstream OOFEM's contact elements.
pub(super) struct ElementBlock {
    pub(super) elements: Vec<Element>,
    pub(super) elem_index: HashMap<usize, usize>,
    pub(super) elem_cs: Vec<Option<usize>>,
    pub(super) elem_mat: Vec<Option<usize>>,
    pub(super) contact_elements: Vec<super::upstream::ContactElement>,
    pub(super) contact_index: HashMap<usize, usize>,
    /// The elements' `BoundaryLoads` pairs: (element index, load number, boundary number) and
    /// the record, for messages.
    pub(super) boundary_loads: Vec<(usize, usize, usize, crate::error::Span)>,
}

/// The element records.
pub(super) fn read_elements(
    c: &mut Cursor,
    nelem: usize,
    node_index: &HashMap<usize, usize>,
    domain: &DomainKind,
) -> Result<ElementBlock> {
    let mut elements = Vec::with_capacity(nelem);
    let mut elem_index: HashMap<usize, usize> = HashMap::new();
    let mut elem_cs: Vec<Option<usize>> = Vec::with_capacity(nelem);
    let mut elem_mat: Vec<Option<usize>> = Vec::with_capacity(nelem);
    let mut contact_elements: Vec<super::upstream::ContactElement> = Vec::new();
    let mut contact_index: HashMap<usize, usize> = HashMap::new();
    let mut boundary_loads = Vec::new();
    for i in 0..nelem {
        let r = c.next_of(Block::Element, i, nelem)?;
        let kw = r.keyword().to_string();
        if kw.starts_with("structuralcontactelement_") {
            let ce = super::upstream::read_contact_element(&r, node_index, domain.nsd())?;
            if elem_index.contains_key(&ce.label)
                || contact_index
                    .insert(ce.label, contact_elements.len())
                    .is_some()
            {
                return Err(r.error(format!("element label {} is used twice", ce.label)));
            }
            contact_elements.push(ce);
            c.finish(&r);
            continue;
        }
        let Some((etype, bbar)) = element_keyword(&kw) else {
            let names: Vec<&str> = ElementType::ALL.iter().map(|(_, t)| t.name()).collect();
            return Err(r.error(format!(
                "unknown element type `{kw}`; supported: {}, LSpaceBB, Quad1PlaneStrainBB",
                names.join(", ")
            )));
        };
        let label = r.number()?;
        let labels = r.int_array("nodes")?;
        if labels.len() != etype.n_nodes() {
            return Err(r.error(format!(
                "{} needs {} nodes, `nodes` lists {}",
                etype.name(),
                etype.n_nodes(),
                labels.len()
            )));
        }
        let mut enodes = Vec::with_capacity(labels.len());
        for &l in &labels {
            let idx = (l > 0).then(|| node_index.get(&(l as usize))).flatten();
            enodes.push(*idx.ok_or_else(|| {
                r.error(format!(
                    "element {label} refers to node {l}, which does not exist"
                ))
            })?);
        }
        let mut sorted = enodes.clone();
        sorted.sort_unstable();
        sorted.dedup();
        if sorted.len() != enodes.len() {
            return Err(r.error(format!("element {label} lists the same node twice")));
        }
        let (nip, nlgeo, truss_plane) = read_options(&r, etype)?;
        if nlgeo && etype.is_truss() {
            return Err(r.error("nlgeo 1 is not supported on truss elements"));
        }
        for k in ["bodyloads", "activityltf", "lcs"] {
            if r.flag(k) {
                return Err(r.error(format!("element keyword `{k}` is not supported; use sets")));
            }
        }
        for (load, boundary) in read_boundary_loads(&r, etype)? {
            boundary_loads.push((elements.len(), load, boundary, r.span()));
        }
        r.flag("reducedshearint");
        elem_cs.push(r.opt_usize("crosssect")?);
        elem_mat.push(r.opt_usize("mat")?);
        if contact_index.contains_key(&label) || elem_index.insert(label, elements.len()).is_some()
        {
            return Err(r.error(format!("element label {label} is used twice")));
        }
        elements.push(Element {
            label,
            etype,
            nodes: enodes,
            bbar,
            cross_section: usize::MAX,
            material: usize::MAX,
            nip,
            nlgeo,
            truss_plane,
            span: r.span(),
        });
        c.finish(&r);
    }

    Ok(ElementBlock {
        elements,
        elem_index,
        elem_cs,
        elem_mat,
        contact_elements,
        contact_index,
        boundary_loads,
    })
}

/// The cross-section records (`SimpleCS`, upstream's `DummyCS`).
pub(super) fn read_cross_sections(c: &mut Cursor, n: &Counts) -> Result<Vec<CrossSection>> {
    let (ncs, nmat, nset) = (n.ncs, n.nmat, n.nset);
    let mut cs = Numbered::new("cross section", ncs);
    for i in 0..ncs {
        let r = c.next_of(Block::CrossSection, i, ncs)?;
        if r.keyword() == "dummycs" {
            // Upstream OOFEM's cross section of contact elements: only its material is read.
            let material = Some(r.usize("mat")?);
            check_ref(&r, "mat", material, nmat)?;
            let set = r.opt_usize("set")?.filter(|&s| s > 0);
            check_ref(&r, "set", set, nset)?;
            cs.put(
                &r,
                CrossSection {
                    thick: None,
                    area: 0.0,
                    material,
                    set,
                },
            )?;
            c.finish(&r);
            continue;
        }
        if r.keyword() != "simplecs" {
            return Err(r.error(format!(
                "expected cross-section record {} of {ncs} (SimpleCS), found `{}`",
                i + 1,
                r.keyword()
            )));
        }
        let thick = r.opt_float("thick")?;
        let width = r.opt_float("width")?;
        let given_area = r.opt_float("area")?;
        for (key, v) in [("thick", thick), ("width", width), ("area", given_area)] {
            if let Some(v) = v.filter(|v| !(*v > 0.0)) {
                return Err(r.error(format!("`{key}` must be positive, found {v}")));
            }
        }
        // Without `area` (or `thick` and `width`) a bar has no section: OOFEM's own contact
        // tests use such zero-stiffness bars; they are accepted with a warning (see below).
        let area = given_area.unwrap_or(match (thick, width) {
            (Some(t), Some(w)) => t * w,
            _ => 0.0,
        });
        for k in ["iy", "iz", "ik", "beamshearcoeff"] {
            r.opt_float(k)?;
        }
        let material = r.opt_usize("material")?;
        let set = r.opt_usize("set")?;
        check_ref(&r, "material", material, nmat)?;
        check_ref(&r, "set", set.filter(|&s| s > 0), nset)?;
        cs.put(
            &r,
            CrossSection {
                thick,
                area,
                material,
                set: set.filter(|&s| s > 0),
            },
        )?;
        c.finish(&r);
    }
    let cross_sections = cs.finish();

    Ok(cross_sections)
}

/// The element type of a keyword (lower case) and whether it is barred: OOFEM's `LSpaceBB` and
/// its plane-strain counterpart `Quad1PlaneStrainBB`.
fn element_keyword(kw: &str) -> Option<(ElementType, bool)> {
    let bbar = matches!(kw, "lspacebb" | "quad1planestrainbb");
    let base = if bbar { &kw[..kw.len() - 2] } else { kw };
    ElementType::from_keyword(base).map(|t| (t, bbar))
}

/// An element record's `BoundaryLoads`: pairs of a load number and one of the element's
/// boundary numbers (OOFEM's legacy way of loading an edge or face).
fn read_boundary_loads(r: &Record, etype: ElementType) -> Result<Vec<(usize, usize)>> {
    let Some(pairs) = r.opt_int_array("boundaryloads")? else {
        return Ok(Vec::new());
    };
    let boundaries = etype.shape().boundaries().len() as i64;
    if pairs.len() % 2 != 0
        || pairs
            .chunks(2)
            .any(|p| p[0] < 1 || !(1..=boundaries).contains(&p[1]))
    {
        return Err(r.error(format!(
            "`BoundaryLoads` lists pairs of a load number and a boundary number (1 to \
             {boundaries} for {}), found {pairs:?}",
            etype.name()
        )));
    }
    Ok(pairs
        .chunks(2)
        .map(|p| (p[0] as usize, p[1] as usize))
        .collect())
}

/// An element record's `nip` (checked against its shape's rules), `nlgeo` and Truss2d's `cs`.
fn read_options(r: &Record, etype: ElementType) -> Result<(Option<usize>, bool, u8)> {
    let nip = r.opt_usize("nip")?;
    if let Some(n) = nip {
        if crate::fem::rule(etype.shape(), n).is_none() {
            return Err(r.error(format!("{} does not support nip {n}", etype.name())));
        }
    }
    let nlgeo = match r.opt_int("nlgeo")? {
        None | Some(0) => false,
        Some(1) => true,
        Some(v) => return Err(r.error(format!("`nlgeo` must be 0 or 1, found {v}"))),
    };
    let truss_plane = match (etype, r.opt_int("cs")?) {
        (_, None) => 0,
        (ElementType::Truss2d, Some(v @ 0..=2)) => v as u8,
        (ElementType::Truss2d, Some(v)) => {
            return Err(r.error(format!("Truss2d `cs` must be 0, 1 or 2, found {v}")))
        }
        (_, Some(_)) => return Err(r.error("keyword `cs` only applies to Truss2d")),
    };
    // OOFEM's point count of an axisymmetric element's hoop and shear terms: hertz takes them
    // as its guide says (the centroid for L4Axisymm, every point otherwise), which `nipfish 1`,
    // OOFEM's default, describes; another count is not what hertz computes (and leaves OOFEM's
    // Q4Axisymm without a B matrix: its QUIRK).
    match r.opt_int("nipfish")? {
        Some(v) if v != 1 || !etype.is_axisymmetric() => {
            return Err(r.error(format!(
                "`nipfish {v}` is not supported: axisymmetric elements take their hoop strain \
                 as the guide's Axisymmetric models says (`nipfish 1`, OOFEM's default)"
            )))
        }
        _ => {}
    }
    Ok((nip, nlgeo, truss_plane))
}

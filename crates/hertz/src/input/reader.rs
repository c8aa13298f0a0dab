//! Builds a [`Model`] from the records of an OOFEM input file in the order of spec §1.2,
//! checking counts, record numbers and every cross reference: the blocks in turn (their readers
//! in this folder), then the checks across them ([`super::resolve`]).

use super::conditions::{read_conditions, read_initial_conditions, Conditions};
use super::cursor::{Block, Cursor, Numbered};
use super::elements::{read_cross_sections, read_elements};
use super::functions::read_time_functions;
use super::header::{read_counts, read_header};
use super::lexer::{read_lines_and_sources, text_lines_and_sources, Line};
use super::materials::read_materials;
use super::nodes::read_nodes;
use super::record::Record;
use super::resolve::{
    attach_boundary_loads, check_axisymmetry, check_follower_loads, check_geometry,
    check_loads_act, elements_ref_nodes, interior_boundary_warnings, resolve_elements,
    warn_early_function_times,
};
use super::sets::{explain_missing_sets, read_sets, Refs};
use crate::error::{Error, Result};
use crate::model::*;
use std::path::{Path, PathBuf};

/// The model and the warnings met while reading it.
pub struct ReadResult {
    pub model: Model,
    pub warnings: Vec<String>,
    /// Every file the input consists of: the input file, its `@include`d files and `@gmsh`
    /// meshes.
    pub sources: Vec<PathBuf>,
}

/// Read and check an OOFEM input file.
pub fn read_model(path: &Path) -> Result<ReadResult> {
    let mut warnings = Vec::new();
    let model = read_model_warning(path, &mut warnings)?;
    Ok(ReadResult { warnings, ..model })
}

/// Read and check an OOFEM input held in memory, named `name` in messages (e.g. a model built
/// by a script); `@include` and `@gmsh` paths are relative to `name`'s directory.
pub fn read_model_str(text: &str, name: &str) -> Result<ReadResult> {
    let mut warnings = Vec::new();
    let path = Path::new(name);
    let (lines, sources) = text_lines_and_sources(path, text)?;
    let model = model_from_lines(path, lines, sources, &mut warnings)?;
    Ok(ReadResult { warnings, ..model })
}

/// [`read_model`], collecting the warnings into `warnings` (also those met before an error: an
/// unread token is often its cause). The result's own `warnings` are empty.
pub fn read_model_warning(path: &Path, warnings: &mut Vec<String>) -> Result<ReadResult> {
    let (lines, sources) = read_lines_and_sources(path)?;
    model_from_lines(path, lines, sources, warnings)
}

/// The model of the logical `lines` of input `path` (its `sources` the files it consists of).
pub(super) fn model_from_lines(
    path: &Path,
    lines: Vec<Line>,
    sources: Vec<PathBuf>,
    warnings: &mut Vec<String>,
) -> Result<ReadResult> {
    let file = path.display().to_string();
    if lines.len() < 2 {
        return Err(Error::InputFile {
            file,
            msg: "file is truncated: it needs an output file name line, a description line and records".into(),
        });
    }
    let output_name = lines[0].text.trim().to_string();
    let description = lines[1].text.trim_end().to_string();
    let mut c = Cursor {
        lines: lines[2..].to_vec(),
        pos: 0,
        file: file.clone(),
        warnings,
        sets_read_early: false,
    };

    let (analysis, domain, output) = read_header(&mut c)?;

    let n = read_counts(&mut c)?;
    let (nelem, nic, nset, ncontactseg, ncontactsurf) =
        (n.nelem, n.nic, n.nset, n.ncontactseg, n.ncontactsurf);

    let (nodes, node_index) = read_nodes(&mut c, n.ndofman)?;

    let mut block = read_elements(&mut c, nelem, &node_index, &domain)?;

    let refs = Refs {
        nodes: &node_index,
        elements: &block.elem_index,
        element_list: &block.elements,
        contact_elements: &block.contact_index,
    };
    // The sets may follow the elements directly (as `hertz import` writes them).
    let explain = |e| explain_missing_sets(e, &lines, &sources);
    let early_sets = (nset > 0 && c.peek_keyword().as_deref() == Some("set"))
        .then(|| read_sets(&mut c, nset, &refs).map_err(explain))
        .transpose()?;
    c.sets_read_early = early_sets.is_some();

    let (pending_segments, surfaces) = read_contact_geometry(
        &mut c,
        (ncontactseg, ncontactsurf),
        &node_index,
        &domain,
        nset,
    )?;

    let cross_sections = read_cross_sections(&mut c, &n)?;

    let materials = read_materials(&mut c, n.nmat, analysis.dynamics.is_some())?;

    let Conditions {
        dirichlet,
        loads,
        pending_penalty_bcs,
        pending_contacts,
    } = read_conditions(&mut c, &n, &analysis, &domain, &node_index)?;

    let initial_conditions = read_initial_conditions(&mut c, nic, nset, &analysis)?;

    let functions = read_time_functions(&mut c, n.nltf)?;

    let mut sets = match early_sets {
        Some(s) => s,
        None => read_sets(&mut c, nset, &refs).map_err(explain)?,
    };
    let mut loads = loads;
    attach_boundary_loads(&mut loads, &mut sets, &block.boundary_loads)?;

    expect_end(&c)?;

    let contact_elements = std::mem::take(&mut block.contact_elements);
    let model_elements =
        resolve_elements(block, &n, &cross_sections, &materials, &sets, c.warnings)?;
    check_loads_act(&loads, &dirichlet, &sets, &model_elements)?;
    check_geometry(&elements_ref_nodes(&nodes), &model_elements)?;
    let (segments, contacts) = resolve_contact(
        (pending_segments, pending_contacts),
        (pending_penalty_bcs, &surfaces, &contact_elements),
        &sets,
        &nodes,
        &model_elements,
    )?;
    let model = Model {
        input_path: path.to_path_buf(),
        output_name,
        description,
        analysis,
        domain,
        output,
        nodes,
        elements: model_elements,
        cross_sections,
        materials,
        dirichlet,
        loads,
        functions,
        sets,
        segments,
        contacts,
        initial_conditions,
    };
    check_axisymmetry(&model)?;
    check_follower_loads(&model)?;
    advise(&model, c.warnings);
    Ok(ReadResult {
        model,
        warnings: Vec::new(),
        sources,
    })
}

/// The contact segments and upstream OOFEM contact surfaces, in their blocks after the elements
/// (`counts`: `ncontactseg`, `ncontactsurf`).
fn read_contact_geometry(
    c: &mut Cursor,
    (nseg, nsurf): (usize, usize),
    node_index: &std::collections::HashMap<usize, usize>,
    domain: &DomainKind,
    nset: usize,
) -> Result<(Vec<super::contact::PendingSegment>, Vec<usize>)> {
    let mut segments = Numbered::new("contact segment", nseg);
    for i in 0..nseg {
        let r = c.next_of(Block::Segment, i, nseg)?;
        let seg = super::contact::read_segment(&r, node_index, domain.nsd(), nset)?;
        segments.put(&r, seg)?;
        c.finish(&r);
    }
    let mut surfaces = Numbered::new("contact surface", nsurf);
    for i in 0..nsurf {
        let r = c.next_of(Block::ContactSurface, i, nsurf)?;
        surfaces.put(&r, super::upstream::read_surface(&r, nset)?)?;
        c.finish(&r);
    }
    Ok((segments.finish(), surfaces.finish()))
}

/// No record may follow the last one the counts expect.
fn expect_end(c: &Cursor) -> Result<()> {
    match c.lines.get(c.pos) {
        Some(line) => {
            let r = Record::new(line.clone());
            Err(r.error(format!(
                "{} record(s) left after the last expected record: is a count (nset, nltf, nbc, ...) too small?",
                c.lines.len() - c.pos
            )))
        }
        None => Ok(()),
    }
}

/// The contact segments and conditions of the records and of upstream OOFEM's contact input,
/// checked: a node held twice against one master is an input error.
#[allow(clippy::type_complexity)]
fn resolve_contact(
    (segments, conditions): (
        Vec<super::contact::PendingSegment>,
        Vec<super::contact::PendingCondition>,
    ),
    (penalty_bcs, surfaces, contact_elements): (
        Vec<super::upstream::PendingPenaltyBc>,
        &[usize],
        &[super::upstream::ContactElement],
    ),
    sets: &[Set],
    nodes: &[Node],
    elements: &[Element],
) -> Result<(Vec<ContactSegment>, Vec<ContactCondition>)> {
    let (mut segments, mut contacts) =
        super::contact::resolve(segments, conditions, sets, nodes, elements)?;
    let (upstream_segments, upstream_contacts) = super::upstream::resolve(
        penalty_bcs,
        surfaces,
        sets,
        contact_elements,
        elements,
        segments.len(),
    )?;
    segments.extend(upstream_segments);
    contacts.extend(upstream_contacts);
    super::contact::check_one_condition_per_node(nodes, elements, &segments, &contacts)?;
    Ok((segments, contacts))
}

/// What a model that reads right would not compute as its author expects: a load inside a
/// body, a function evaluated before its first point, a nearly incompressible material on
/// elements that lock.
fn advise(model: &Model, warnings: &mut Vec<String>) {
    warnings.extend(interior_boundary_warnings(
        &model.elements,
        &model.loads,
        &model.segments,
        &model.sets,
    ));
    warn_early_function_times(model, warnings);
    warnings.extend(crate::model::advice::locking_warnings(model));
}

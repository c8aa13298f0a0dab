//! The set block: nodes, elements and their boundaries, edges and surfaces.

use super::cursor::{Block, Cursor, Numbered};
use super::lexer::{meshes_without_groups, Line};
use super::record::Record;
use crate::error::{Error, Result};
use crate::model::*;
use std::collections::HashMap;
use std::path::PathBuf;

pub(super) struct Refs<'a> {
    pub(super) nodes: &'a HashMap<usize, usize>,
    pub(super) elements: &'a HashMap<usize, usize>,
    pub(super) element_list: &'a [Element],
    /// Upstream OOFEM contact elements by label (indices into their own list).
    pub(super) contact_elements: &'a HashMap<usize, usize>,
}

/// A missing set record, when a spliced Gmsh mesh (of the input's `lines` from `sources`) has no
/// physical groups: say that this is why.
pub(super) fn explain_missing_sets(e: Error, lines: &[Line], sources: &[PathBuf]) -> Error {
    if !e.to_string().contains("expected set record") {
        return e;
    }
    let groupless = meshes_without_groups(lines, sources);
    let Some(mesh) = groupless.first() else {
        return e;
    };
    let note = format!(
        " ({} has no physical groups, so `@gmsh` gives no sets: hertz makes one set per physical \
         group; define Physical Curve/Surface/Volume groups in Gmsh for the body and each loaded, \
         supported or contact boundary)",
        mesh.display()
    );
    match e {
        Error::InputFile { file, msg } if msg.contains("expected set record") => Error::InputFile {
            file,
            msg: msg + &note,
        },
        Error::Input { span, msg } if msg.contains("expected set record") => Error::Input {
            span,
            msg: msg + &note,
        },
        e => e,
    }
}

/// The nodes of an unordered set: those `listed`, of its `elements` and of its element
/// boundaries, edges and surfaces (in that order of `sides`), sorted, once each.
pub(super) fn member_nodes(
    mut all: Vec<usize>,
    elements: &[usize],
    sides: [&[(usize, usize)]; 3],
    refs: &Refs,
) -> Vec<usize> {
    for &e in elements {
        all.extend(&refs.element_list[e].nodes);
    }
    for (list, edge) in sides.into_iter().zip([false, true, false]) {
        for &(e, b) in list {
            let el = &refs.element_list[e];
            let shape = el.etype.shape();
            let local = if edge {
                shape.edges()[b - 1]
            } else {
                shape.boundaries()[b - 1]
            };
            all.extend(local.iter().map(|&a| el.nodes[a]));
        }
    }
    all.sort_unstable();
    all.dedup();
    all
}

pub(super) fn read_sets(c: &mut Cursor, nset: usize, refs: &Refs) -> Result<Vec<Set>> {
    let mut sets = Numbered::new("set", nset);
    let mut names = HashMap::new();
    for i in 0..nset {
        let r = c.next_of(Block::Set, i, nset)?;
        if r.keyword() != "set" {
            return Err(r.error(format!(
                "expected set record {} of {nset}, found `{}`",
                i + 1,
                r.keyword()
            )));
        }
        let set = read_set(&r, refs)?;
        if let Some(name) = &set.name {
            if let Some(k) = names.insert(name.clone(), r.number()?) {
                return Err(r.error(format!(
                    "set name \"{name}\" is set {k}'s already: a name must name one set"
                )));
            }
        }
        sets.put(&r, set)?;
        refuse_stray_numbers(&r)?;
        c.finish(&r);
    }
    Ok(sets.finish())
}

/// A node or an element of a set record `r`, by its label.
fn member(r: &Record, index: &HashMap<usize, usize>, what: &str, l: i64) -> Result<usize> {
    (l > 0)
        .then(|| index.get(&(l as usize)).copied())
        .flatten()
        .ok_or_else(|| r.error(format!("set refers to {what} {l}, which does not exist")))
}

/// The (element, boundary or edge number) pairs of `key` in a set record.
fn side_pairs(r: &Record, refs: &Refs, key: &str, edges: bool) -> Result<Vec<(usize, usize)>> {
    let v = r.opt_int_array(key)?.unwrap_or_default();
    if v.len() % 2 != 0 {
        return Err(r.error(format!(
            "`{key}` needs (element, number) pairs: an even count"
        )));
    }
    v.chunks(2)
        .map(|p| {
            let e = member(r, refs.elements, "element", p[0])?;
            let shape = refs.element_list[e].etype.shape();
            let n = if edges {
                shape.edges().len()
            } else {
                shape.boundaries().len()
            };
            if p[1] < 1 || p[1] as usize > n {
                return Err(r.error(format!(
                    "`{key}`: element {} has boundaries 1..{n}, not {}",
                    p[0], p[1]
                )));
            }
            Ok((e, p[1] as usize))
        })
        .collect()
}

/// The nodes a set record gives more than once in `nodes` and `noderanges`.
fn repeated_nodes(explicit: &[usize], ranges: &[usize]) -> Vec<usize> {
    let mut given: Vec<usize> = explicit.iter().chain(ranges).copied().collect();
    given.sort_unstable();
    let mut twice: Vec<usize> = given
        .windows(2)
        .filter(|w| w[0] == w[1])
        .map(|w| w[0])
        .collect();
    twice.dedup();
    twice
}

/// The bulk elements of a set record (`elements`, `elementranges`, `allelements`) and,
/// listed apart, its upstream OOFEM contact elements.
fn set_elements(r: &Record, refs: &Refs) -> Result<(Vec<usize>, Vec<usize>)> {
    let listed = r.opt_int_array("elements")?.unwrap_or_default();
    let contact_elements: Vec<usize> = listed
        .iter()
        .filter_map(|&l| {
            (l > 0)
                .then(|| refs.contact_elements.get(&(l as usize)))
                .flatten()
        })
        .copied()
        .collect();
    let mut elements: Vec<usize> = listed
        .into_iter()
        .filter(|&l| !(l > 0 && refs.contact_elements.contains_key(&(l as usize))))
        .map(|l| member(r, refs.elements, "element", l))
        .collect::<Result<_>>()?;
    for e in r
        .opt_range_list("elementranges", refs.element_list.len())?
        .unwrap_or_default()
    {
        elements.push(member(r, refs.elements, "element", e)?);
    }
    if r.flag("allelements") {
        elements = (0..refs.element_list.len()).collect();
    }
    Ok((elements, contact_elements))
}

/// One set record.
fn read_set(r: &Record, refs: &Refs) -> Result<Set> {
    let node = |l: i64| member(r, refs.nodes, "node", l);
    let explicit: Vec<usize> = r
        .opt_int_array("nodes")?
        .unwrap_or_default()
        .into_iter()
        .map(node)
        .collect::<Result<_>>()?;
    let ranges: Vec<usize> = r
        .opt_range_list("noderanges", refs.nodes.len())?
        .unwrap_or_default()
        .into_iter()
        .map(node)
        .collect::<Result<_>>()?;
    let repeated = repeated_nodes(&explicit, &ranges);
    let (mut elements, contact_elements) = set_elements(r, refs)?;
    let boundaries = side_pairs(r, refs, "elementboundaries", false)?;
    let edges = side_pairs(r, refs, "elementedges", true)?;
    let surfaces = side_pairs(r, refs, "elementsurfaces", false)?;
    let ordered = r.flag("ordered_nodes");
    if let Some(i) = r.tokens.iter().position(|t| t == "ordered_nodes") {
        if r.tokens
            .get(i + 1)
            .is_some_and(|t| t.parse::<i64>().is_ok())
        {
            return Err(r.error(
                "`ordered_nodes` is a flag, not a kind of set: write \
                 `Set k ordered_nodes nodes n l1 .. ln` (the nodes in the order given)",
            ));
        }
    }
    let nodes = if r.flag("allnodes") {
        (0..refs.nodes.len()).collect()
    } else if ordered {
        let mut sorted = ranges.clone();
        sorted.sort_unstable();
        sorted.dedup();
        explicit.into_iter().chain(sorted).collect()
    } else {
        let listed = explicit.into_iter().chain(ranges).collect();
        member_nodes(listed, &elements, [&boundaries, &edges, &surfaces], refs)
    };
    elements.sort_unstable();
    elements.dedup();
    let name = r.opt_string("name")?;
    if name
        .as_deref()
        .is_some_and(|n| n.is_empty() || n.parse::<f64>().is_ok())
    {
        return Err(r.error(
            "a set's `name` is text that is not a number (a set is addressed by its number \
             or its name)",
        ));
    }
    Ok(Set {
        name,
        nodes,
        elements,
        boundaries,
        edges,
        surfaces,
        contact_elements,
        repeated,
    })
}

/// `nodes 1 2 3 4` (the count forgotten) reads one node, 2: numbers that no count covers are an
/// error, not a set with fewer members.
fn refuse_stray_numbers(r: &Record) -> Result<()> {
    let stray: Vec<&str> = r
        .unread()
        .into_iter()
        .filter(|t| t.parse::<f64>().is_ok())
        .collect();
    if stray.is_empty() {
        return Ok(());
    }
    Err(r.error(format!(
        "numbers `{}` that no count covers: an array is written with its count first, \
         e.g. `nodes 3 1 2 3` (was the count forgotten, or is it too small?)",
        stray.join(" ")
    )))
}

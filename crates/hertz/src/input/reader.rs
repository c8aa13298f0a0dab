//! Builds a [`Model`] from the records of an OOFEM input file in the order of spec §1.2,
//! checking counts, record numbers and every cross reference.

use super::lexer::{meshes_without_groups, read_lines_and_sources, text_lines_and_sources, Line};
use super::record::Record;
use crate::error::{Error, Result};
use crate::model::*;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// The model and the warnings met while reading it.
pub struct ReadResult {
    pub model: Model,
    pub warnings: Vec<String>,
    /// Every file the input consists of: the input file, its `@include`d files and `@gmsh`
    /// meshes.
    pub sources: Vec<PathBuf>,
}

/// Upper bound on the number of steps (guards allocations against absurd inputs).
const MAX_STEPS: usize = 10_000_000;
const SUPPORTED_ANALYSES: &str = "LinearStatic, NonLinearStatic, StaticStructural";

struct Cursor<'w> {
    lines: Vec<Line>,
    pos: usize,
    file: String,
    /// The caller's: the warnings met so far stay with it when reading fails.
    warnings: &'w mut Vec<String>,
    /// The sets came right after the elements: a set record met later is one too many.
    sets_read_early: bool,
}

impl Cursor<'_> {
    fn next(&mut self, what: &str) -> Result<Record> {
        let Some(line) = self.lines.get(self.pos).cloned() else {
            return Err(Error::InputFile {
                file: self.file.clone(),
                msg: format!("unexpected end of file: expected {what}"),
            });
        };
        self.pos += 1;
        Ok(Record::new(line))
    }

    fn peek_keyword(&self) -> Option<String> {
        self.lines.get(self.pos).map(|l| {
            Record::new(l.clone())
                .tokens
                .first()
                .cloned()
                .unwrap_or_default()
        })
    }

    /// Warn about tokens no lookup consumed (misspelled optional keywords).
    fn finish(&mut self, r: &Record) {
        const SHOWN: usize = 6;
        let unread = r.unread();
        if !unread.is_empty() {
            let more = match unread.len().saturating_sub(SHOWN) {
                0 => String::new(),
                n => format!(" and {n} more"),
            };
            self.warnings.push(format!(
                "{}:{}: unread token(s) `{}`{more} in record `{}` (misspelled keyword, or an \
                 array longer than its count?)",
                r.line.file.display(),
                r.line.line,
                unread[..unread.len().min(SHOWN)].join(" "),
                r.keyword()
            ));
        }
    }
}

/// The record blocks of an input file, in file order (sets may also follow the elements).
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Debug)]
enum Block {
    Node,
    Element,
    Segment,
    ContactSurface,
    CrossSection,
    Material,
    Condition,
    TimeFunction,
    Set,
}

const MATERIAL_KEYWORDS: [&str; 5] = [
    "isole",
    "misesmat",
    "mooneyrivlincompressiblemat",
    "ogdencompressiblemat",
    "simopistermat",
];
/// Boundary condition and load records (keywords compare case-insensitively).
const LOAD_KEYWORDS: [&str; 6] = [
    "BoundaryCondition",
    "NodalLoad",
    "ConstantEdgeLoad",
    "ConstantSurfaceLoad",
    "ConstantPressureLoad",
    "DeadWeight",
];
/// The upstream OOFEM contact condition record.
const UPSTREAM_CONDITION: &str = "StructuralPenaltyContactBC";
/// Records of the boundary-condition block that hertz reads but refuses with a message of their
/// own (not offered as supported).
const REFUSED_CONDITIONS: [&str; 1] = ["ConstantPressureLoad"];

/// The boundary-condition block's supported records, from the keyword tables.
fn supported_conditions() -> String {
    LOAD_KEYWORDS
        .iter()
        .filter(|k| !REFUSED_CONDITIONS.contains(k))
        .copied()
        .chain(super::contact::CONDITION_KEYWORDS)
        .chain([UPSTREAM_CONDITION])
        .collect::<Vec<_>>()
        .join(", ")
}

/// Whether `kw` (lower case) is a record of the boundary-condition block.
fn is_condition(kw: &str) -> bool {
    LOAD_KEYWORDS.iter().any(|k| k.eq_ignore_ascii_case(kw))
        || super::contact::CONDITION_KEYWORDS.contains(&kw)
        || UPSTREAM_CONDITION.eq_ignore_ascii_case(kw)
}
const FUNCTION_KEYWORDS: [&str; 3] = ["constantfunction", "piecewiselinfunction", "peakfunction"];

impl Block {
    /// The block a record keyword belongs to, if hertz knows the keyword.
    fn of(kw: &str) -> Option<Block> {
        Some(match kw {
            "node" | "slavenode" => Block::Node,
            "simplecs" | "dummycs" => Block::CrossSection,
            "structuralfecontactsurface" => Block::ContactSurface,
            "dummymat" => Block::Material,
            "set" => Block::Set,
            _ if ElementType::from_keyword(kw).is_some()
                || super::upstream::CONTACT_ELEMENTS.iter().any(|c| c.0 == kw) =>
            {
                Block::Element
            }
            _ if super::contact::SEGMENTS.contains(&kw) => Block::Segment,
            _ if MATERIAL_KEYWORDS.contains(&kw) => Block::Material,
            _ if is_condition(kw) => Block::Condition,
            _ if FUNCTION_KEYWORDS.contains(&kw) => Block::TimeFunction,
            _ => return None,
        })
    }

    fn name(self) -> &'static str {
        match self {
            Block::Node => "node",
            Block::Element => "element",
            Block::Segment => "contact segment",
            Block::ContactSurface => "contact surface",
            Block::CrossSection => "cross-section",
            Block::Material => "material",
            Block::Condition => "boundary-condition",
            Block::TimeFunction => "time-function",
            Block::Set => "set",
        }
    }

    fn count_key(self) -> &'static str {
        match self {
            Block::Node => "ndofman",
            Block::Element => "nelem",
            Block::Segment => "ncontactseg",
            Block::ContactSurface => "ncontactsurf",
            Block::CrossSection => "ncrosssect",
            Block::Material => "nmat",
            Block::Condition => "nbc",
            Block::TimeFunction => "nltf",
            Block::Set => "nset",
        }
    }
}

impl Cursor<'_> {
    /// Record `i` (0-based) of the `n` records of `block`. A record that belongs to another block
    /// means a count is wrong: the error names the count and the record found.
    fn next_of(&mut self, block: Block, i: usize, n: usize) -> Result<Record> {
        let (name, key) = (block.name(), block.count_key());
        let r = self.next(&format!("{name} record {} of {n} (`{key} {n}`)", i + 1))?;
        let kw = r.keyword().to_string();
        match Block::of(&kw) {
            Some(found) if found != block => {
                let early_set = found == Block::Set && self.sets_read_early;
                let why = if found > block && !early_set {
                    format!("`{key} {n}` is larger than the {i} {name} record(s) present")
                } else {
                    format!("is `{}` too small?", found.count_key())
                };
                let other = found.name();
                let article = if other.starts_with(['a', 'e', 'i', 'o', 'u']) {
                    "an"
                } else {
                    "a"
                };
                Err(r.error(format!(
                    "expected {name} record {} of {n}, found `{kw}`, {article} {other} record: {why}",
                    i + 1
                )))
            }
            _ => Ok(r),
        }
    }
}

/// Numbered records (materials, sets, ...) must be numbered 1..=count, each once.
struct Numbered<T> {
    what: &'static str,
    items: Vec<Option<T>>,
}

impl<T> Numbered<T> {
    fn new(what: &'static str, count: usize) -> Self {
        Numbered {
            what,
            items: (0..count).map(|_| None).collect(),
        }
    }
    fn put(&mut self, r: &Record, value: T) -> Result<()> {
        let n = r.number()?;
        let count = self.items.len();
        let slot = self.items.get_mut(n - 1).ok_or_else(|| {
            r.error(format!(
                "{} number {n} is out of range 1..{count} (the counts record declares {count})",
                self.what
            ))
        })?;
        if slot.is_some() {
            return Err(r.error(format!("{} number {n} is defined twice", self.what)));
        }
        *slot = Some(value);
        Ok(())
    }
    fn finish(self) -> Vec<T> {
        self.items
            .into_iter()
            .map(|x| x.expect("all slots filled: count records read"))
            .collect()
    }
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
fn model_from_lines(
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
    let mut sets: Option<Vec<Set>> = None;
    if nset > 0 && c.peek_keyword().as_deref() == Some("set") {
        sets = Some(
            read_sets(&mut c, nset, &refs)
                .map_err(|e| explain_missing_sets(e, &lines, &sources))?,
        );
        c.sets_read_early = true;
    }

    let mut pending_segments = Numbered::new("contact segment", ncontactseg);
    for i in 0..ncontactseg {
        let r = c.next_of(Block::Segment, i, ncontactseg)?;
        let seg = super::contact::read_segment(&r, &node_index, domain.nsd(), nset)?;
        pending_segments.put(&r, seg)?;
        c.finish(&r);
    }
    let pending_segments = pending_segments.finish();
    let mut surfaces = Numbered::new("contact surface", ncontactsurf);
    for i in 0..ncontactsurf {
        let r = c.next_of(Block::ContactSurface, i, ncontactsurf)?;
        surfaces.put(&r, super::upstream::read_surface(&r, nset)?)?;
        c.finish(&r);
    }
    let surfaces = surfaces.finish();

    let cross_sections = read_cross_sections(&mut c, &n)?;

    let materials = read_materials(&mut c, n.nmat)?;

    let Conditions {
        dirichlet,
        loads,
        pending_penalty_bcs,
        pending_contacts,
    } = read_conditions(&mut c, &n, &analysis, &domain, &node_index)?;

    if nic > 0 {
        let r = c.next("initial-condition record 1")?;
        return Err(r.error("initial conditions are not supported (set nic 0)"));
    }

    let functions = read_time_functions(&mut c, n.nltf)?;

    let sets = match sets {
        Some(s) => s,
        None => {
            read_sets(&mut c, nset, &refs).map_err(|e| explain_missing_sets(e, &lines, &sources))?
        }
    };

    if let Some(line) = c.lines.get(c.pos) {
        let r = Record::new(line.clone());
        return Err(r.error(format!(
            "{} record(s) left after the last expected record: is a count (nset, nltf, nbc, ...) too small?",
            c.lines.len() - c.pos
        )));
    }

    let contact_elements = std::mem::take(&mut block.contact_elements);
    let model_elements =
        resolve_elements(block, &n, &cross_sections, &materials, &sets, c.warnings)?;
    check_loads_act(&loads, &dirichlet, &sets, &model_elements)?;

    check_geometry(&elements_ref_nodes(&nodes), &model_elements)?;
    let (mut segments, mut contacts) = super::contact::resolve(
        pending_segments,
        pending_contacts,
        &sets,
        &nodes,
        &model_elements,
    )?;
    let (upstream_segments, upstream_contacts) = super::upstream::resolve(
        pending_penalty_bcs,
        &surfaces,
        &sets,
        &contact_elements,
        &model_elements,
        segments.len(),
    )?;
    segments.extend(upstream_segments);
    contacts.extend(upstream_contacts);
    super::contact::check_one_condition_per_node(&nodes, &model_elements, &segments, &contacts)?;
    c.warnings.extend(interior_boundary_warnings(
        &model_elements,
        &loads,
        &segments,
        &sets,
    ));
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
    };
    warn_early_function_times(&model, c.warnings);
    c.warnings
        .extend(crate::model::advice::locking_warnings(&model));
    Ok(ReadResult {
        model,
        warnings: Vec::new(),
        sources,
    })
}

/// The records before the counts: the engineering model (with its modules), the domain and the
/// output manager.
fn read_header(c: &mut Cursor) -> Result<(Analysis, DomainKind, OutputSelection)> {
    let file = c.file.clone();
    let r = c.next("the engineering-model record (e.g. StaticStructural nsteps 1)")?;
    let (mut analysis, nmodules, ninit, nmonitors) = read_analysis(&r)?;
    c.finish(&r);
    for i in 0..ninit {
        let r = c.next(&format!("init module record {} of {ninit}", i + 1))?;
        c.warnings.push(format!(
            "{}:{}: init module `{}` ignored",
            file,
            r.line.line,
            r.keyword()
        ));
    }
    for i in 0..nmodules {
        let r = c.next(&format!("export module record {} of {nmodules}", i + 1))?;
        if r.keyword() == "errorcheck" {
            analysis.errorcheck = true;
        } else {
            c.warnings.push(format!(
                "{}:{}: export module `{}` ignored",
                file,
                r.line.line,
                r.keyword()
            ));
        }
    }
    for i in 0..nmonitors {
        let r = c.next(&format!("monitor record {} of {nmonitors}", i + 1))?;
        c.warnings.push(format!(
            "{}:{}: monitor `{}` ignored",
            file,
            r.line.line,
            r.keyword()
        ));
    }

    // Domain record.
    let r = c.next("the domain record (e.g. domain 2dPlaneStress)")?;
    let domain = read_domain(&r)?;
    c.finish(&r);

    // Output manager.
    let r = c.next("the OutputManager record")?;
    if r.keyword() != "outputmanager" {
        return Err(r.error(format!(
            "expected the OutputManager record, found `{}`",
            r.keyword()
        )));
    }
    let left_records = c.lines.len() - c.pos;
    let output = OutputSelection {
        tstep_all: r.flag("tstep_all"),
        tstep_step: r.opt_usize("tstep_step")?,
        tsteps_out: r
            .opt_range_list("tsteps_out", MAX_STEPS)?
            .unwrap_or_default(),
        dofman_all: r.flag("dofman_all"),
        dofman_output: r
            .opt_range_list("dofman_output", left_records)?
            .unwrap_or_default(),
        dofman_except: r
            .opt_range_list("dofman_except", left_records)?
            .unwrap_or_default(),
        element_all: r.flag("element_all"),
        element_output: r
            .opt_range_list("element_output", left_records)?
            .unwrap_or_default(),
        element_except: r
            .opt_range_list("element_except", left_records)?
            .unwrap_or_default(),
    };
    c.finish(&r);

    Ok((analysis, domain, output))
}

/// The counts record: how many records of each block follow.
struct Counts {
    ndofman: usize,
    nelem: usize,
    ncs: usize,
    nmat: usize,
    nbc: usize,
    nic: usize,
    nltf: usize,
    nset: usize,
    ncontactseg: usize,
    ncontactsurf: usize,
}

/// The counts record, each count checked against the records left.
fn read_counts(c: &mut Cursor) -> Result<Counts> {
    let r = c.next("the counts record (ndofman nelem ncrosssect nmat nbc nic nltf ...)")?;
    r.keyword();
    let n = Counts {
        ndofman: r.usize("ndofman")?,
        nelem: r.usize("nelem")?,
        ncs: r.usize("ncrosssect")?,
        nmat: r.usize("nmat")?,
        nbc: r.usize("nbc")?,
        nic: r.usize("nic")?,
        nltf: r.usize("nltf")?,
        nset: r.opt_usize("nset")?.unwrap_or(0),
        ncontactseg: r.opt_usize("ncontactseg")?.unwrap_or(0),
        ncontactsurf: r.opt_usize("ncontactsurf")?.unwrap_or(0),
    };
    let left = c.lines.len() - c.pos;
    for (k, v) in [
        ("ndofman", n.ndofman),
        ("nelem", n.nelem),
        ("ncrosssect", n.ncs),
        ("nmat", n.nmat),
        ("nbc", n.nbc),
        ("nic", n.nic),
        ("nltf", n.nltf),
        ("nset", n.nset),
        ("ncontactseg", n.ncontactseg),
        ("ncontactsurf", n.ncontactsurf),
    ] {
        if v > left {
            return Err(r.error(format!(
                "`{k} {v}` is more than the {left} records left in the file"
            )));
        }
    }
    for k in ["nsd", "nbarrier", "nxfemman", "ncontactman", "nfracman"] {
        if r.opt_usize(k)?.unwrap_or(0) > 0 && k != "nsd" {
            return Err(r.error(format!("`{k}` > 0 is not supported by hertz")));
        }
    }
    r.flag("axisymm");
    c.finish(&r);

    Ok(n)
}

/// The node records (`Node`, `SlaveNode`), with the index of each label.
fn read_nodes(c: &mut Cursor, ndofman: usize) -> Result<(Vec<Node>, HashMap<usize, usize>)> {
    let mut nodes = Vec::with_capacity(ndofman);
    let mut node_index: HashMap<usize, usize> = HashMap::new();
    // (slave node index, master labels, weights, record) resolved once all nodes are known.
    type SlaveSpec = (usize, Vec<i64>, Option<Vec<f64>>, Record);
    let mut slave_masters: Vec<SlaveSpec> = Vec::new();
    for i in 0..ndofman {
        let r = c.next_of(Block::Node, i, ndofman)?;
        let kw = r.keyword().to_string();
        if kw != "node" && kw != "slavenode" {
            return Err(r.error(format!(
                "expected node record {} of {ndofman} (Node or SlaveNode), found `{kw}`",
                i + 1
            )));
        }
        let label = r.number()?;
        let coords = r.float_array("coords")?;
        if coords.is_empty() || coords.len() > 3 {
            return Err(r.error(format!(
                "`coords` needs 1 to 3 values, found {}",
                coords.len()
            )));
        }
        for k in ["bc", "load", "lcs", "dofidmask"] {
            if r.flag(k) {
                return Err(r.error(format!(
                    "node keyword `{k}` is not supported; use sets and BC records"
                )));
            }
        }
        let mut x = [0.0; 3];
        x[..coords.len()].copy_from_slice(&coords);
        if node_index.insert(label, i).is_some() {
            return Err(r.error(format!("node label {label} is used twice")));
        }
        if kw == "slavenode" {
            let masters = r.int_array("masterdofman")?;
            let weights = r.opt_float_array("weights")?;
            r.opt_int_array("doftype")?;
            slave_masters.push((i, masters, weights, Record::new(r.line.clone())));
        }
        nodes.push(Node {
            label,
            coords: x,
            slave: None,
            span: r.span(),
        });
        c.finish(&r);
    }
    for (i, masters, weights, r) in slave_masters {
        if masters.is_empty() {
            return Err(r.error("`masterDofMan` lists no master node"));
        }
        let idx = masters
            .iter()
            .map(|&m| {
                node_index
                    .get(&(m as usize))
                    .copied()
                    .filter(|_| m > 0)
                    .ok_or_else(|| r.error(format!("master node {m} does not exist")))
            })
            .collect::<Result<Vec<_>>>()?;
        if idx.contains(&i) {
            return Err(r.error("a slave node cannot be its own master"));
        }
        let w = weights.unwrap_or_else(|| vec![1.0 / idx.len() as f64; idx.len()]);
        if w.len() != idx.len() {
            return Err(r.error(format!(
                "`weights` has {} values for {} master nodes",
                w.len(),
                idx.len()
            )));
        }
        nodes[i].slave = Some(SlaveLink {
            masters: idx,
            weights: w,
        });
    }
    for n in &nodes {
        if let Some(s) = &n.slave {
            if s.masters.iter().any(|&m| nodes[m].slave.is_some()) {
                return Err(Error::Input {
                    span: n.span.clone(),
                    msg: "a slave node's master must not itself be a slave node".into(),
                });
            }
        }
    }

    Ok((nodes, node_index))
}

/// The element records: bulk elements (their cross section and material numbers as given,
/// resolved later) and upstream OOFEM's contact elements.
struct ElementBlock {
    elements: Vec<Element>,
    elem_index: HashMap<usize, usize>,
    elem_cs: Vec<Option<usize>>,
    elem_mat: Vec<Option<usize>>,
    contact_elements: Vec<super::upstream::ContactElement>,
    contact_index: HashMap<usize, usize>,
}

/// The element records.
fn read_elements(
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
        let Some(etype) = ElementType::from_keyword(&kw) else {
            let names: Vec<&str> = ElementType::ALL.iter().map(|(_, t)| t.name()).collect();
            return Err(r.error(format!(
                "unknown element type `{kw}`; supported: {}",
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
        if nlgeo && etype.is_truss() {
            return Err(r.error("nlgeo 1 is not supported on truss elements"));
        }
        for k in ["bodyloads", "boundaryloads", "activityltf", "lcs"] {
            if r.flag(k) {
                return Err(r.error(format!("element keyword `{k}` is not supported; use sets")));
            }
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
    })
}

/// The cross-section records (`SimpleCS`, upstream's `DummyCS`).
fn read_cross_sections(c: &mut Cursor, n: &Counts) -> Result<Vec<CrossSection>> {
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

/// The material records.
fn read_materials(c: &mut Cursor, nmat: usize) -> Result<Vec<Material>> {
    let mut mats = Numbered::new("material", nmat);
    for i in 0..nmat {
        let r = c.next_of(Block::Material, i, nmat)?;
        let m = if r.keyword() == "dummymat" {
            Material {
                density: 0.0,
                talpha: 0.0,
                law: MaterialLaw::Dummy,
            }
        } else {
            read_material(&r)?
        };
        mats.put(&r, m)?;
        c.finish(&r);
    }
    let materials = mats.finish();

    Ok(materials)
}

/// The boundary-condition block: Dirichlet conditions, loads, and contact conditions still to be
/// resolved against sets and segments.
struct Conditions {
    dirichlet: Vec<Dirichlet>,
    loads: Vec<Load>,
    pending_penalty_bcs: Vec<super::upstream::PendingPenaltyBc>,
    pending_contacts: Vec<super::contact::PendingCondition>,
}

/// The boundary-condition, load and contact-condition records.
fn read_conditions(
    c: &mut Cursor,
    n: &Counts,
    analysis: &Analysis,
    domain: &DomainKind,
    node_index: &HashMap<usize, usize>,
) -> Result<Conditions> {
    let (nbc, nltf, nset, ncontactsurf, ncontactseg) =
        (n.nbc, n.nltf, n.nset, n.ncontactsurf, n.ncontactseg);
    let mut pending_penalty_bcs = Vec::new();
    let mut pending_contacts = Vec::new();
    let mut bcs: Numbered<Option<Dirichlet>> = Numbered::new("boundary condition", nbc);
    let mut loads = Vec::new();
    for i in 0..nbc {
        let r = c.next_of(Block::Condition, i, nbc)?;
        let kw = r.keyword().to_string();
        let number = r.number()?;
        let function = r.usize("loadtimefunction")?;
        if function == 0 || function > nltf {
            return Err(r.error(format!(
                "loadTimeFunction {function} does not exist (nltf {nltf})"
            )));
        }
        let set = r.opt_usize("set")?.unwrap_or(0);
        check_ref(&r, "set", Some(set).filter(|&s| s > 0), nset)?;
        if r.flag("istimefunction") || r.flag("isimposedtimefunction") {
            return Err(r.error("`isImposedTimeFunction` is not supported"));
        }
        r.opt_usize("valtype")?;
        match kw.as_str() {
            "boundarycondition" => {
                let d = read_dirichlet(&r, number, function, set, domain)?;
                bcs.put(&r, Some(d))?;
            }
            "nodalload"
            | "constantedgeload"
            | "constantsurfaceload"
            | "constantpressureload"
            | "deadweight" => {
                loads.push(read_load(&r, &kw, number, function, set, domain)?);
                bcs.put(&r, None)?;
            }
            "structuralpenaltycontactbc" => {
                if analysis.kind == AnalysisKind::LinearStatic {
                    return Err(r.error(
                        "contact needs NonLinearStatic or StaticStructural, not LinearStatic",
                    ));
                }
                pending_penalty_bcs.push(super::upstream::read_penalty_bc(
                    &r,
                    domain.nsd(),
                    ncontactsurf,
                )?);
                bcs.put(&r, None)?;
            }
            k if super::contact::CONDITION_KEYWORDS.contains(&k) => {
                if analysis.kind == AnalysisKind::LinearStatic {
                    return Err(r.error(
                        "contact needs NonLinearStatic or StaticStructural, not LinearStatic",
                    ));
                }
                pending_contacts.push(super::contact::read_condition(
                    &r,
                    node_index,
                    domain.nsd(),
                    nset,
                    ncontactseg,
                )?);
                bcs.put(&r, None)?;
            }
            _ => {
                return Err(r.error(format!(
                    "unsupported boundary condition or load `{kw}`; supported: {}",
                    supported_conditions()
                )))
            }
        }
        c.finish(&r);
    }
    let dirichlet: Vec<Dirichlet> = bcs.finish().into_iter().flatten().collect();

    Ok(Conditions {
        dirichlet,
        loads,
        pending_penalty_bcs,
        pending_contacts,
    })
}

/// The DOF ids a `dofs` array names (displacements only), if it is there.
fn read_dofs(r: &Record) -> Result<Option<Vec<DofId>>> {
    match r.opt_int_array("dofs")? {
        None => Ok(None),
        Some(v) => v
            .iter()
            .map(|&d| {
                if (1..=3).contains(&d) {
                    Ok(d as DofId)
                } else {
                    Err(r.error(format!("DOF id {d} is not a displacement DOF (1, 2 or 3)")))
                }
            })
            .collect::<Result<Vec<_>>>()
            .map(Some),
    }
}

/// A `BoundaryCondition` record: prescribed values of DOFs on a set's nodes.
fn read_dirichlet(
    r: &Record,
    number: usize,
    function: usize,
    set: usize,
    domain: &DomainKind,
) -> Result<Dirichlet> {
    let dofs = read_dofs(r)?.unwrap_or_else(|| domain.default_dofs().to_vec());
    let values = match r.opt_float_array("values")? {
        Some(v) => v,
        None => {
            let v = match r.opt_float("prescribedvalue")? {
                Some(v) => v,
                None => r
                    .opt_float("d")?
                    .ok_or_else(|| r.error("BoundaryCondition needs `values`"))?,
            };
            vec![v; dofs.len()]
        }
    };
    if values.len() != dofs.len() {
        return Err(r.error(format!(
            "`values` has {} entries for {} dofs",
            values.len(),
            dofs.len()
        )));
    }
    Ok(Dirichlet {
        number,
        function,
        dofs,
        values,
        set: Some(set).filter(|&s| s > 0),
        span: r.span(),
    })
}

/// A load record (`NodalLoad`, `ConstantEdgeLoad`, `ConstantSurfaceLoad`, `DeadWeight`).
fn read_load(
    r: &Record,
    kw: &str,
    number: usize,
    function: usize,
    set: usize,
    domain: &DomainKind,
) -> Result<Load> {
    let kind = match kw {
        "nodalload" => LoadKind::Nodal,
        "constantedgeload" => LoadKind::Edge,
        "deadweight" => LoadKind::DeadWeight,
        _ => LoadKind::Surface,
    };
    if kw == "constantpressureload" {
        return Err(r.error("ConstantPressureLoad is not supported; use ConstantSurfaceLoad"));
    }
    let components = r.float_array("components")?;
    let dofs = match (&kind, read_dofs(r)?) {
        (_, Some(d)) => d,
        (LoadKind::DeadWeight, None) => (1..=components.len() as DofId).collect(),
        (_, None) => domain.default_dofs().to_vec(),
    };
    if components.len() != dofs.len() {
        return Err(r.error(format!(
            "`components` has {} entries for {} dofs",
            components.len(),
            dofs.len()
        )));
    }
    if r.opt_int("cstype")?.unwrap_or(0) != 0 {
        return Err(r.error("`cstype 1` (local load coordinates) is not supported"));
    }
    r.opt_int("loadtype")?;
    if set == 0 {
        return Err(r.error(format!(
            "{kw} needs `set` (legacy element boundaryloads are not supported)"
        )));
    }
    Ok(Load {
        number,
        kind,
        function,
        dofs,
        components,
        set,
        span: r.span(),
    })
}

/// The time-function records.
fn read_time_functions(c: &mut Cursor, nltf: usize) -> Result<Vec<TimeFunction>> {
    let mut funcs = Numbered::new("time function", nltf);
    for i in 0..nltf {
        let r = c.next_of(Block::TimeFunction, i, nltf)?;
        let f = match r.keyword() {
            "constantfunction" => TimeFunction::Constant(r.float("f(t)")?),
            "peakfunction" => TimeFunction::Peak { t: r.float("t")?, value: r.float("f(t)")? },
            "piecewiselinfunction" => {
                if r.flag("datafile") {
                    return Err(r.error("PiecewiseLinFunction `datafile` is not supported; list t and f(t)"));
                }
                let npoints = r.opt_usize("npoints")?;
                let t = r.float_array("t")?;
                let f = r.float_array("f(t)")?;
                if t.is_empty() || t.len() != f.len() {
                    return Err(r.error(format!("`t` has {} points and `f(t)` {}: they must match", t.len(), f.len())));
                }
                if npoints.is_some_and(|n| n != t.len()) {
                    return Err(r.error(format!(
                        "`npoints {}` but `t` and `f(t)` have {} points: they must match",
                        npoints.unwrap_or(0),
                        t.len()
                    )));
                }
                if t.windows(2).any(|w| w[1] <= w[0]) {
                    return Err(r.error("`t` must be strictly increasing"));
                }
                TimeFunction::PiecewiseLinear { t, f }
            }
            k => {
                return Err(r.error(format!(
                    "unsupported time function `{k}`; supported: ConstantFunction, PiecewiseLinFunction, PeakFunction"
                )))
            }
        };
        funcs.put(&r, f)?;
        c.finish(&r);
    }
    let functions = funcs.finish();

    Ok(functions)
}

/// Each element's cross section and material (from its record or a cross section's set),
/// checked against each other.
fn resolve_elements(
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
        if matches!(materials[mat - 1].law, MaterialLaw::Mises { .. }) && !e.etype.is_truss() {
            return Err(span_err(format!(
                "element {} has material {mat}, a MisesMat: plasticity is implemented for bars \
                 (Truss1d, Truss2d) only",
                e.label
            )));
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
fn check_loads_act(
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
fn warn_early_function_times(model: &Model, warnings: &mut Vec<String>) {
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

fn check_ref(r: &Record, what: &str, n: Option<usize>, count: usize) -> Result<()> {
    match n {
        Some(v) if v == 0 || v > count => Err(r.error(format!(
            "{what} {v} does not exist (the counts record declares {count})"
        ))),
        _ => Ok(()),
    }
}

fn read_analysis(r: &Record) -> Result<(Analysis, usize, usize, usize)> {
    let kind = match r.keyword() {
        "linearstatic" => AnalysisKind::LinearStatic,
        "nonlinearstatic" => AnalysisKind::NonLinearStatic,
        "staticstructural" => AnalysisKind::StaticStructural,
        k => {
            return Err(r.error(format!(
                "unsupported analysis type `{k}`; supported: {SUPPORTED_ANALYSES}"
            )));
        }
    };
    let prescribed_times = if kind == AnalysisKind::StaticStructural {
        r.opt_float_array("prescribedtimes")?
    } else {
        None
    };
    let nsteps = match (&prescribed_times, r.opt_usize("nsteps")?) {
        (Some(t), _) => t.len(),
        (None, Some(n)) => n,
        (None, None) => return Err(r.error("missing required keyword `nsteps`")),
    };
    if nsteps == 0 {
        return Err(r.error("`nsteps` must be positive"));
    }
    if nsteps > MAX_STEPS {
        return Err(r.error(format!(
            "`nsteps {nsteps}` is more than hertz runs ({MAX_STEPS})"
        )));
    }
    if r.opt_usize("nmsteps")?.unwrap_or(0) > 0 {
        return Err(r.error("metasteps (`nmsteps` > 0) are not supported"));
    }
    if kind == AnalysisKind::NonLinearStatic {
        let mode = match r.opt_int("controlmode")? {
            Some(m) => Some(m),
            None => r.opt_int("controllmode")?,
        };
        if mode.unwrap_or(0) != 1 {
            return Err(r.error(
                "NonLinearStatic needs `controlmode 1` (direct load control); indirect (arc-length) control is not supported",
            ));
        }
        if r.flag("deltatfunction") {
            return Err(r.error("`deltatfunction` is not supported"));
        }
    }
    let deltat = r.opt_float("deltat")?.unwrap_or(1.0);
    if !(deltat > 0.0) {
        return Err(r.error("`deltat` must be positive"));
    }
    let rtolv = r.opt_float("rtolv")?;
    let rtolf = r.opt_float("rtolf")?.or(rtolv).unwrap_or(1e-3);
    let rtold = r.opt_float("rtold")?.or(rtolv).unwrap_or(0.0);
    let maxiter = r.opt_usize("maxiter")?.unwrap_or(50).max(1);
    let manrmsteps = r.opt_usize("manrmsteps")?.filter(|&k| k > 0);
    let refloadmode = match r.opt_int("refloadmode")?.unwrap_or(0) {
        v @ (0 | 1) => v as u8,
        v => return Err(r.error(format!("`refloadmode` must be 0 or 1, found {v}"))),
    };
    let default_guess = if kind == AnalysisKind::StaticStructural {
        1
    } else {
        0
    };
    let initialguess = r.opt_int("initialguess")?.unwrap_or(default_guess) != 0;
    for k in [
        "renumber",
        "lstype",
        "smtype",
        "stiffmode",
        "miniter",
        "nonlinform",
        "contextoutputstep",
        "profileopt",
    ] {
        r.opt_int(k)?;
    }
    r.opt_string("solvertype")?;
    for k in [
        "soldepextforces",
        "suppress_output",
        "keepll",
        "donotfixload",
    ] {
        r.flag(k);
    }
    let nmodules = r.opt_usize("nmodules")?.unwrap_or(0);
    let ninit = r.opt_usize("ninitmodules")?.unwrap_or(0);
    let nmonitors = r.opt_usize("nmonitors")?.unwrap_or(0);
    let analysis = Analysis {
        kind,
        nsteps,
        deltat,
        prescribed_times,
        rtolf,
        rtold,
        maxiter,
        manrmsteps,
        refloadmode,
        initialguess,
        errorcheck: false,
    };
    Ok((analysis, nmodules, ninit, nmonitors))
}

fn read_domain(r: &Record) -> Result<DomainKind> {
    let i = r.tokens.iter().position(|t| t == "domain").ok_or_else(|| {
        r.error(format!(
            "expected the domain record (e.g. `domain 2dPlaneStress`), found `{}`",
            r.keyword()
        ))
    })?;
    r.flag("domain");
    r.opt_string("domain")?;
    let t = r.tokens.get(i + 1).map(String::as_str).unwrap_or("");
    let kind = if t.starts_with("2dplanestressrot") {
        None
    } else if t.starts_with("2dplanestress") {
        Some(DomainKind::PlaneStress)
    } else if t.starts_with("planestrain") {
        Some(DomainKind::PlaneStrain)
    } else if t.starts_with("2dtruss") {
        Some(DomainKind::Truss2d)
    } else if t.starts_with("1dtruss") {
        Some(DomainKind::Truss1d)
    } else if t.starts_with("3d") && !t.starts_with("3daxisymm") && !t.starts_with("3dshell") {
        Some(DomainKind::ThreeD)
    } else {
        None
    };
    kind.ok_or_else(|| {
        r.error(format!("unsupported domain type `{t}`; supported: 2dPlaneStress, PlaneStrain, 3d, 2dTruss, 1dTruss"))
    })
}

struct Refs<'a> {
    nodes: &'a HashMap<usize, usize>,
    elements: &'a HashMap<usize, usize>,
    element_list: &'a [Element],
    /// Upstream OOFEM contact elements by label (indices into their own list).
    contact_elements: &'a HashMap<usize, usize>,
}

/// A missing set record, when a spliced Gmsh mesh (of the input's `lines` from `sources`) has no
/// physical groups: say that this is why.
fn explain_missing_sets(e: Error, lines: &[Line], sources: &[PathBuf]) -> Error {
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
fn member_nodes(
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

fn read_sets(c: &mut Cursor, nset: usize, refs: &Refs) -> Result<Vec<Set>> {
    let mut sets = Numbered::new("set", nset);
    for i in 0..nset {
        let r = c.next_of(Block::Set, i, nset)?;
        if r.keyword() != "set" {
            return Err(r.error(format!(
                "expected set record {} of {nset}, found `{}`",
                i + 1,
                r.keyword()
            )));
        }
        let node = |l: i64| -> Result<usize> {
            (l > 0)
                .then(|| refs.nodes.get(&(l as usize)).copied())
                .flatten()
                .ok_or_else(|| r.error(format!("set refers to node {l}, which does not exist")))
        };
        let elem = |l: i64| -> Result<usize> {
            (l > 0)
                .then(|| refs.elements.get(&(l as usize)).copied())
                .flatten()
                .ok_or_else(|| r.error(format!("set refers to element {l}, which does not exist")))
        };
        let pairs = |key: &str, edges: bool| -> Result<Vec<(usize, usize)>> {
            let v = r.opt_int_array(key)?.unwrap_or_default();
            if v.len() % 2 != 0 {
                return Err(r.error(format!(
                    "`{key}` needs (element, number) pairs: an even count"
                )));
            }
            v.chunks(2)
                .map(|p| {
                    let e = elem(p[0])?;
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
        };
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
        let repeated: Vec<usize> = {
            let mut given: Vec<usize> = explicit.iter().chain(&ranges).copied().collect();
            given.sort_unstable();
            let mut twice: Vec<usize> = given
                .windows(2)
                .filter(|w| w[0] == w[1])
                .map(|w| w[0])
                .collect();
            twice.dedup();
            twice
        };
        // Contact elements (upstream OOFEM) are listed apart from the bulk elements.
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
            .map(elem)
            .collect::<Result<_>>()?;
        for e in r
            .opt_range_list("elementranges", refs.element_list.len())?
            .unwrap_or_default()
        {
            elements.push(elem(e)?);
        }
        if r.flag("allelements") {
            elements = (0..refs.element_list.len()).collect();
        }
        let boundaries = pairs("elementboundaries", false)?;
        let edges = pairs("elementedges", true)?;
        let surfaces = pairs("elementsurfaces", false)?;
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
        sets.put(
            &r,
            Set {
                nodes,
                elements,
                boundaries,
                edges,
                surfaces,
                contact_elements,
                repeated,
            },
        )?;
        // `nodes 1 2 3 4` (the count forgotten) reads one node, 2: numbers that no count covers
        // are an error, not a set with fewer members.
        let stray: Vec<&str> = r
            .unread()
            .into_iter()
            .filter(|t| t.parse::<f64>().is_ok())
            .collect();
        if !stray.is_empty() {
            return Err(r.error(format!(
                "numbers `{}` that no count covers: an array is written with its count first, \
                 e.g. `nodes 3 1 2 3` (was the count forgotten, or is it too small?)",
                stray.join(" ")
            )));
        }
        c.finish(&r);
    }
    Ok(sets.finish())
}

fn elements_ref_nodes(nodes: &[Node]) -> Vec<[f64; 3]> {
    nodes.iter().map(|n| n.coords).collect()
}

/// Every element must have a non-degenerate reference geometry whose Jacobian keeps one sign
/// (OOFEM integrates with |det J|, so a consistently clockwise element is fine).
/// Warnings for loads and contact segments on element boundaries that are interior to the mesh
/// (shared by two elements, e.g. between two glued parts): a traction or a contact surface
/// there acts inside the body, which is rarely meant.
fn interior_boundary_warnings(
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

fn check_geometry(coords: &[[f64; 3]], elements: &[Element]) -> Result<()> {
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

/// A material record: `IsoLE`, or one of upstream OOFEM's compressible hyperelastic laws.
fn read_material(r: &Record) -> Result<Material> {
    let density = r.float("d")?;
    let talpha = r.opt_float("talpha")?.unwrap_or(0.0);
    r.opt_float("referencetemperature")?;
    let positive = |key: &str, v: f64| -> Result<f64> {
        if v > 0.0 {
            Ok(v)
        } else {
            Err(r.error(format!("`{key}` must be positive, found {v}")))
        }
    };
    let law = match r.keyword() {
        "isole" => {
            let young = r.float("e")?;
            let poisson = r.float("n")?;
            r.float("talpha")?;
            if !(young > 0.0) {
                return Err(r.error(format!("Young's modulus E must be positive, found {young}")));
            }
            if !(poisson > -1.0 && poisson < 0.5) {
                return Err(r.error(format!(
                    "Poisson's ratio n must lie in (-1, 0.5), found {poisson}"
                )));
            }
            MaterialLaw::LinearElastic { young, poisson }
        }
        "misesmat" => {
            let young = positive("E", r.float("e")?)?;
            let poisson = r.float("n")?;
            r.opt_float("talpha")?;
            let yield_stress = positive("sig0", r.float("sig0")?)?;
            let hardening = r.opt_float("h")?.unwrap_or(0.0);
            if !(hardening >= 0.0) {
                return Err(r.error(format!(
                    "the hardening modulus H must not be negative, found {hardening}"
                )));
            }
            for (key, what) in [
                ("omega_crit", "damage"),
                ("siginf", "saturation hardening"),
                ("kappa1", "piecewise hardening"),
            ] {
                if r.opt_float(key)?.is_some_and(|v| v != 0.0) {
                    return Err(r.error(format!(
                        "`{key}` ({what}) is not supported: MisesMat here has linear isotropic \
                         hardening only (sig0, H)"
                    )));
                }
            }
            r.opt_float("a")?;
            MaterialLaw::Mises {
                young,
                poisson,
                yield_stress,
                hardening,
            }
        }
        "mooneyrivlincompressiblemat" => {
            let (c1, c2) = (r.float("c1")?, r.float("c2")?);
            let k = positive("k", r.float("k")?)?;
            if !(c1 + c2 > 0.0) {
                return Err(r.error(format!(
                    "the shear modulus 2(c1 + c2) must be positive, found {}",
                    2.0 * (c1 + c2)
                )));
            }
            MaterialLaw::MooneyRivlin { c1, c2, k }
        }
        "ogdencompressiblemat" => {
            let alpha = r.float_array("alpha")?;
            let mu = r.float_array("mu")?;
            let k = positive("k", r.float("k")?)?;
            if alpha.is_empty() || alpha.len() != mu.len() || alpha.len() > 7 {
                return Err(r.error(format!(
                    "`alpha` and `mu` need the same number of terms, 1 to 7 (found {} and {})",
                    alpha.len(),
                    mu.len()
                )));
            }
            if alpha.iter().any(|a| !(a.abs() > 0.0)) {
                return Err(r.error("every `alpha` must be non-zero"));
            }
            let g = 0.5 * alpha.iter().zip(&mu).map(|(a, m)| a * m).sum::<f64>();
            if !(g > 0.0) {
                return Err(r.error(format!(
                    "the shear modulus ½ Σ alpha·mu must be positive, found {g}"
                )));
            }
            MaterialLaw::Ogden { alpha, mu, k }
        }
        "simopistermat" => MaterialLaw::SimoPister {
            g: positive("g", r.float("g")?)?,
            k: positive("k", r.float("k")?)?,
        },
        other => {
            return Err(r.error(format!(
                "unsupported material `{other}`; supported: IsoLE, MisesMat (bars), \
                 MooneyRivlinCompressibleMat, OgdenCompressibleMat, SimoPisterMat (or is a count \
                 before nmat wrong?)"
            )))
        }
    };
    Ok(Material {
        density,
        talpha,
        law,
    })
}

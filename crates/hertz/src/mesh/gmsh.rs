//! Gmsh meshes (`.msh` 2.2 and 4.1, ASCII) to OOFEM records: nodes, elements in hertz's types and
//! node orders with a positive Jacobian, and one set per physical group (elements for the
//! mesh's own dimension, element boundaries with their local numbers for the dimension below,
//! nodes for points).
//!
//! Glossary: `dim` the mesh dimension (highest element dimension present), `tag` Gmsh's node,
//! element, entity or physical number, `corner` the first nodes of an element or boundary that
//! identify it.

use crate::error::{Error, Result};
use crate::fem::geometry::det_j_at_centre;
use crate::fem::shape::Shape;
use crate::model::ElementType;
use std::collections::{BTreeMap, HashMap};
use std::path::Path;

/// One Gmsh element: its type number, physical tags and node tags (Gmsh order).
#[derive(Debug, Clone)]
struct RawElement {
    gmsh_type: usize,
    physical: Vec<usize>,
    nodes: Vec<usize>,
}

/// A mesh as read from the file.
#[derive(Debug, Default)]
struct RawMesh {
    /// Node tag -> coordinates, in file order.
    nodes: Vec<(usize, [f64; 3])>,
    elements: Vec<RawElement>,
    /// (dim, physical tag) -> name.
    names: BTreeMap<(usize, usize), String>,
}

/// A physical group turned into an OOFEM set.
#[derive(Debug, Clone)]
pub struct GroupSet {
    pub number: usize,
    pub name: String,
    pub dim: usize,
    pub physical: usize,
    /// Element records (0-based indices into `Converted::elements`).
    pub elements: Vec<usize>,
    /// (element index, 1-based boundary number).
    pub boundaries: Vec<(usize, usize)>,
    /// Node records (0-based) of point groups.
    pub nodes: Vec<usize>,
}

/// The mesh in hertz's terms.
#[derive(Debug)]
pub struct Converted {
    pub dim: usize,
    pub coords: Vec<[f64; 3]>,
    pub elements: Vec<(ElementType, Vec<usize>)>,
    pub sets: Vec<GroupSet>,
    /// Elements whose Gmsh order had a negative Jacobian and were mirrored.
    pub n_flipped: usize,
    /// The element records say `nlgeo 1` (large deformation).
    pub nlgeo: bool,
}

/// How 2D elements are named.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Plane {
    /// PlaneStress2d, TrPlaneStress2d, QPlaneStress2d, QTrPlStr
    #[default]
    Stress,
    /// Quad1PlaneStrain, TrPlaneStrain, QPlaneStrain, QTrPlaneStrain
    Strain,
    /// L4Axisymm, Axisymm3d, Q4Axisymm (x the radius; no 6-node axisymmetric triangle)
    Axisymmetric,
}

/// The first words of every file `hertz import` writes (see [`Converted::fragment`]).
const FRAGMENT_MARK: &str = "# Converted by hertz ";

/// `hertz import` writes `out` only where no file is, or over a file it wrote itself (its first
/// line is the conversion header): never over the mesh, an input or any other file of the user's.
fn refuse_to_overwrite_a_users_file(out: &Path, mesh: &Path) -> Result<()> {
    let same = |a: &Path, b: &Path| match (a.canonicalize(), b.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => a == b,
    };
    if same(out, mesh) {
        return Err(Error::InputFile {
            file: mesh.display().to_string(),
            msg: format!(
                "the output {} would overwrite the mesh: name another with -o FILE",
                out.display()
            ),
        });
    }
    let Ok(mut f) = std::fs::File::open(out) else {
        return Ok(());
    };
    let mut head = [0u8; FRAGMENT_MARK.len()];
    let ours =
        std::io::Read::read_exact(&mut f, &mut head).is_ok() && head == FRAGMENT_MARK.as_bytes();
    if ours {
        return Ok(());
    }
    Err(Error::InputFile {
        file: mesh.display().to_string(),
        msg: format!(
            "{} exists and was not written by `hertz import`: refusing to overwrite it; name the \
             output with -o FILE (or remove the file)",
            out.display()
        ),
    })
}

fn err(path: &Path, line: usize, msg: impl Into<String>) -> Error {
    Error::InputFile {
        file: if line > 0 {
            format!("{}:{line}", path.display())
        } else {
            path.display().to_string()
        },
        msg: msg.into(),
    }
}

/// Whitespace tokens with their 1-based line numbers.
struct Tokens<'a> {
    path: &'a Path,
    lines: std::iter::Peekable<std::iter::Enumerate<std::str::Lines<'a>>>,
    pending: std::collections::VecDeque<(usize, &'a str)>,
    line: usize,
}

impl<'a> Tokens<'a> {
    fn new(path: &'a Path, text: &'a str) -> Self {
        Tokens {
            path,
            lines: text.lines().enumerate().peekable(),
            pending: Default::default(),
            line: 0,
        }
    }

    fn next(&mut self) -> Option<&'a str> {
        while self.pending.is_empty() {
            let (i, l) = self.lines.next()?;
            self.pending
                .extend(l.split_whitespace().map(|t| (i + 1, t)));
        }
        let (line, t) = self.pending.pop_front()?;
        self.line = line;
        Some(t)
    }

    /// The rest of the current line (for names with spaces).
    fn rest_of_line(&mut self) -> Vec<&'a str> {
        let line = self.line;
        let mut out = Vec::new();
        while self.pending.front().is_some_and(|(l, _)| *l == line) {
            out.push(self.pending.pop_front().unwrap().1);
        }
        out
    }

    fn word(&mut self, what: &str) -> Result<&'a str> {
        self.next().ok_or_else(|| {
            err(
                self.path,
                self.line,
                format!("file ends where {what} should be"),
            )
        })
    }

    fn num<T: std::str::FromStr>(&mut self, what: &str) -> Result<T> {
        let w = self.word(what)?;
        w.parse().map_err(|_| {
            err(
                self.path,
                self.line,
                format!("{what}: expected a number, found `{w}`"),
            )
        })
    }

    /// A node coordinate: a finite number (NaN or infinity is an error at its line).
    fn coord(&mut self, what: &str) -> Result<f64> {
        let v: f64 = self.num(what)?;
        if v.is_finite() {
            Ok(v)
        } else {
            Err(err(
                self.path,
                self.line,
                format!("node coordinate {what} is `{v}`, not a finite number"),
            ))
        }
    }

    /// Nodes per element of Gmsh type `ty`, or an error naming the type.
    fn nodes_of_type(&self, ty: usize) -> Result<usize> {
        gmsh_type(ty).map(|t| t.1).ok_or_else(|| {
            err(
                self.path,
                self.line,
                format!("Gmsh element type {ty} is not read by hertz"),
            )
        })
    }

    fn expect(&mut self, end: &str) -> Result<()> {
        match self.next() {
            Some(w) if w == end => Ok(()),
            Some(w) => Err(err(
                self.path,
                self.line,
                format!("expected `{end}`, found `{w}`"),
            )),
            None => Err(err(
                self.path,
                self.line,
                format!("file ends before `{end}`"),
            )),
        }
    }
}

/// Nodes per Gmsh element type hertz reads (dimension, nodes); None for other types.
fn gmsh_type(t: usize) -> Option<(usize, usize, &'static str)> {
    Some(match t {
        1 => (1, 2, "2-node line"),
        2 => (2, 3, "3-node triangle"),
        3 => (2, 4, "4-node quadrangle"),
        4 => (3, 4, "4-node tetrahedron"),
        5 => (3, 8, "8-node hexahedron"),
        6 => (3, 6, "6-node prism"),
        8 => (1, 3, "3-node line"),
        9 => (2, 6, "6-node triangle"),
        10 => (2, 9, "9-node quadrangle"),
        11 => (3, 10, "10-node tetrahedron"),
        15 => (0, 1, "point"),
        16 => (2, 8, "8-node quadrangle"),
        17 => (3, 20, "20-node hexahedron"),
        18 => (3, 15, "15-node prism"),
        _ => return None,
    })
}

/// `$Entities` (format 4.1): each entity's physical tags.
fn read_entities(
    t: &mut Tokens,
    entity_physical: &mut HashMap<(usize, usize), Vec<usize>>,
) -> Result<()> {
    let counts: Vec<usize> = (0..4)
        .map(|_| t.num("an entity count"))
        .collect::<Result<_>>()?;
    for (dim, &count) in counts.iter().enumerate() {
        for _ in 0..count {
            let tag: usize = t.num("an entity tag")?;
            let n_box = if dim == 0 { 3 } else { 6 };
            for _ in 0..n_box {
                t.num::<f64>("an entity bounding box")?;
            }
            let n_phys: usize = t.num("the number of physical tags")?;
            let phys = (0..n_phys)
                .map(|_| {
                    t.num::<i64>("a physical tag")
                        .map(|p| p.unsigned_abs() as usize)
                })
                .collect::<Result<Vec<_>>>()?;
            entity_physical.insert((dim, tag), phys);
            if dim > 0 {
                let n_b: usize = t.num("the number of bounding entities")?;
                for _ in 0..n_b {
                    t.num::<i64>("a bounding entity")?;
                }
            }
        }
    }
    t.expect("$EndEntities")?;
    Ok(())
}

/// `$Nodes` in format 2.2.
fn read_nodes_v2(t: &mut Tokens, mesh: &mut RawMesh) -> Result<()> {
    let n: usize = t.num("the number of nodes")?;
    for _ in 0..n {
        let tag = t.num("a node tag")?;
        let x = [t.coord("x")?, t.coord("y")?, t.coord("z")?];
        mesh.nodes.push((tag, x));
    }
    t.expect("$EndNodes")?;
    Ok(())
}

/// `$Nodes` in format 4.1: blocks of tags, then their coordinates.
fn read_nodes_v4(t: &mut Tokens, mesh: &mut RawMesh) -> Result<()> {
    let blocks: usize = t.num("the number of node blocks")?;
    let _n: usize = t.num("the number of nodes")?;
    t.num::<usize>("the minimum node tag")?;
    t.num::<usize>("the maximum node tag")?;
    for _ in 0..blocks {
        let _dim: usize = t.num("an entity dimension")?;
        let _tag: usize = t.num("an entity tag")?;
        let parametric: usize = t.num("the parametric flag")?;
        let n: usize = t.num("the nodes in a block")?;
        let tags = (0..n)
            .map(|_| t.num("a node tag"))
            .collect::<Result<Vec<usize>>>()?;
        for tag in tags {
            let x = [t.coord("x")?, t.coord("y")?, t.coord("z")?];
            if parametric == 1 {
                return Err(err(t.path, t.line, "parametric node coordinates are not read; save without them (Mesh.SaveParametric = 0)"));
            }
            mesh.nodes.push((tag, x));
        }
    }
    t.expect("$EndNodes")?;
    Ok(())
}

/// `$Elements` in format 2.2: the physical group is each element's first tag.
fn read_elements_v2(t: &mut Tokens, mesh: &mut RawMesh) -> Result<()> {
    let n: usize = t.num("the number of elements")?;
    for _ in 0..n {
        t.num::<usize>("an element tag")?;
        let ty: usize = t.num("an element type")?;
        let nn = t.nodes_of_type(ty)?;
        let ntags: usize = t.num("the number of element tags")?;
        let tags = (0..ntags)
            .map(|_| t.num::<i64>("an element tag"))
            .collect::<Result<Vec<_>>>()?;
        let physical = tags
            .first()
            .filter(|&&p| p > 0)
            .map(|&p| vec![p as usize])
            .unwrap_or_default();
        let nodes = (0..nn)
            .map(|_| t.num("a node tag"))
            .collect::<Result<Vec<usize>>>()?;
        mesh.elements.push(RawElement {
            gmsh_type: ty,
            physical,
            nodes,
        });
    }
    t.expect("$EndElements")?;
    Ok(())
}

/// `$Elements` in format 4.1: blocks per entity, whose physical groups `entity_physical` gives.
fn read_elements_v4(
    t: &mut Tokens,
    mesh: &mut RawMesh,
    entity_physical: &HashMap<(usize, usize), Vec<usize>>,
) -> Result<()> {
    let blocks: usize = t.num("the number of element blocks")?;
    t.num::<usize>("the number of elements")?;
    t.num::<usize>("the minimum element tag")?;
    t.num::<usize>("the maximum element tag")?;
    for _ in 0..blocks {
        let dim: usize = t.num("an entity dimension")?;
        let tag: usize = t.num("an entity tag")?;
        let ty: usize = t.num("an element type")?;
        let n: usize = t.num("the elements in a block")?;
        let nn = t.nodes_of_type(ty)?;
        let physical = entity_physical
            .get(&(dim, tag))
            .cloned()
            .unwrap_or_default();
        for _ in 0..n {
            t.num::<usize>("an element tag")?;
            let nodes = (0..nn)
                .map(|_| t.num("a node tag"))
                .collect::<Result<Vec<usize>>>()?;
            mesh.elements.push(RawElement {
                gmsh_type: ty,
                physical: physical.clone(),
                nodes,
            });
        }
    }
    t.expect("$EndElements")?;
    Ok(())
}

fn read_raw(path: &Path) -> Result<RawMesh> {
    let bytes = std::fs::read(path).map_err(|e| err(path, 0, format!("cannot read file: {e}")))?;
    let text = std::str::from_utf8(&bytes).map_err(|_| {
        err(
            path,
            0,
            "not ASCII text: binary .msh files are not read; save as ASCII (Gmsh: Mesh.Binary = 0)",
        )
    })?;
    let mut t = Tokens::new(path, text);
    let mut mesh = RawMesh::default();
    let mut version = None;
    // Gmsh 4.1: entity (dim, tag) -> physical tags.
    let mut entity_physical: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
    while let Some(section) = t.next() {
        match section {
            "$MeshFormat" => {
                let v: String = t.word("the format version")?.to_string();
                let file_type: usize = t.num("the file type")?;
                t.num::<usize>("the data size")?;
                if file_type != 0 {
                    return Err(err(
                        path,
                        t.line,
                        "binary .msh files are not read; save as ASCII (Gmsh: Mesh.Binary = 0)",
                    ));
                }
                version = Some(match v.as_str() {
                    "2.2" | "2.1" | "2" => 2,
                    "4.1" => 4,
                    other => {
                        return Err(err(path, t.line, format!("Gmsh format {other} is not read; save as 4.1 or 2.2 (Mesh.MshFileVersion)")))
                    }
                });
                t.expect("$EndMeshFormat")?;
            }
            "$PhysicalNames" => {
                let n: usize = t.num("the number of physical names")?;
                for _ in 0..n {
                    let dim: usize = t.num("a physical dimension")?;
                    let tag: usize = t.num("a physical tag")?;
                    let name = t.rest_of_line().join(" ").trim_matches('"').to_string();
                    mesh.names.insert((dim, tag), name);
                }
                t.expect("$EndPhysicalNames")?;
            }
            "$Entities" if version == Some(4) => read_entities(&mut t, &mut entity_physical)?,
            "$Nodes" => match version {
                Some(2) => read_nodes_v2(&mut t, &mut mesh)?,
                Some(4) => read_nodes_v4(&mut t, &mut mesh)?,
                _ => return Err(err(path, t.line, "$Nodes before $MeshFormat")),
            },
            "$Elements" => match version {
                Some(2) => read_elements_v2(&mut t, &mut mesh)?,
                Some(4) => read_elements_v4(&mut t, &mut mesh, &entity_physical)?,
                _ => return Err(err(path, t.line, "$Elements before $MeshFormat")),
            },
            s if s.starts_with('$') && !s.starts_with("$End") => {
                // Sections hertz does not need ($Periodic, $NodeData, ...): skip to their end.
                let end = format!("$End{}", &s[1..]);
                while t.next().is_some_and(|w| w != end) {}
            }
            other => {
                return Err(err(
                    path,
                    t.line,
                    format!("expected a section such as $Nodes, found `{other}`"),
                ))
            }
        }
    }
    if version.is_none() {
        return Err(err(
            path,
            0,
            "no $MeshFormat section: is this a Gmsh .msh file?",
        ));
    }
    Ok(mesh)
}

/// hertz element type and node order (hertz node a = Gmsh node `order[a]`) of a Gmsh element.
fn hertz_element(
    type_number: usize,
    plane: Plane,
) -> std::result::Result<(ElementType, &'static [usize]), String> {
    use ElementType as E;
    Ok(match (type_number, plane) {
        (2, Plane::Stress) => (E::TrPlaneStress2d, &[0, 1, 2]),
        (2, Plane::Strain) => (E::TrPlaneStrain, &[0, 1, 2]),
        (3, Plane::Stress) => (E::PlaneStress2d, &[0, 1, 2, 3]),
        (3, Plane::Strain) => (E::Quad1PlaneStrain, &[0, 1, 2, 3]),
        (9, Plane::Stress) => (E::QTrPlaneStress2d, &[0, 1, 2, 3, 4, 5]),
        (9, Plane::Strain) => (E::QTrPlaneStrain, &[0, 1, 2, 3, 4, 5]),
        (16, Plane::Stress) => (E::QPlaneStress2d, &[0, 1, 2, 3, 4, 5, 6, 7]),
        (16, Plane::Strain) => (E::QPlaneStrain, &[0, 1, 2, 3, 4, 5, 6, 7]),
        (2, Plane::Axisymmetric) => (E::Axisymm3d, &[0, 1, 2]),
        (3, Plane::Axisymmetric) => (E::L4Axisymm, &[0, 1, 2, 3]),
        (16, Plane::Axisymmetric) => (E::Q4Axisymm, &[0, 1, 2, 3, 4, 5, 6, 7]),
        (9, Plane::Axisymmetric) => {
            return Err(
                "6-node triangles have no axisymmetric element (OOFEM has none): mesh \
                        the section with quadrilaterals (`Mesh.RecombineAll = 1`) or linear \
                        triangles"
                    .into(),
            )
        }
        (4, _) => (E::LTRSpace, &[1, 2, 3, 0]),
        // Gmsh's hexahedron starts on its bottom face, OOFEM's LSpace on its top face.
        (5, _) => (E::LSpace, &[4, 7, 6, 5, 0, 3, 2, 1]),
        (6, _) => (E::LWedge, &[0, 1, 2, 3, 4, 5]),
        // Corners as type 4; Gmsh's mid-edge nodes 4..9 lie on its edges 0–1, 1–2, 2–0, 3–0,
        // 3–2, 3–1 (its 8 and 9 are swapped against VTK's).
        (11, _) => (E::QTRSpace, &[1, 2, 3, 0, 5, 8, 9, 4, 6, 7]),
        // Corners as type 5; Gmsh's mid-edge nodes 8..19 lie on its edges 0–1, 0–3, 0–4, 1–2,
        // 1–5, 2–3, 2–6, 3–7, 4–5, 4–7, 5–6, 6–7.
        (17, _) => (
            E::QSpace,
            &[
                4, 7, 6, 5, 0, 3, 2, 1, 17, 19, 18, 16, 9, 13, 11, 8, 10, 15, 14, 12,
            ],
        ),
        (t, _) => {
            let name = gmsh_type(t).map_or("this element", |x| x.2);
            return Err(format!(
                "hertz has no {name} element (Gmsh type {t}); mesh with first-order elements \
                 (Mesh.ElementOrder = 1), or second-order triangles and 8-node quadrangles \
                 (Mesh.ElementOrder = 2, Mesh.SecondOrderIncomplete = 1) in 2D, or second-order \
                 tetrahedra and 20-node hexahedra (Mesh.ElementOrder = 2, \
                 Mesh.SecondOrderIncomplete = 1) in 3D"
            ));
        }
    })
}

/// The set of physical group (`dim`, `physical`), created empty on first use.
fn group<'g>(
    groups: &'g mut BTreeMap<(usize, usize), GroupSet>,
    names: &BTreeMap<(usize, usize), String>,
    dim: usize,
    physical: usize,
) -> &'g mut GroupSet {
    groups.entry((dim, physical)).or_insert_with(|| GroupSet {
        number: 0,
        name: names.get(&(dim, physical)).cloned().unwrap_or_default(),
        dim,
        physical,
        elements: vec![],
        boundaries: vec![],
        nodes: vec![],
    })
}

/// Read `path` and convert it (see the module doc).
pub fn convert(path: &Path, plane: Plane) -> Result<Converted> {
    let raw = read_raw(path)?;
    let dim = raw
        .elements
        .iter()
        .filter_map(|e| gmsh_type(e.gmsh_type).map(|t| t.0))
        .max()
        .unwrap_or(0);
    if dim < 2 {
        return Err(err(path, 0, "the mesh has no 2D or 3D elements"));
    }
    let (coords, node_index) = mesh_nodes(path, &raw, dim)?;
    let index = |tag: usize| {
        node_index.get(&tag).copied().ok_or_else(|| {
            err(
                path,
                0,
                format!("an element refers to node {tag}, which is not in $Nodes"),
            )
        })
    };
    let mut groups: BTreeMap<(usize, usize), GroupSet> = BTreeMap::new();
    let (elements, n_flipped) =
        mesh_elements(path, &raw, dim, plane, &coords, &index, &mut groups)?;
    boundary_groups(path, &raw, dim, &elements, &index, &mut groups)?;
    let mut sets: Vec<GroupSet> = groups.into_values().collect();
    // Mesh-dimension groups first, then boundaries, then lower groups: stable numbering.
    sets.sort_by_key(|g| (std::cmp::Reverse(g.dim), g.physical));
    for (i, s) in sets.iter_mut().enumerate() {
        s.number = i + 1;
        s.nodes.sort_unstable();
        s.nodes.dedup();
        s.boundaries.sort_unstable();
        s.boundaries.dedup();
    }
    Ok(Converted {
        dim,
        coords,
        elements,
        sets,
        n_flipped,
        nlgeo: false,
    })
}

/// Each Gmsh node tag's index among the converted nodes.
type NodeIndex = HashMap<usize, usize>;

/// The mesh's nodes (in the plane z = 0 for a 2D mesh, each tag once) and each tag's index.
fn mesh_nodes(path: &Path, raw: &RawMesh, dim: usize) -> Result<(Vec<[f64; 3]>, NodeIndex)> {
    let mut node_index = HashMap::with_capacity(raw.nodes.len());
    let mut coords = Vec::with_capacity(raw.nodes.len());
    for (tag, x) in &raw.nodes {
        if dim == 2 && x[2] != 0.0 {
            return Err(err(
                path,
                0,
                format!(
                    "node {tag} has z = {}: a 2D mesh must lie in the plane z = 0",
                    x[2]
                ),
            ));
        }
        if node_index.insert(*tag, coords.len()).is_some() {
            return Err(err(path, 0, format!("node {tag} is defined twice")));
        }
        coords.push(*x);
    }
    Ok((coords, node_index))
}

/// The elements of the mesh's dimension in hertz's node order (mirrored where their Jacobian is
/// negative: how many were is returned too), each in its physical groups.
#[allow(clippy::type_complexity)]
fn mesh_elements(
    path: &Path,
    raw: &RawMesh,
    dim: usize,
    plane: Plane,
    coords: &[[f64; 3]],
    index: &dyn Fn(usize) -> Result<usize>,
    groups: &mut BTreeMap<(usize, usize), GroupSet>,
) -> Result<(Vec<(ElementType, Vec<usize>)>, usize)> {
    let mut elements = Vec::new();
    let mut n_flipped = 0;
    for e in raw
        .elements
        .iter()
        .filter(|e| gmsh_type(e.gmsh_type).unwrap().0 == dim)
    {
        let (etype, order) = hertz_element(e.gmsh_type, plane).map_err(|m| err(path, 0, m))?;
        let mut nodes: Vec<usize> = order
            .iter()
            .map(|&g| index(e.nodes[g]))
            .collect::<Result<_>>()?;
        let x: Vec<[f64; 3]> = nodes.iter().map(|&n| coords[n]).collect();
        let det = det_j_at_centre(etype.shape(), &x);
        if det < 0.0 {
            nodes = etype.shape().mirror().iter().map(|&a| nodes[a]).collect();
            n_flipped += 1;
        } else if det == 0.0 {
            return Err(err(
                path,
                0,
                format!(
                    "a {} element is degenerate (zero area or volume)",
                    etype.name()
                ),
            ));
        }
        for &p in &e.physical {
            group(groups, &raw.names, dim, p)
                .elements
                .push(elements.len());
        }
        elements.push((etype, nodes));
    }
    Ok((elements, n_flipped))
}

/// The lower-dimensional physical groups: boundary elements as (element, boundary) pairs of the
/// mesh's elements (keyed by their sorted corner nodes), lower ones as nodes.
fn boundary_groups(
    path: &Path,
    raw: &RawMesh,
    dim: usize,
    elements: &[(ElementType, Vec<usize>)],
    index: &dyn Fn(usize) -> Result<usize>,
    groups: &mut BTreeMap<(usize, usize), GroupSet>,
) -> Result<()> {
    let corners = |nodes: &[usize], shape_nodes: usize| -> Vec<usize> {
        let mut c: Vec<usize> = nodes[..shape_nodes].to_vec();
        c.sort_unstable();
        c
    };
    let mut boundary_of: HashMap<Vec<usize>, (usize, usize)> = HashMap::new();
    for (ei, (etype, nodes)) in elements.iter().enumerate() {
        for (b, local) in etype.shape().boundaries().iter().enumerate() {
            // Quadratic elements: an edge is keyed by its two corners, a face by its three.
            let n_corner = match etype.shape() {
                Shape::Quad8 | Shape::Tri6 => 2,
                Shape::Tet10 => 3,
                Shape::Hexa20 => 4,
                _ => local.len(),
            };
            let global: Vec<usize> = local.iter().map(|&a| nodes[a]).collect();
            boundary_of.insert(corners(&global, n_corner), (ei, b + 1));
        }
    }
    for e in raw.elements.iter().filter(|e| !e.physical.is_empty()) {
        let edim = gmsh_type(e.gmsh_type).unwrap().0;
        if edim == dim {
            continue;
        }
        let nodes: Vec<usize> = e.nodes.iter().map(|&t| index(t)).collect::<Result<_>>()?;
        for &p in &e.physical {
            let g = group(groups, &raw.names, edim, p);
            if edim + 1 == dim {
                let n_corner = match e.gmsh_type {
                    8 => 2,
                    9 if dim == 3 => 3,
                    16 if dim == 3 => 4,
                    9 | 16 | 10 => return Err(err(path, 0, "second-order boundary elements in a physical group: hertz reads them only as 3-node lines (Gmsh type 8) on the edges of 6-node triangles and 8-node quadrangles, and as 6-node triangles and 8-node quadrangles (types 9, 16) on the faces of 10-node tetrahedra and 20-node hexahedra")),
                    _ => nodes.len(),
                };
                let key = corners(&nodes, n_corner);
                let found = boundary_of.get(&key).copied().ok_or_else(|| {
                    err(path, 0, format!(
                        "physical group {p} has a boundary element on nodes {:?} that is no boundary of a {dim}D element",
                        e.nodes
                    ))
                })?;
                g.boundaries.push(found);
            } else {
                g.nodes.extend(nodes.iter().copied());
            }
        }
    }
    Ok(())
}

impl Converted {
    /// The counts to put in the counts record.
    pub fn counts(&self) -> String {
        format!(
            "ndofman {} nelem {} nset {}",
            self.coords.len(),
            self.elements.len(),
            self.sets.len()
        )
    }

    /// The OOFEM records: nodes, elements, sets (each a line, numbered from 1).
    pub fn records(&self) -> Vec<String> {
        let mut out = Vec::with_capacity(self.coords.len() + self.elements.len() + self.sets.len());
        for (i, x) in self.coords.iter().enumerate() {
            out.push(if self.dim == 2 {
                format!("Node {} coords 2 {} {}", i + 1, x[0], x[1])
            } else {
                format!("Node {} coords 3 {} {} {}", i + 1, x[0], x[1], x[2])
            });
        }
        for (i, (etype, nodes)) in self.elements.iter().enumerate() {
            let list: Vec<String> = nodes.iter().map(|n| (n + 1).to_string()).collect();
            out.push(format!(
                "{} {} nodes {} {}{}",
                etype.name(),
                i + 1,
                nodes.len(),
                list.join(" "),
                if self.nlgeo { " nlgeo 1" } else { "" }
            ));
        }
        for s in &self.sets {
            let mut r = format!("Set {}", s.number);
            if !s.elements.is_empty() {
                let l: Vec<String> = s.elements.iter().map(|e| (e + 1).to_string()).collect();
                r += &format!(" elements {} {}", l.len(), l.join(" "));
            }
            if !s.boundaries.is_empty() {
                let l: Vec<String> = s
                    .boundaries
                    .iter()
                    .map(|(e, b)| format!("{} {b}", e + 1))
                    .collect();
                r += &format!(" elementboundaries {} {}", 2 * l.len(), l.join(" "));
            }
            if !s.nodes.is_empty() {
                let l: Vec<String> = s.nodes.iter().map(|n| (n + 1).to_string()).collect();
                r += &format!(" nodes {} {}", l.len(), l.join(" "));
            }
            if self.writes_name(s) {
                r += &format!(" name \"{}\"", s.name);
            }
            out.push(r);
        }
        out
    }

    /// Whether set `s`'s record names it (hertz's `name`): a physical group's name that no
    /// other group has, that is not a number and holds no quote or control character.
    fn writes_name(&self, s: &GroupSet) -> bool {
        let n = &s.name;
        !n.is_empty()
            && n.parse::<f64>().is_err()
            && !n.chars().any(|c| c == '"' || c.is_control())
            && self.sets.iter().filter(|t| &t.name == n).count() == 1
    }

    /// One line per set: number, name, what it holds.
    pub fn set_summary(&self) -> Vec<String> {
        self.sets
            .iter()
            .map(|s| {
                let what = if !s.elements.is_empty() {
                    format!("{} elements", s.elements.len())
                } else if !s.boundaries.is_empty() {
                    format!(
                        "{} element {}",
                        s.boundaries.len(),
                        if self.dim == 2 { "edges" } else { "faces" }
                    )
                } else {
                    format!("{} nodes", s.nodes.len())
                };
                let name = if s.name.is_empty() {
                    "(no name)".to_string()
                } else {
                    format!("\"{}\"", s.name)
                };
                format!(
                    "set {} = physical group {} {name} ({}D): {what}",
                    s.number, s.physical, s.dim
                )
            })
            .collect()
    }

    /// The `@include`-able fragment: a comment header (the counts, the sets) and the records.
    pub fn fragment(&self, source: &Path) -> String {
        let mut out = format!(
            "{FRAGMENT_MARK}{} from {}: {} nodes, {} elements{}.\n\
             # Counts record: {}\n\
             # Nodes, elements and sets follow in this order: @include this file after the counts\n\
             # record; further sets of your own come right after the @include, numbered on.\n",
            env!("CARGO_PKG_VERSION"),
            source.display(),
            self.coords.len(),
            self.elements.len(),
            match self.n_flipped {
                0 => String::new(),
                n => format!(" ({n} mirrored to a positive Jacobian)"),
            },
            self.counts()
        );
        for l in self.set_summary() {
            out += &format!("# {l}\n");
        }
        for r in self.records() {
            out += &r;
            out.push('\n');
        }
        out
    }
}

impl Converted {
    /// Write the records to `out` (see [`Converted::fragment`]; `mesh` the mesh they come
    /// from), whole or not at all, and only where no file is or over a fragment hertz wrote:
    /// never over the mesh, an input or any other file of the user's.
    pub fn write_fragment(&self, out: &Path, mesh: &Path) -> Result<()> {
        refuse_to_overwrite_a_users_file(out, mesh)?;
        crate::output::write_atomic(out, self.fragment(mesh).as_bytes())
    }
}

//! Helpers shared by the integration tests.
#![allow(dead_code)] // each test binary uses a part of them

use hertz::model::Model;
use std::path::{Path, PathBuf};

/// A scratch directory under the system's temporary directory, `hertz-TAG-PID`: emptied when
/// made, removed when dropped (also when the test fails).
pub struct Scratch(PathBuf);

impl std::ops::Deref for Scratch {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<Path> for Scratch {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// The scratch directory `hertz-{tag}-{pid}` (not created).
pub fn scratch(tag: &str) -> Scratch {
    let d = std::env::temp_dir().join(format!("hertz-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    Scratch(d)
}

/// Read a model from input text held in memory (named `test.in` in messages).
pub fn model_from_text(text: &str) -> hertz::error::Result<Model> {
    hertz::input::read_model_str(text, "test.in").map(|r| r.model)
}

/// Solver settings of the tests: the defaults (the library prints nothing).
pub fn quiet() -> hertz::solve::SolveParams {
    hertz::solve::SolveParams::default()
}

/// Solve the input file `path`; return its model, the last step's contact states and residual
/// history (iteration 0 first).
pub fn solve_contact(path: &std::path::Path) -> (Model, Vec<hertz::contact::SlotState>, Vec<f64>) {
    let model = hertz::input::read_model(path).unwrap().model;
    let (states, history) = solve_model(&model);
    (model, states, history)
}

/// Solve `model` quietly; return the last step's contact states and residual history.
pub fn solve_model(model: &Model) -> (Vec<hertz::contact::SlotState>, Vec<f64>) {
    let mut out = (Vec::new(), Vec::new());
    hertz::solve::run_analysis(model, &quiet(), |r| {
        out = (r.contact.to_vec(), r.info.residual_history.clone());
        Ok(())
    })
    .unwrap();
    out
}

/// A strip of `nm` unit elements (Q4 or Q8) side by side whose top edges form the master segment,
/// and a slave quad above it whose bottom-left node (label `s`, printed first) is the contact
/// node at (sx, sy).
pub fn strip(
    kind: &str,
    nlgeo: u8,
    nm: usize,
    (sx, sy): (f64, f64),
    segment: Option<&str>,
    condition: &str,
) -> String {
    let q8 = kind == "q8";
    let mut nodes = Vec::new();
    let mut elems = Vec::new();
    let id = |i: usize, j: usize| 1 + j * (nm + 1) + i;
    for j in 0..2 {
        for i in 0..=nm {
            // A slightly wavy top so that vertex normals are averages of different edge normals.
            let y = if j == 1 {
                1.0 + 0.03 * (i as f64 * 1.7).sin()
            } else {
                0.0
            };
            nodes.push(format!("node {} coords 2 {i} {y}", id(i, j)));
        }
    }
    let mut next = 2 * (nm + 1) + 1;
    let mut edges = Vec::new();
    for i in 0..nm {
        let c = [id(i + 1, 1), id(i, 1), id(i, 0), id(i + 1, 0)];
        if q8 {
            let mids: Vec<usize> = (0..4).map(|k| next + k).collect();
            let xy = |n: usize| -> (f64, f64) {
                let (ii, jj) = ((n - 1) % (nm + 1), (n - 1) / (nm + 1));
                let y = if jj == 1 {
                    1.0 + 0.03 * (ii as f64 * 1.7).sin()
                } else {
                    0.0
                };
                (ii as f64, y)
            };
            for k in 0..4 {
                let (a, b) = (xy(c[k]), xy(c[(k + 1) % 4]));
                let bulge = if k == 0 { 0.02 } else { 0.0 };
                nodes.push(format!(
                    "node {} coords 2 {} {}",
                    mids[k],
                    0.5 * (a.0 + b.0),
                    0.5 * (a.1 + b.1) + bulge
                ));
            }
            next += 4;
            elems.push(format!(
                "QPlaneStress2d {} nodes 8 {} {} {} {} {} {} {} {} nlgeo {nlgeo}",
                i + 1,
                c[0],
                c[1],
                c[2],
                c[3],
                mids[0],
                mids[1],
                mids[2],
                mids[3]
            ));
        } else {
            elems.push(format!(
                "Quad1PlaneStrain {} nodes 4 {} {} {} {} nlgeo {nlgeo}",
                i + 1,
                c[0],
                c[1],
                c[2],
                c[3]
            ));
        }
        edges.push(format!("{} 1", i + 1));
    }
    let s = next;
    for (k, (dx, dy)) in [(0.0, 0.0), (0.6, 0.0), (0.6, 1.0), (0.0, 1.0)]
        .iter()
        .enumerate()
    {
        nodes.push(format!("node {} coords 2 {} {}", s + k, sx + dx, sy + dy));
    }
    elems.push(format!(
        "Quad1PlaneStrain {} nodes 4 {} {} {} {}",
        nm + 1,
        s + 2,
        s + 3,
        s,
        s + 1
    ));
    let extra_node = segment.is_some_and(|g| g.contains(" node 900"));
    if extra_node {
        nodes.push("node 900 coords 2 0.3 5.0".into());
    }
    let segment = segment
        .map(str::to_string)
        .unwrap_or_else(|| "linear2delementedgecontactsegment 1 edgeset 2".to_string());
    let condition = condition.replace("NODE", &s.to_string());
    format!(
        "fd.out\nfd\nNonLinearStatic nsteps 1 controlmode 1\ndomain {}\nOutputManager\n\
         ndofman {} nelem {} ncrosssect 1 nmat 1 nbc 1 nic 0 nltf 1 nset 2 ncontactseg 1\n{}\n{}\n{segment}\n\
         SimpleCS 1 thick 1 material 1 set 1\nIsoLE 1 d 0 E 100 n 0.3 tAlpha 0\n{condition}\n\
         ConstantFunction 1 f(t) 1\nSet 1 allelements\nSet 2 elementboundaries {} {}\n",
        if q8 { "2dPlaneStress" } else { "PlaneStrain" },
        nodes.len(),
        elems.len(),
        nodes.join("\n"),
        elems.join("\n"),
        2 * edges.len(),
        edges.join(" ")
    )
}

pub const PEN: &str =
    "n2spenaltycontact 1 loadTimeFunction 1 penalty 1000 nodeset 1 NODE segmentset 1 1";
pub const LM: &str =
    "n2slagrangianmultipliercontact 1 loadTimeFunction 1 nodeset 1 NODE segmentset 1 1";

/// The contact node: the `NODE` substituted into the condition, read back from the nodeset.
pub fn label_of_slave(text: &str) -> usize {
    let line = text.lines().find(|l| l.contains("nodeset 1 ")).unwrap();
    let after = line.split("nodeset 1 ").nth(1).unwrap();
    after.split_whitespace().next().unwrap().parse().unwrap()
}

/// A 3D face case: a 2×2×1 master block of `kind` elements (cube symmetry `sym`) on [0, 2]² ×
/// [0, 1] with a wavy top whose faces form the master segment, and a 2×2 slave brick block above
/// whose bottom nodes are the contact nodes; its middle bottom node (the returned label) is at
/// `pos`, the others 0.25 away in x and y.
pub fn face_input(
    kind: hertz_bench::mesh::Solid,
    sym: usize,
    nlgeo: u8,
    pos: [f64; 3],
    condition: &str,
) -> (String, usize) {
    face_input_of(kind, false, sym, nlgeo, pos, condition)
}

/// [`face_input`], the master's elements quadratic if `quadratic` (QTRSpace, QSpace): its top
/// faces curved, the mid-side nodes on the wavy surface too, off the chords.
pub fn face_input_of(
    kind: hertz_bench::mesh::Solid,
    quadratic: bool,
    sym: usize,
    nlgeo: u8,
    pos: [f64; 3],
    condition: &str,
) -> (String, usize) {
    let mut inp = hertz_bench::mesh::Input::default();
    let extra = format!("mat 1 crossSect 1 nlgeo {nlgeo}");
    let g = hertz_bench::mesh::uniform(0.0, 2.0, 2);
    let master = inp.solid3d(
        kind,
        &g,
        &g,
        &hertz_bench::mesh::uniform(0.0, 1.0, 1),
        &extra,
        sym,
    );
    let mut top = master.top.clone();
    if quadratic {
        let mids = inp.make_quadratic(master.elements);
        top.extend(mids.into_iter().filter(|&n| inp.nodes[n - 1][2] > 0.99));
    }
    for &n in &top {
        let p = &mut inp.nodes[n - 1];
        p[2] += 0.05 * (1.3 * p[0] + 0.7 * p[1]).sin();
    }
    let faces = inp.faces_where(&master, &|p| p[2] > 0.5);
    let around = |c: f64| vec![c - 0.25, c, c + 0.25];
    let slave = inp.block3d(
        &around(pos[0]),
        &around(pos[1]),
        &[pos[2], pos[2] + 0.3],
        &extra,
    );
    inp.sections.push("SimpleCS 1".into());
    inp.materials
        .push("IsoLE 1 d 0 E 100 n 0.3 tAlpha 0".into());
    let segset = inp.boundary_set(&faces);
    let nodes: Vec<String> = slave.bottom.iter().map(|n| n.to_string()).collect();
    inp.segments.push(format!(
        "linear3delementsurfacecontactsegment 1 boundaryset {segset}"
    ));
    inp.bcs.push(format!(
        "{condition} nodeset {} {} segmentset 1 1",
        nodes.len(),
        nodes.join(" ")
    ));
    inp.functions.push("ConstantFunction 1 f(t) 1".into());
    let text = inp.render("fd3", "NonLinearStatic nsteps 1 controlmode 1", "3d");
    (text, slave.bottom[4])
}

/// Run the input file `path` writing its outputs (into `out_dir`, else next to it) with VTU
/// arrays in `format`; the last `.vtu` written.
pub fn run_writing_vtu(
    path: &std::path::Path,
    out_dir: Option<std::path::PathBuf>,
    vtu_format: hertz::output::vtu::VtuFormat,
) -> std::path::PathBuf {
    let report = hertz::app::run_file(
        path,
        &hertz::app::RunOptions {
            write_outputs: true,
            out_dir,
            vtu_format,
            ..Default::default()
        },
    )
    .unwrap();
    report
        .written
        .into_iter()
        .rev()
        .find(|p| p.extension().is_some_and(|e| e == "vtu"))
        .expect("a .vtu written")
}

/// The data arrays of a `.vtu` file by name, as doubles, whether written as text or as raw
/// appended binary (`header_type="UInt64"`, little-endian).
pub fn read_vtu(path: &std::path::Path) -> std::collections::BTreeMap<String, Vec<f64>> {
    let bytes = std::fs::read(path).unwrap();
    let marker = b"<AppendedData encoding=\"raw\">";
    let (xml_end, data) = match bytes.windows(marker.len()).position(|w| w == marker) {
        Some(at) => {
            let underscore = at + bytes[at..].iter().position(|&b| b == b'_').unwrap();
            (at, &bytes[underscore + 1..])
        }
        None => (bytes.len(), &bytes[..0]),
    };
    let xml = std::str::from_utf8(&bytes[..xml_end]).unwrap();
    let attr = |tag: &str, key: &str| -> Option<String> {
        let at = tag.find(&format!(" {key}=\""))? + key.len() + 3;
        Some(tag[at..at + tag[at..].find('"')?].to_string())
    };
    let mut arrays = std::collections::BTreeMap::new();
    for piece in xml.split("<DataArray").skip(1) {
        let tag = &piece[..piece.find('>').unwrap()];
        let name = attr(tag, "Name").unwrap();
        let values: Vec<f64> = match attr(tag, "format").as_deref() {
            Some("ascii") => piece[tag.len() + 1..piece.find("</DataArray>").unwrap()]
                .split_whitespace()
                .map(|w| w.parse().unwrap())
                .collect(),
            Some("appended") => {
                let offset: usize = attr(tag, "offset").unwrap().parse().unwrap();
                let len = u64::from_le_bytes(data[offset..offset + 8].try_into().unwrap()) as usize;
                let block = &data[offset + 8..offset + 8 + len];
                match attr(tag, "type").as_deref() {
                    Some("Float64") => block
                        .chunks(8)
                        .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
                        .collect(),
                    Some("Int64") => block
                        .chunks(8)
                        .map(|c| i64::from_le_bytes(c.try_into().unwrap()) as f64)
                        .collect(),
                    Some("UInt8") => block.iter().map(|&b| f64::from(b)).collect(),
                    other => panic!("data type {other:?}"),
                }
            }
            other => panic!("format {other:?}"),
        };
        arrays.insert(name, values);
    }
    arrays
}

/// Two blocks of the same material, [0, 2] x [-1, 0] in `n_low` and [0, 2] x [0, 1] in `n_up`
/// elements across (two rows each), pressed together by a uniform pressure 10 on the top; rollers
/// on x = 0 and under the bottom. `condition` is the contact record: `SLAVE` is the upper
/// block's bottom edges (segment 1) and its nodes (set 4), `MASTER` the lower block's top edges
/// (segment 2).
pub fn mortar_blocks(n_low: usize, n_up: usize, nlgeo: u8, condition: &str) -> String {
    let mut nodes = Vec::new();
    let mut elems = Vec::new();
    let mut id = 0;
    let mut grid = |nx: usize, y0: f64, nodes: &mut Vec<String>| -> Vec<Vec<usize>> {
        (0..=2)
            .map(|j| {
                (0..=nx)
                    .map(|i| {
                        id += 1;
                        nodes.push(format!(
                            "node {id} coords 2 {} {}",
                            2.0 * i as f64 / nx as f64,
                            y0 + 0.5 * j as f64
                        ));
                        id
                    })
                    .collect()
            })
            .collect()
    };
    let low = grid(n_low, -1.0, &mut nodes);
    let up = grid(n_up, 0.0, &mut nodes);
    let quads = |g: &Vec<Vec<usize>>, mat: usize, elems: &mut Vec<String>| -> Vec<usize> {
        let mut row = Vec::new();
        for j in 0..2 {
            for i in 0..g[0].len() - 1 {
                let e = elems.len() + 1;
                elems.push(format!(
                    "PlaneStress2d {e} nodes 4 {} {} {} {} crossSect 1 mat {mat} nlgeo {nlgeo}",
                    g[j][i],
                    g[j][i + 1],
                    g[j + 1][i + 1],
                    g[j + 1][i]
                ));
                row.push(e);
            }
        }
        row
    };
    let el_low = quads(&low, 1, &mut elems);
    let el_up = quads(&up, 1, &mut elems);
    blocks_input(&nodes, &elems, (&low, &el_low), (&up, &el_up), condition)
}

/// `mortar_blocks` in 8-node quadrilaterals (QPlaneStress2d): the contact edges are quadratic.
pub fn mortar_blocks_q8(n_low: usize, n_up: usize, nlgeo: u8, condition: &str) -> String {
    let mut nodes = Vec::new();
    let mut elems = Vec::new();
    let mut id = 0;
    // Node ids on the half-spacing grid (none at element centres), rows j = 0..=4.
    let mut grid = |nx: usize, y0: f64, nodes: &mut Vec<String>| -> Vec<Vec<usize>> {
        (0..=4)
            .map(|j| {
                (0..=2 * nx)
                    .map(|i| {
                        if i % 2 == 1 && j % 2 == 1 {
                            return 0;
                        }
                        id += 1;
                        nodes.push(format!(
                            "node {id} coords 2 {} {}",
                            i as f64 / nx as f64,
                            y0 + 0.25 * j as f64
                        ));
                        id
                    })
                    .collect()
            })
            .collect()
    };
    let low = grid(n_low, -1.0, &mut nodes);
    let up = grid(n_up, 0.0, &mut nodes);
    let quads = |g: &Vec<Vec<usize>>, elems: &mut Vec<String>| -> Vec<usize> {
        let mut row = Vec::new();
        for j in (0..4).step_by(2) {
            for i in (0..g[0].len() - 1).step_by(2) {
                let e = elems.len() + 1;
                elems.push(format!(
                    "QPlaneStress2d {e} nodes 8 {} {} {} {} {} {} {} {} crossSect 1 mat 1 nlgeo {nlgeo}",
                    g[j][i],
                    g[j][i + 2],
                    g[j + 2][i + 2],
                    g[j + 2][i],
                    g[j][i + 1],
                    g[j + 1][i + 2],
                    g[j + 2][i + 1],
                    g[j + 1][i]
                ));
                row.push(e);
            }
        }
        row
    };
    let el_low = quads(&low, &mut elems);
    let el_up = quads(&up, &mut elems);
    blocks_input(&nodes, &elems, (&low, &el_low), (&up, &el_up), condition)
}

/// The input of `mortar_blocks`: nodes and elements, each block's node grid (rows bottom to top,
/// 0 where no node) and its elements (the bottom row's first), and the contact record.
/// Elements' edges: 1 bottom, 3 top.
fn blocks_input(
    nodes: &[String],
    elems: &[String],
    (low, el_low): (&[Vec<usize>], &[usize]),
    (up, el_up): (&[Vec<usize>], &[usize]),
    condition: &str,
) -> String {
    let (n_low, n_up) = (el_low.len() / 2, el_up.len() / 2);
    let edges = |els: &[usize], k: usize| -> String {
        els.iter()
            .map(|e| format!("{e} {k}"))
            .collect::<Vec<_>>()
            .join(" ")
    };
    let join = |v: &[usize]| {
        v.iter()
            .map(|x| x.to_string())
            .collect::<Vec<_>>()
            .join(" ")
    };
    let left: Vec<usize> = low.iter().chain(up).map(|r| r[0]).collect();
    format!(
        "mortar_patch.out\npatch\nStaticStructural nsteps 1 rtolf 1e-12 maxiter 20\n\
         domain 2dPlaneStress\nOutputManager\n\
         ndofman {} nelem {} ncrosssect 1 nmat 1 nbc 4 nic 0 nltf 1 nset 7 ncontactseg 2\n\
         {}\n{}\n\
         linear2delementedgecontactsegment 1 edgeset 1\n\
         linear2delementedgecontactsegment 2 edgeset 2\n\
         SimpleCS 1 thick 1.0 material 1 set 3\nIsoLE 1 d 0 E 1000 n 0.3 tAlpha 0\n\
         BoundaryCondition 1 loadTimeFunction 1 dofs 1 1 values 1 0 set 5\n\
         BoundaryCondition 2 loadTimeFunction 1 dofs 1 2 values 1 0 set 6\n\
         ConstantEdgeLoad 3 loadTimeFunction 1 dofs 2 1 2 components 2 0 -10 set 7\n\
         {condition}\nConstantFunction 1 f(t) 1\n\
         Set 1 elementboundaries {} {}\nSet 2 elementboundaries {} {}\nSet 3 allelements\n\
         Set 4 nodes {} {}\nSet 5 nodes {} {}\nSet 6 nodes {} {}\nSet 7 elementedges {} {}\n",
        nodes.len(),
        elems.len(),
        nodes.join("\n"),
        elems.join("\n"),
        2 * n_up,
        edges(&el_up[..n_up], 1),
        2 * n_low,
        edges(&el_low[n_low..], 3),
        up[0].len(),
        join(&up[0]),
        left.len(),
        join(&left),
        low[0].len(),
        join(&low[0]),
        2 * n_up,
        edges(&el_up[n_up..], 3),
    )
}

/// `mortar_blocks` under a uniform pressure `p` and shear `tau` (ν = 0): the top of the upper
/// block carries the traction (τ, −p), the sides of both blocks (0, ∓τ) (left, right), the
/// bottom is clamped. The exact solution is the uniform stress σ_xx = 0, σ_yy = −p, σ_xy = τ in
/// both blocks, the interface carrying a uniform pressure p and a uniform friction traction τ
/// (the upper block held in x by friction alone: τ below μp to stick).
pub fn sheared_blocks(n_low: usize, n_up: usize, p: f64, tau: f64, condition: &str) -> String {
    let text = mortar_blocks(n_low, n_up, 0, condition);
    let lo = 2 * n_low;
    let side = |col: &dyn Fn(usize, usize) -> usize, edge: usize| {
        let mut v = Vec::new();
        for (first, n) in [(0, n_low), (lo, n_up)] {
            for row in 0..2 {
                v.push(format!("{} {edge}", first + col(row, n)));
            }
        }
        v.join(" ")
    };
    let left = side(&|row, n| row * n + 1, 4);
    let right = side(&|row, n| row * n + n, 2);
    text.replace("nbc 4", "nbc 6")
        .replace("nset 7", "nset 9")
        .replace("IsoLE 1 d 0 E 1000 n 0.3", "IsoLE 1 d 0 E 1000 n 0")
        .replace(
            "BoundaryCondition 1 loadTimeFunction 1 dofs 1 1 values 1 0 set 5",
            "BoundaryCondition 1 loadTimeFunction 1 dofs 1 1 values 1 0 set 6",
        )
        .replace(
            "components 2 0 -10 set 7",
            &format!("components 2 {tau} {} set 7", -p),
        )
        .replace(
            "ConstantFunction 1",
            &format!(
                "ConstantEdgeLoad 5 loadTimeFunction 1 dofs 2 1 2 components 2 0 {} set 8\n\
                 ConstantEdgeLoad 6 loadTimeFunction 1 dofs 2 1 2 components 2 0 {tau} set 9\n\
                 ConstantFunction 1",
                -tau
            ),
        )
        + &format!("Set 8 elementedges 8 {left}\nSet 9 elementedges 8 {right}\n")
}

/// A 3D patch input (`hertz_bench::verify::Patch`) with its master faces (segment 1) replaced
/// by the rigid shape `record` (segment 1 as well); a shape moving with `node 999` gets that
/// node at `reference`.
pub fn with_rigid_master(text: &str, record: &str, reference: [f64; 3]) -> String {
    let mut out = String::new();
    let mut nodes = 0;
    for line in text.lines() {
        if line.starts_with("linear3delementsurfacecontactsegment 1 ") {
            out.push_str(record);
        } else if let Some(rest) = line.strip_prefix("ndofman ") {
            let (n, tail) = rest.split_once(' ').unwrap();
            nodes = n.parse::<usize>().unwrap();
            let extra = usize::from(record.contains("node 999"));
            out.push_str(&format!("ndofman {} {tail}", nodes + extra));
        } else {
            out.push_str(line);
        }
        out.push('\n');
        if line.starts_with(&format!("node {nodes} coords")) && record.contains("node 999") {
            let [x, y, z] = reference;
            out.push_str(&format!("node 999 coords 3 {x} {y} {z}\n"));
        }
    }
    out
}

/// The element records of one cell of a structured grid: `c(a, b)` the node at the cell's local
/// position (a, b) ∈ {0, 1, 2}² (1: a mid-side), `corners` 4 (one quadrilateral), 3 (two
/// triangles cut along its diagonal 1–3) or 8 (a quadrilateral with mid-side nodes), numbered
/// from `label` in OOFEM's node order.
pub fn cell_records(
    keyword: &str,
    label: usize,
    corners: usize,
    c: impl Fn(usize, usize) -> usize,
) -> Vec<String> {
    let (n1, n2, n3, n4) = (c(0, 0), c(2, 0), c(2, 2), c(0, 2));
    match corners {
        4 => vec![format!("{keyword} {label} nodes 4 {n1} {n2} {n3} {n4}")],
        3 => vec![
            format!("{keyword} {label} nodes 3 {n1} {n2} {n3}"),
            format!("{keyword} {} nodes 3 {n1} {n3} {n4}", label + 1),
        ],
        _ => vec![format!(
            "{keyword} {label} nodes 8 {n1} {n2} {n3} {n4} {} {} {} {}",
            c(1, 0),
            c(2, 1),
            c(1, 2),
            c(0, 1)
        )],
    }
}

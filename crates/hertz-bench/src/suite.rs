//! The contact robustness suite: the setups people build every day (flush blocks, slave nodes on
//! master vertices and ends, sliding over many vertices and off the end, quadratic edges,
//! unloading, large penalties, touching starts under force control, starting penetration of each
//! rigid shape, large-deformation blocks to 30 % strain, the elastic cylinder at five mesh sizes,
//! 3D), each generated with a penalty and with Lagrange multipliers.
//!
//! `hertz bench --suite` runs them all and prints iterations per step; the tests assert that every
//! one converges with at most 25 iterations per step and no step cut-back, and that the penalty
//! answer equals its multiplier twin within the penalty's own error.

use super::mesh::{graded, uniform, Input, Kind, Solid};
use hertz::error::{Error, Result};
use hertz::solve::{run_analysis, SolveParams};
use std::time::Instant;

/// Young's modulus of the suite's bodies (the slave's may differ).
pub const E: f64 = 1000.0;
const NU: f64 = 0.3;
/// Penalty of most setups: 1000 E.
pub const PENALTY: f64 = 1e6;

/// Contact law of a run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Law {
    Penalty(f64),
    Multiplier,
}

/// One setup: its name, its class, and its input text for a law.
pub struct Setup {
    pub name: String,
    pub class: &'static str,
    /// The penalty of the penalty twin.
    pub penalty: f64,
    /// The order r of the penalty's displacement error, ε^(−r): 1 for nodes held by a force
    /// against a surface; lower where a node is held by the fall of its weight w ≈ 3τ² at the
    /// end of an open master (ε·w·(−g) = its force: r = 1/2, and 1/3 for a node at the master's
    /// corner, g ∝ τ there).
    pub order: f64,
    make: Box<dyn Fn(Law) -> String + Send + Sync>,
}

impl Setup {
    fn new(
        name: impl Into<String>,
        class: &'static str,
        penalty: f64,
        make: impl Fn(Law) -> String + Send + Sync + 'static,
    ) -> Setup {
        Setup {
            name: name.into(),
            class,
            penalty,
            order: 1.0,
            make: Box::new(make),
        }
    }

    /// The factor 10^r − 1 by which the penalty's error is its difference to the ε/10 run
    /// (Richardson's rule for an error ε^(−r)).
    pub fn richardson(&self) -> f64 {
        10f64.powf(self.order) - 1.0
    }

    /// [`twin_mismatch`] of this setup's twins.
    pub fn mismatch(&self, t: &Twins) -> (f64, f64) {
        twin_mismatch(
            self.penalty,
            self.richardson(),
            &t.penalty,
            &t.penalty10,
            &t.multipliers,
        )
    }

    /// The input text of the twin with `law`.
    pub fn input(&self, law: Law) -> String {
        (self.make)(law)
    }
}

/// The contact condition record for a law (node-to-segment).
pub(crate) fn n2s(
    number: usize,
    law: Law,
    nodes: &[usize],
    segments: &[usize],
    extra: &str,
) -> String {
    let list: Vec<String> = nodes.iter().map(|v| v.to_string()).collect();
    let segs: Vec<String> = segments.iter().map(|v| v.to_string()).collect();
    let head = match law {
        Law::Penalty(p) => format!("n2spenaltycontact {number} loadTimeFunction 1 penalty {p:e}"),
        Law::Multiplier => format!("n2slagrangianmultipliercontact {number} loadTimeFunction 1"),
    };
    format!(
        "{head} nodeset {} {} segmentset {} {} {extra}",
        nodes.len(),
        list.join(" "),
        segments.len(),
        segs.join(" ")
    )
}

/// A mortar condition record `number` with `law`: slave segment 2 on master segment 1.
pub(crate) fn s2s(number: usize, law: Law) -> String {
    let head = match law {
        Law::Penalty(p) => format!("s2spenaltycontact {number} loadTimeFunction 1 penalty {p:e}"),
        Law::Multiplier => format!("s2slagrangianmultipliercontact {number} loadTimeFunction 1"),
    };
    format!("{head} slavesegment 2 segmentset 1 1")
}

/// A piecewise-linear load history through the factors `steps` at t = 1, 2, …
pub(crate) fn history(steps: &[f64]) -> String {
    let t: Vec<String> = (0..=steps.len()).map(|i| i.to_string()).collect();
    let f: Vec<String> = std::iter::once(0.0)
        .chain(steps.iter().copied())
        .map(|v| format!("{v}"))
        .collect();
    format!(
        "PiecewiseLinFunction 1 npoints {} t {} {} f(t) {} {}",
        t.len(),
        t.len(),
        t.join(" "),
        f.len(),
        f.join(" ")
    )
}

pub(crate) fn analysis(nsteps: usize) -> String {
    format!("StaticStructural nsteps {nsteps} deltat 1 rtolf 1e-8 maxiter 25")
}

/// How the upper block of [`two_blocks`] is driven.
#[derive(Debug, Clone, Copy)]
enum Drive {
    /// Its top moved down by `down` and sideways by `side` (times the history).
    Displacement { down: f64, side: f64 },
    /// A total downward force on its top (times the history), its top held sideways.
    Force(f64),
}

/// Two blocks of height 1: a master [0, w] × [−1, 0] fixed at its bottom, and a slave
/// [xs0, xs0 + ws] × [gap, gap + 1] on it, node-to-segment from the slave's bottom nodes to the
/// master's top edges.
#[derive(Debug, Clone)]
struct TwoBlocks {
    kind: Kind,
    nx: usize,
    nxs: usize,
    w: f64,
    ws: f64,
    xs0: f64,
    gap: f64,
    e_slave: f64,
    nlgeo: bool,
    drive: Drive,
    steps: Vec<f64>,
    /// Also the master's top nodes on the slave's bottom edges (two-pass).
    two_pass: bool,
}

impl TwoBlocks {
    fn flush(nx: usize) -> TwoBlocks {
        TwoBlocks {
            kind: Kind::Q4,
            nx,
            nxs: nx,
            w: 2.0,
            ws: 2.0,
            xs0: 0.0,
            gap: 0.0,
            e_slave: E,
            nlgeo: false,
            drive: Drive::Displacement {
                down: 0.02,
                side: 0.0,
            },
            steps: vec![1.0],
            two_pass: false,
        }
    }

    fn input(&self, law: Law) -> String {
        let mut inp = Input::default();
        let extra = if self.nlgeo { "nlgeo 1" } else { "" };
        let master = inp.block2d(
            self.kind,
            &uniform(0.0, self.w, self.nx),
            &|_| uniform(-1.0, 0.0, 2),
            &format!("mat 1 crossSect 1 {extra}"),
        );
        let slave = inp.block2d(
            self.kind,
            &uniform(self.xs0, self.xs0 + self.ws, self.nxs),
            &|_| uniform(self.gap, self.gap + 1.0, 2),
            &format!("mat 2 crossSect 1 {extra}"),
        );
        inp.segments.push(format!(
            "linear2delementedgecontactsegment 1 edgeset {}",
            inp.sets.len() + 1
        ));
        inp.boundary_set(&master.top_edges);
        inp.sections.push("SimpleCS 1 thick 1.0".into());
        inp.materials
            .push(format!("IsoLE 1 d 0 E {E} n {NU} tAlpha 0"));
        inp.materials
            .push(format!("IsoLE 2 d 0 E {} n {NU} tAlpha 0", self.e_slave));
        let fixed = inp.node_set(&master.bottom);
        let top = inp.node_set(&slave.top);
        inp.bcs.push(format!(
            "BoundaryCondition 1 loadTimeFunction 2 dofs 2 1 2 values 2 0 0 set {fixed}"
        ));
        match self.drive {
            Drive::Displacement { down, side } => inp.bcs.push(format!(
                "BoundaryCondition 2 loadTimeFunction 1 dofs 2 1 2 values 2 {side} {} set {top}",
                -down
            )),
            Drive::Force(f) => {
                inp.bcs.push(format!(
                    "BoundaryCondition 2 loadTimeFunction 2 dofs 1 1 values 1 0 set {top}"
                ));
                inp.bcs.push(format!(
                    "NodalLoad 4 loadTimeFunction 1 dofs 2 1 2 components 2 0 {} set {top}",
                    -f / slave.top.len() as f64
                ));
            }
        }
        inp.bcs.push(n2s(3, law, &slave.bottom, &[1], ""));
        if self.two_pass {
            inp.segments.push(format!(
                "linear2delementedgecontactsegment 2 edgeset {}",
                inp.sets.len() + 1
            ));
            inp.boundary_set(&slave.bottom_edges);
            let number = inp.bcs.len() + 1;
            inp.bcs.push(n2s(number, law, &master.top, &[2], ""));
        }
        inp.functions.push(history(&self.steps));
        inp.functions.push("ConstantFunction 2 f(t) 1.0".into());
        let domain = if self.kind == Kind::Q8 {
            "2dPlaneStress"
        } else {
            "PlaneStrain"
        };
        inp.render("suite", &analysis(self.steps.len()), domain)
    }
}

/// Node-to-node: two flush blocks with matched meshes, pairs from the master's top to the slave's
/// bottom (2D), or two stacked bricks (3D), the slave's top pushed down.
fn node_to_node(dim: usize, law: Law) -> String {
    let mut inp = Input::default();
    let (master, slave) = if dim == 2 {
        let m = inp.block2d(
            Kind::Q4,
            &uniform(0.0, 2.0, 4),
            &|_| uniform(-1.0, 0.0, 2),
            "mat 1 crossSect 1",
        );
        let s = inp.block2d(
            Kind::Q4,
            &uniform(0.0, 2.0, 4),
            &|_| uniform(0.0, 1.0, 2),
            "mat 1 crossSect 1",
        );
        (m, s)
    } else {
        let g = uniform(0.0, 1.0, 2);
        let m = inp.block3d(&g, &g, &uniform(-1.0, 0.0, 2), "mat 1 crossSect 1");
        let s = inp.block3d(&g, &g, &uniform(0.0, 1.0, 2), "mat 1 crossSect 1");
        (m, s)
    };
    inp.sections.push("SimpleCS 1 thick 1.0".into());
    inp.materials
        .push(format!("IsoLE 1 d 0 E {E} n {NU} tAlpha 0"));
    let fixed = inp.node_set(&master.bottom);
    let top = inp.node_set(&slave.top);
    let list = |v: &[usize]| {
        v.iter()
            .map(|x| x.to_string())
            .collect::<Vec<_>>()
            .join(" ")
    };
    let ms = inp.set(format!(
        "nodes {} {} ordered_nodes",
        master.top.len(),
        list(&master.top)
    ));
    let ss = inp.set(format!(
        "nodes {} {} ordered_nodes",
        slave.bottom.len(),
        list(&slave.bottom)
    ));
    let zeros = vec!["0"; dim].join(" ");
    let dofs = (1..=dim)
        .map(|d| d.to_string())
        .collect::<Vec<_>>()
        .join(" ");
    inp.bcs.push(format!(
        "BoundaryCondition 1 loadTimeFunction 2 dofs {dim} {dofs} values {dim} {zeros} set {fixed}"
    ));
    let down = if dim == 2 { "0 -0.02" } else { "0 0 -0.02" };
    inp.bcs.push(format!(
        "BoundaryCondition 2 loadTimeFunction 1 dofs {dim} {dofs} values {dim} {down} set {top}"
    ));
    let normal = format!(" normal {dim} {}", if dim == 2 { "0 1" } else { "0 0 1" });
    // Matched meshes start touching, so the pairs' normal is given (a hertz extension for the
    // multipliers' record).
    inp.bcs.push(match law {
        Law::Penalty(p) => format!(
            "n2npenaltycontact 3 loadTimeFunction 1 penalty {p:e} masterset {ms} slaveset {ss}{normal}"
        ),
        Law::Multiplier => format!(
            "n2nlagrangianmultipliercontact 3 loadTimeFunction 1 masterset {ms} slaveset {ss}{normal}"
        ),
    });
    inp.functions.push(history(&[1.0]));
    inp.functions.push("ConstantFunction 2 f(t) 1.0".into());
    inp.render(
        "suite",
        &analysis(1),
        if dim == 2 { "PlaneStrain" } else { "3d" },
    )
}

/// A block [0, 2] × [−1, 0] (2D) or [0, 1]² × [−1, 0] (3D) fixed at its bottom, whose top nodes
/// meet the rigid segment `segment` (a record with number 1); the reference node, if the record
/// names node `ref`, is driven down by `down` (times the history).
fn against_rigid(
    dim: usize,
    law: Law,
    segment: &str,
    down: f64,
    steps: &[f64],
    force: Option<f64>,
) -> String {
    let mut inp = Input::default();
    let block = if dim == 2 {
        inp.block2d(
            Kind::Q4,
            &uniform(0.0, 2.0, 8),
            &|_| uniform(-1.0, 0.0, 4),
            "mat 1 crossSect 1",
        )
    } else {
        let g = uniform(0.0, 1.0, 4);
        inp.block3d(&g, &g, &uniform(-1.0, 0.0, 2), "mat 1 crossSect 1")
    };
    let r = if dim == 2 {
        inp.node(1.0, 2.0, 0.0)
    } else {
        inp.node(0.5, 0.5, 2.0)
    };
    inp.segments.push(segment.replace("REF", &r.to_string()));
    inp.sections.push("SimpleCS 1 thick 1.0".into());
    inp.materials
        .push(format!("IsoLE 1 d 0 E {E} n {NU} tAlpha 0"));
    let dofs = (1..=dim)
        .map(|d| d.to_string())
        .collect::<Vec<_>>()
        .join(" ");
    let zeros = vec!["0"; dim].join(" ");
    let fixed = inp.node_set(&block.bottom);
    let refset = inp.node_set(&[r]);
    inp.bcs.push(format!(
        "BoundaryCondition 1 loadTimeFunction 2 dofs {dim} {dofs} values {dim} {zeros} set {fixed}"
    ));
    let down_v = if dim == 2 {
        format!("0 {}", -down)
    } else {
        format!("0 0 {}", -down)
    };
    match force {
        None => inp.bcs.push(format!(
            "BoundaryCondition 2 loadTimeFunction 1 dofs {dim} {dofs} values {dim} {down_v} set {refset}"
        )),
        Some(f) => {
            // The reference node is held sideways and pushed down by a force.
            let side = (1..dim).map(|d| d.to_string()).collect::<Vec<_>>().join(" ");
            let side_zeros = vec!["0"; dim - 1].join(" ");
            inp.bcs.push(format!(
                "BoundaryCondition 2 loadTimeFunction 2 dofs {} {side} values {} {side_zeros} set {refset}",
                dim - 1,
                dim - 1
            ));
            let comp = if dim == 2 {
                format!("0 {}", -f)
            } else {
                format!("0 0 {}", -f)
            };
            inp.bcs.push(format!(
                "NodalLoad 4 loadTimeFunction 1 dofs {dim} {dofs} components {dim} {comp} set {refset}"
            ));
        }
    }
    inp.bcs.push(n2s(3, law, &block.top, &[1], ""));
    inp.functions.push(history(steps));
    inp.functions.push("ConstantFunction 2 f(t) 1.0".into());
    inp.render(
        "suite",
        &analysis(steps.len()),
        if dim == 2 { "PlaneStrain" } else { "3d" },
    )
}

/// Radius, indentation, block width and depth, and cap size of [`cylinder_on_block`].
pub const CYL_R: f64 = 20.0;
pub const CYL_DELTA: f64 = 0.022;
pub const CYL_W: f64 = 6.0;
pub const CYL_DEPTH: f64 = 6.0;
pub const CYL_CAP: f64 = 4.0;

/// An elastic cylinder (the cap of radius `r` within x ≤ 3) on an elastic block, half model,
/// plane strain, fine spacing h under the contact; the cap's flat top pushed down by `delta`.
pub fn cylinder_on_block(h: f64, law: Law, nlgeo: bool) -> String {
    let (r, delta, w, depth, wc, hc) = (CYL_R, CYL_DELTA, CYL_W, CYL_DEPTH, CYL_CAP, CYL_CAP);
    let extra = if nlgeo { "nlgeo 1" } else { "" };
    let mut inp = Input::default();
    let xs = graded(w, h, 1.0, 1.2);
    let ys: Vec<f64> = graded(depth, h, 0.5, 1.2)
        .iter()
        .rev()
        .map(|d| -d)
        .collect();
    let block = inp.block2d(
        Kind::Q4,
        &xs,
        &|_| ys.clone(),
        &format!("mat 1 crossSect 1 {extra}"),
    );
    let xc = graded(wc, h, 1.0, 1.2);
    let hcs = graded(hc, h, 0.5, 1.2);
    let cap = inp.block2d(
        Kind::Q4,
        &xc,
        &|i| {
            let yb = r - (r * r - xc[i] * xc[i]).sqrt();
            hcs.iter().map(|t| yb + t * (hc - yb) / hc).collect()
        },
        &format!("mat 1 crossSect 1 {extra}"),
    );
    inp.segments.push(format!(
        "linear2delementedgecontactsegment 1 edgeset {}",
        inp.sets.len() + 1
    ));
    inp.boundary_set(&block.top_edges);
    inp.sections.push("SimpleCS 1 thick 1.0".into());
    inp.materials
        .push(format!("IsoLE 1 d 0 E {E} n {NU} tAlpha 0"));
    let sym: Vec<usize> = block.left.iter().chain(&cap.left).copied().collect();
    let sym = inp.node_set(&sym);
    let bottom = inp.node_set(&block.bottom);
    let top = inp.node_set(&cap.top);
    inp.bcs.push(format!(
        "BoundaryCondition 1 loadTimeFunction 2 dofs 1 1 values 1 0 set {sym}"
    ));
    inp.bcs.push(format!(
        "BoundaryCondition 2 loadTimeFunction 2 dofs 1 2 values 1 0 set {bottom}"
    ));
    inp.bcs.push(format!(
        "BoundaryCondition 3 loadTimeFunction 1 dofs 1 2 values 1 {} set {top}",
        -delta
    ));
    let contact: Vec<usize> = cap
        .bottom
        .iter()
        .zip(&xc)
        .filter(|(_, &x)| x <= 1.2)
        .map(|(&n, _)| n)
        .collect();
    inp.bcs.push(n2s(4, law, &contact, &[1], ""));
    inp.functions.push(history(&[1.0]));
    inp.functions.push("ConstantFunction 2 f(t) 1.0".into());
    inp.render("suite", &analysis(1), "PlaneStrain")
}

/// A block [0, 1]² (6 × 6, `nlgeo 1`) fixed at its bottom and compressed 50 % in ten steps by a
/// rigid plane (`circle`: false) or a circle of radius 2 whose reference node is driven down.
/// `neo_hooke`: a neo-Hookean material of E = 1000, ν = 0.3; else `IsoLE` of the same moduli, the
/// St. Venant–Kirchhoff law, which softens past a stretch of 1/√3 (see
/// [`hertz::solve::softening`]).
pub fn compressed_by_a_moving_rigid(circle: bool, neo_hooke: bool, law: Law) -> String {
    let mut inp = Input::default();
    let xs = uniform(0.0, 1.0, 6);
    let block = inp.block2d(Kind::Q4, &xs, &|_| xs.clone(), "mat 1 crossSect 1 nlgeo 1");
    let r = inp.node(0.5, 1.0, 0.0);
    inp.segments.push(if circle {
        format!("circlecontactsegment 1 centerpoint 2 0.5 3.0 radius 2.0 node {r}")
    } else {
        format!("planecontactsegment 1 point 2 0.5 1.0 normal 2 0 -1 node {r}")
    });
    inp.sections.push("SimpleCS 1 thick 1.0".into());
    inp.materials.push(if neo_hooke {
        let (mu, k) = (E / (2.0 * (1.0 + NU)), E / (3.0 * (1.0 - 2.0 * NU)));
        format!(
            "MooneyRivlinCompressibleMat 1 d 0 c1 {} c2 0 k {k}",
            mu / 2.0
        )
    } else {
        format!("IsoLE 1 d 0 E {E} n {NU} tAlpha 0")
    });
    let fixed = inp.node_set(&block.bottom);
    let refset = inp.node_set(&[r]);
    inp.bcs.push(format!(
        "BoundaryCondition 1 loadTimeFunction 1 dofs 2 1 2 values 2 0 0 set {fixed}"
    ));
    inp.bcs.push(format!(
        "BoundaryCondition 2 loadTimeFunction 1 dofs 2 1 2 values 2 0 -0.5 set {refset}"
    ));
    inp.bcs.push(n2s(3, law, &block.top, &[1], ""));
    let steps: Vec<f64> = (1..=10).map(|i| i as f64 / 10.0).collect();
    inp.functions.push(history(&steps));
    inp.render("suite", &analysis(steps.len()), "PlaneStrain")
}

/// The unit cross-section, the neo-Hookean rubber (material 1: c1 = 0.5, k = 10, E = 90/31)
/// and a die a thousand times stiffer (material 2) of the die and punch setups.
fn rubber_and_stiff_die(inp: &mut Input) {
    inp.sections.push("SimpleCS 1 thick 1.0".into());
    inp.materials
        .push("MooneyRivlinCompressibleMat 1 d 0 c1 0.5 c2 0 k 10".into());
    inp.materials
        .push("MooneyRivlinCompressibleMat 2 d 0 c1 500 c2 0 k 10000".into());
}

/// The penalty of [`die_as_wide_as_the_block`]'s twin: 10³ times the block's modulus (90/31).
pub const DIE_PENALTY: f64 = 3e3;

/// A plate 2 × 1 (4 × 2 elements) on a fixed block, pressed down 0.02 and drawn 0.05 along x
/// by its top, μ = 0.3: in plane strain (`dim` 2), or in 3D one element thick with u_z = 0 on
/// every node of the plate (`dim` 3), the same problem. The condition is `keyword` with
/// `params` (law and friction); `mortar`: the plate's bottom is its slave segment.
pub fn plate_drawn_on_a_block(dim: usize, keyword: &str, params: &str, mortar: bool) -> String {
    let (nx, ny) = (4usize, 2usize);
    let layers = if dim == 3 { 2 } else { 1 };
    let mut nodes: Vec<[f64; 3]> = Vec::new();
    let mut id = std::collections::HashMap::new();
    // Plate (tag 0, y = 0..1) and block (tag 1, y = −0.5..0) nodes, z = 0 then z = 1.
    for (tag, ys) in [(0u8, vec![0.0, 0.5, 1.0]), (1, vec![-0.5, 0.0])] {
        for k in 0..layers {
            for (j, y) in ys.iter().enumerate() {
                for i in 0..=nx {
                    nodes.push([0.5 * i as f64, *y, k as f64]);
                    id.insert((tag, i, j, k), nodes.len());
                }
            }
        }
    }
    let n = |t: u8, i: usize, j: usize, k: usize| id[&(t, i, j, k)];
    // LSpace: nodes 5-8 under 1-4 (the guide); Quad1PlaneStrain counter-clockwise.
    let element = |t: u8, i: usize, j: usize| -> Vec<usize> {
        if dim == 3 {
            let face = |k| {
                [
                    n(t, i, j, k),
                    n(t, i, j + 1, k),
                    n(t, i + 1, j + 1, k),
                    n(t, i + 1, j, k),
                ]
            };
            [face(1), face(0)].concat()
        } else {
            vec![
                n(t, i, j, 0),
                n(t, i + 1, j, 0),
                n(t, i + 1, j + 1, 0),
                n(t, i, j + 1, 0),
            ]
        }
    };
    let mut elements: Vec<Vec<usize>> = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            elements.push(element(0, i, j));
        }
    }
    let plate_elements = elements.len();
    elements.extend((0..nx).map(|i| element(1, i, 0)));
    let list = |v: &[usize]| {
        let items: Vec<String> = v.iter().map(|x| x.to_string()).collect();
        format!("{} {}", v.len(), items.join(" "))
    };
    // The block's top and the plate's bottom: LSpace faces 4 and 6, quadrilateral edges 3 and 1.
    let (top_face, bottom_face) = if dim == 3 { (4, 6) } else { (3, 1) };
    let boundaries = |first: usize, b: usize| {
        let v: Vec<usize> = (0..nx).flat_map(|e| [first + e + 1, b]).collect();
        list(&v)
    };
    let tagged = |tag: u8| {
        let mut v: Vec<usize> = id
            .iter()
            .filter(|(key, _)| key.0 == tag)
            .map(|(_, &m)| m)
            .collect();
        v.sort_unstable();
        v
    };
    let row = |j: usize| -> Vec<usize> {
        (0..layers)
            .flat_map(|k| (0..=nx).map(move |i| (i, k)))
            .map(|(i, k)| n(0, i, j, k))
            .collect()
    };
    let face = if dim == 3 {
        "linear3delementsurfacecontactsegment"
    } else {
        "linear2delementedgecontactsegment"
    };
    let set = if dim == 3 { "boundaryset" } else { "edgeset" };
    let (segments, pairing) = if mortar {
        (
            format!("{face} 1 {set} 4\n{face} 2 {set} 5\n"),
            "slavesegment 2 segmentset 1 1".to_string(),
        )
    } else {
        (
            format!("{face} 1 {set} 4\n"),
            format!("nodeset {} segmentset 1 1", list(&row(0))),
        )
    };
    let (domain, fixed) = if dim == 3 {
        ("3d", "dofs 3 1 2 3 values 3 0 0 0")
    } else {
        ("PlaneStrain", "dofs 2 1 2 values 2 0 0")
    };
    let mut t = format!(
        "plate.out\nplate on a block, drawn along it\nStaticStructural nsteps 2 rtolf 1e-10 maxiter 30\n\
         domain {domain}\nOutputManager\n\
         ndofman {} nelem {} ncrosssect 1 nmat 1 nbc 4 nic 0 nltf 2 nset 5 ncontactseg {}\n",
        nodes.len(),
        elements.len(),
        if mortar { 2 } else { 1 },
    );
    for (k, x) in nodes.iter().enumerate() {
        let c: Vec<String> = x[..dim].iter().map(|c| c.to_string()).collect();
        t += &format!("node {} coords {dim} {}\n", k + 1, c.join(" "));
    }
    let kind = if dim == 3 {
        "LSpace"
    } else {
        "Quad1PlaneStrain"
    };
    for (k, e) in elements.iter().enumerate() {
        t += &format!("{kind} {} nodes {} mat 1 crossSect 1\n", k + 1, list(e));
    }
    t += &segments;
    t += "SimpleCS 1 thick 1.0\nIsoLE 1 d 0 E 1000 n 0.3 tAlpha 0\n";
    t += &format!("BoundaryCondition 1 loadTimeFunction 1 {fixed} set 3\n");
    t += "BoundaryCondition 2 loadTimeFunction 2 dofs 2 1 2 values 2 0.05 -0.02 set 2\n";
    // In 3D u_z = 0 on every plate node (in 2D a condition on nothing free: u_y = 0 of the block).
    if dim == 3 {
        t += "BoundaryCondition 3 loadTimeFunction 1 dofs 1 3 values 1 0 set 1\n";
    } else {
        t += "BoundaryCondition 3 loadTimeFunction 1 dofs 1 2 values 1 0 set 3\n";
    }
    t += &format!("{keyword} 4 loadTimeFunction 1 {params} {pairing}\n");
    t += "ConstantFunction 1 f(t) 1.0\nPiecewiseLinFunction 2 npoints 3 t 3 0 1 2 f(t) 3 0 0.5 1\n";
    t += &format!(
        "Set 1 nodes {}\nSet 2 nodes {}\nSet 3 nodes {}\n",
        list(&tagged(0)),
        list(&row(ny)),
        list(&tagged(1))
    );
    t += &format!(
        "Set 4 elementboundaries {}\n",
        boundaries(plate_elements, top_face)
    );
    t += &format!("Set 5 elementboundaries {}\n", boundaries(0, bottom_face));
    t
}

/// Code_Aster's SSNV128 (V6.04.128, after a GRECO case): a square plate of side 40 mm
/// (`n` × `n` elements, E = 1.3e11, ν = 0.2) on a rigid plane y = 0 with Coulomb friction μ = 1,
/// pressed by a pressure 5e7 on its top and pushed along x by 15e7 on its face x = 0, u_x = 0 on
/// its face x = 40 mm (the problem's symmetry plane) and u_y = 0 at the node (40 mm, 0, 0). In
/// plane strain (`dim` 2), or in 3D one layer of bricks 2 mm thick with u_z = 0 on every node,
/// the same problem but for the corner's second node (40 mm, 0, 2 mm), which the contact holds.
/// The plate's bottom is the slave of the contact condition `law` (the record's keyword and its
/// law's parameters, e.g. `s2spenaltycontact` or `n2spenaltycontact penalty 1e12`): its edges
/// (faces) in mortar, its nodes in node-to-segment; friction 1.
pub fn plate_pushed_on_a_rigid_plane(dim: usize, n: usize, law: &str) -> String {
    let (side, t) = (0.04, 0.002);
    let layers = if dim == 3 { 2 } else { 1 };
    let id = |i: usize, j: usize, k: usize| k * (n + 1) * (n + 1) + j * (n + 1) + i + 1;
    let mut text = String::new();
    let mut records = Vec::new();
    for k in 0..layers {
        for j in 0..=n {
            for i in 0..=n {
                let (x, y) = (side * i as f64 / n as f64, side * j as f64 / n as f64);
                records.push(if dim == 3 {
                    format!("node {} coords 3 {x} {y} {}", id(i, j, k), t * k as f64)
                } else {
                    format!("node {} coords 2 {x} {y}", id(i, j, k))
                });
            }
        }
    }
    let element = |i: usize, j: usize| j * n + i + 1;
    for j in 0..n {
        for i in 0..n {
            let face = |k| {
                [
                    id(i, j, k),
                    id(i + 1, j, k),
                    id(i + 1, j + 1, k),
                    id(i, j + 1, k),
                ]
            };
            let nodes: Vec<String> = match dim {
                3 => [face(0), face(1)].concat(),
                _ => face(0).to_vec(),
            }
            .iter()
            .map(|x| x.to_string())
            .collect();
            let kind = if dim == 3 {
                "LSpace"
            } else {
                "Quad1PlaneStrain"
            };
            records.push(format!(
                "{kind} {} nodes {} {} crossSect 1 mat 1",
                element(i, j),
                nodes.len(),
                nodes.join(" ")
            ));
        }
    }
    let list = |v: Vec<String>| format!("{} {}", v.len(), v.join(" "));
    // The bottom, top and x = 0 sides: LSpace faces 3, 5, 6; quadrilateral edges 1, 3, 4.
    let sides = |elements: Vec<usize>, side: usize| {
        list(
            elements
                .iter()
                .flat_map(|e| [e.to_string(), side.to_string()])
                .collect(),
        )
    };
    let (bottom, top, left) = if dim == 3 { (3, 5, 6) } else { (1, 3, 4) };
    let symmetry: Vec<String> = (0..layers)
        .flat_map(|k| (0..=n).map(move |j| id(n, j, k).to_string()))
        .collect();
    let (segment, set, plane, load, thick) = if dim == 3 {
        (
            "linear3delementsurfacecontactsegment",
            "boundaryset",
            "planecontactsegment 2 point 3 0 0 0 normal 3 0 1 0",
            "ConstantSurfaceLoad",
            "",
        )
    } else {
        (
            "linear2delementedgecontactsegment",
            "edgeset",
            "planecontactsegment 2 point 2 0 0 normal 2 0 1",
            "ConstantEdgeLoad",
            " thick 0.002",
        )
    };
    let (down, along) = if dim == 3 {
        ("components 3 0 -5e7 0", "components 3 15e7 0 0")
    } else {
        ("components 2 0 -5e7", "components 2 15e7 0")
    };
    text += &format!(
        "ssnv128.out\nSSNV128, {dim}D\nNonLinearStatic nsteps 1 controlmode 1 rtolf 1e-10 maxiter 30\n\
         domain {}\nOutputManager\nndofman {} nelem {} ncrosssect 1 nmat 1 nbc {} nic 0 nltf 1 \
         nset 7 ncontactseg 2\n",
        if dim == 3 { "3d" } else { "PlaneStrain" },
        layers * (n + 1) * (n + 1),
        n * n,
        if dim == 3 { 6 } else { 5 },
    );
    for r in records {
        text += &r;
        text += "\n";
    }
    text += &format!("{segment} 1 {set} 1\n{plane}\nSimpleCS 1{thick} material 1 set 7\n");
    text += "IsoLE 1 d 0 E 1.3e11 n 0.2 tAlpha 0\n";
    text += "BoundaryCondition 1 loadTimeFunction 1 dofs 1 1 values 1 0 set 2\n";
    text += "BoundaryCondition 2 loadTimeFunction 1 dofs 1 2 values 1 0 set 3\n";
    text += &format!("{load} 3 loadTimeFunction 1 {down} set 5\n");
    text += &format!("{load} 4 loadTimeFunction 1 {along} set 6\n");
    let (keyword, params) = law.split_once(' ').unwrap_or((law, ""));
    let pairing = match keyword.starts_with("n2s") {
        true => format!(
            "nodeset {} segmentset 1 2",
            list(
                (0..layers)
                    .flat_map(|k| (0..=n).map(move |i| id(i, 0, k).to_string()))
                    .collect()
            )
        ),
        false => "slavesegment 1 segmentset 1 2".to_string(),
    };
    text += &format!("{keyword} 5 loadTimeFunction 1 {params} friction 1.0 {pairing}\n");
    if dim == 3 {
        let all: Vec<String> = (1..=2 * (n + 1) * (n + 1)).map(|x| x.to_string()).collect();
        text += "BoundaryCondition 6 loadTimeFunction 1 dofs 1 3 values 1 0 set 4\n";
        text += "ConstantFunction 1 f(t) 1.0\n";
        text += &format!("Set 4 nodes {}\n", list(all));
    } else {
        text += "ConstantFunction 1 f(t) 1.0\nSet 4 nodes 0\n";
    }
    text += &format!(
        "Set 1 elementboundaries {}\n",
        sides((0..n).map(|i| element(i, 0)).collect(), bottom)
    );
    text += &format!("Set 2 nodes {}\n", list(symmetry));
    text += &format!("Set 3 nodes 1 {}\n", id(n, 0, 0));
    text += &format!(
        "Set 5 elementboundaries {}\n",
        sides((0..n).map(|i| element(i, n - 1)).collect(), top)
    );
    text += &format!(
        "Set 6 elementboundaries {}\n",
        sides((0..n).map(|j| element(0, j)).collect(), left)
    );
    text += "Set 7 allelements\n";
    text
}

/// A neo-Hookean block [0, 1]^dim (8 elements a side in 2D, 5 in 3D; c1 = 0.5, k = 10)
/// compressed 30 % in ten steps of large deformation by a die exactly as wide and a thousand
/// times stiffer (two layers over the block, 0.2 thick), the block's top nodes the slave side:
/// its sides bulge past the die's edges and the corners away from the held one curl up past the
/// die's end. `mortar`: the block's top edges (faces) are a mortar condition's slave segment,
/// else its top nodes a node-to-segment condition's slave nodes.
///
/// In 3D it is a quarter model: the block is held on the symmetry planes x = 0 and y = 0, the
/// die by its driven top alone. Held instead by two bottom nodes (the 2D way), the block's turn
/// about z and its sideways drift are resisted by those nodes alone, while the die's edges,
/// which it bulges past, push it out from under the die: a near mechanism that failed every law
/// and formulation at 10 × 10 × 10 elements (node-to-face at step 6, mortar at step 5). The
/// die is held by its driven top alone ([`die_and_block_on_the_symmetry_planes`] holds it on
/// the planes too).
pub fn die_as_wide_as_the_block(dim: usize, mortar: bool, law: Law) -> String {
    die_as_wide(dim, mortar, law, false)
}

/// [`die_as_wide_as_the_block`] in 3D as mortar, the die held on the symmetry planes as well as
/// the block: the slave faces' sides along x = 0 and y = 0 lie on the master faces' sides.
pub fn die_and_block_on_the_symmetry_planes(law: Law) -> String {
    die_as_wide(3, true, law, true)
}

fn die_as_wide(dim: usize, mortar: bool, law: Law, die_on_planes: bool) -> String {
    let mut inp = Input::default();
    let (block, die) = if dim == 2 {
        let xs = uniform(0.0, 1.0, 8);
        let block = inp.block2d(Kind::Q4, &xs, &|_| xs.clone(), "mat 1 crossSect 1 nlgeo 1");
        let die = inp.block2d(
            Kind::Q4,
            &xs,
            &|_| uniform(1.0, 1.2, 2),
            "mat 2 crossSect 1 nlgeo 1",
        );
        (block, die)
    } else {
        let g = uniform(0.0, 1.0, 5);
        let block = inp.block3d(&g, &g, &g, "mat 1 crossSect 1 nlgeo 1");
        let die = inp.block3d(&g, &g, &uniform(1.0, 1.2, 2), "mat 2 crossSect 1 nlgeo 1");
        (block, die)
    };
    let kind = if dim == 2 {
        "linear2delementedgecontactsegment"
    } else {
        "linear3delementsurfacecontactsegment"
    };
    inp.segments
        .push(format!("{kind} 1 edgeset {}", inp.sets.len() + 1));
    let faces = if dim == 2 {
        die.bottom_edges.clone()
    } else {
        inp.faces_where(&die, &|x| (x[2] - 1.0).abs() < 1e-9)
    };
    inp.boundary_set(&faces);
    rubber_and_stiff_die(&mut inp);
    // The bottom slides on its plane; in 2D the corner at the origin is held, in 3D the block
    // on the symmetry planes x = 0 and y = 0.
    let bottom = inp.node_set(&block.bottom);
    let last = if die_on_planes {
        die.nodes.1
    } else {
        block.nodes.1
    };
    let on_plane = |i: usize| {
        inp.nodes_where(&|x| x[i].abs() < 1e-9)
            .into_iter()
            .filter(|n| (block.nodes.0..=last).contains(n))
            .collect::<Vec<_>>()
    };
    let held = if dim == 2 {
        block.bottom[..1].to_vec()
    } else {
        on_plane(0)
    };
    let across = (dim == 3).then(|| on_plane(1));
    let held = inp.node_set(&held);
    inp.bcs.push(format!(
        "BoundaryCondition 1 loadTimeFunction 1 dofs 1 {dim} values 1 0 set {bottom}"
    ));
    inp.bcs.push(format!(
        "BoundaryCondition 2 loadTimeFunction 1 dofs 1 1 values 1 0 set {held}"
    ));
    let top = inp.node_set(&die.top);
    let down = if dim == 2 { "0 -0.3" } else { "0 0 -0.3" };
    let dofs = if dim == 2 { "1 2" } else { "1 2 3" };
    inp.bcs.push(format!(
        "BoundaryCondition 3 loadTimeFunction 1 dofs {dim} {dofs} values {dim} {down} set {top}"
    ));
    if let Some(across) = across {
        let across = inp.node_set(&across);
        inp.bcs.push(format!(
            "BoundaryCondition 4 loadTimeFunction 1 dofs 1 2 values 1 0 set {across}"
        ));
    }
    let number = inp.bcs.len() + 1;
    if mortar {
        inp.segments
            .push(format!("{kind} 2 edgeset {}", inp.sets.len() + 1));
        let faces = if dim == 2 {
            block.top_edges.clone()
        } else {
            inp.faces_where(&block, &|x| (x[2] - 1.0).abs() < 1e-9)
        };
        inp.boundary_set(&faces);
        inp.bcs.push(s2s(number, law));
    } else {
        inp.bcs.push(n2s(number, law, &block.top, &[1], ""));
    }
    let steps: Vec<f64> = (1..=10).map(|i| i as f64 / 10.0).collect();
    inp.functions.push(history(&steps));
    inp.render(
        "suite",
        &analysis(steps.len()),
        if dim == 2 { "PlaneStrain" } else { "3d" },
    )
}

/// A neo-Hookean block [0, 1]² (8 × 8, c1 = 0.5, k = 10, E = 90/31) indented 20 % in ten steps
/// of large deformation by a punch over its middle half a thousand times stiffer (4 × 2 over
/// [0.25, 0.75] × [1, 1.2]), the punch's bottom nodes the slave side on the block's top edges: a
/// stiff slave on a soft master.
pub fn stiff_punch_on_a_soft_block(law: Law) -> String {
    let mut inp = Input::default();
    let xs = uniform(0.0, 1.0, 8);
    let block = inp.block2d(Kind::Q4, &xs, &|_| xs.clone(), "mat 1 crossSect 1 nlgeo 1");
    let punch = inp.block2d(
        Kind::Q4,
        &uniform(0.25, 0.75, 4),
        &|_| uniform(1.0, 1.2, 2),
        "mat 2 crossSect 1 nlgeo 1",
    );
    inp.segments.push(format!(
        "linear2delementedgecontactsegment 1 edgeset {}",
        inp.sets.len() + 1
    ));
    inp.boundary_set(&block.top_edges);
    rubber_and_stiff_die(&mut inp);
    let bottom = inp.node_set(&block.bottom);
    let top = inp.node_set(&punch.top);
    inp.bcs.push(format!(
        "BoundaryCondition 1 loadTimeFunction 1 dofs 2 1 2 values 2 0 0 set {bottom}"
    ));
    inp.bcs.push(format!(
        "BoundaryCondition 2 loadTimeFunction 1 dofs 2 1 2 values 2 0 -0.2 set {top}"
    ));
    inp.bcs.push(n2s(3, law, &punch.bottom, &[1], ""));
    let steps: Vec<f64> = (1..=10).map(|i| i as f64 / 10.0).collect();
    inp.functions.push(history(&steps));
    inp.render("suite", &analysis(steps.len()), "PlaneStrain")
}

/// Every setup of the suite.
pub fn setups() -> Vec<Setup> {
    let mut out = Vec::new();
    let mut blocks = |name: &str, class: &'static str, tb: TwoBlocks| {
        out.push(Setup::new(name, class, PENALTY, move |law| tb.input(law)));
    };
    let base = TwoBlocks::flush(4);
    // Flush blocks: the slave's nodes on every master vertex, its corners on the master's ends.
    blocks("flush, displacement", "flush", base.clone());
    blocks(
        "flush, force (touching start)",
        "touching start, force control",
        TwoBlocks {
            drive: Drive::Force(20.0),
            ..base.clone()
        },
    );
    blocks(
        "flush, soft slave, force",
        "flush",
        TwoBlocks {
            e_slave: 300.0,
            drive: Drive::Force(20.0),
            ..base.clone()
        },
    );
    blocks(
        "flush, stiff slave, coarse",
        "flush",
        TwoBlocks {
            e_slave: 3000.0,
            nx: 8,
            nxs: 4,
            ..base.clone()
        },
    );
    blocks(
        "slave 1 % narrower",
        "flush",
        TwoBlocks {
            ws: 1.98,
            ..base.clone()
        },
    );
    blocks(
        "vertex-centred slave",
        "vertex-centred",
        TwoBlocks {
            ws: 1.0,
            xs0: 0.5,
            nx: 2,
            nxs: 2,
            ..base.clone()
        },
    );
    blocks(
        "vertex-centred, force",
        "vertex-centred",
        TwoBlocks {
            ws: 1.0,
            xs0: 0.5,
            nx: 2,
            nxs: 2,
            drive: Drive::Force(10.0),
            ..base.clone()
        },
    );
    blocks(
        "non-matching meshes",
        "flush",
        TwoBlocks {
            nxs: 7,
            ..base.clone()
        },
    );
    // Two-pass: each block's nodes on the other's edges (the constraints of coincident nodes
    // repeat each other).
    blocks(
        "two-pass, flush",
        "two-pass",
        TwoBlocks {
            two_pass: true,
            ..base.clone()
        },
    );
    blocks(
        "two-pass, non-matching, force",
        "two-pass",
        TwoBlocks {
            nxs: 7,
            two_pass: true,
            drive: Drive::Force(20.0),
            ..base.clone()
        },
    );
    // Sliding: a narrow slave pressed, then moved sideways over many master vertices, and off the
    // master's end.
    let slide = TwoBlocks {
        nx: 8,
        w: 4.0,
        ws: 0.5,
        xs0: 0.5,
        nxs: 2,
        drive: Drive::Displacement {
            down: 0.01,
            side: 3.0,
        },
        steps: (1..=12).map(|i| i as f64 / 12.0).collect(),
        ..base.clone()
    };
    blocks("sliding over 6 vertices", "sliding", slide.clone());
    blocks(
        "sliding over 6 vertices, nlgeo",
        "sliding",
        TwoBlocks {
            nlgeo: true,
            ..slide.clone()
        },
    );
    blocks(
        "sliding off the master's end",
        "sliding",
        TwoBlocks {
            xs0: 3.0,
            drive: Drive::Displacement {
                down: 0.01,
                side: 0.8,
            },
            steps: (1..=8).map(|i| i as f64 / 8.0).collect(),
            ..slide.clone()
        },
    );
    blocks(
        "sliding, quadratic edges",
        "quadratic edges",
        TwoBlocks {
            kind: Kind::Q8,
            ..slide.clone()
        },
    );
    // Quadratic edges.
    blocks(
        "quadratic, flush",
        "quadratic edges",
        TwoBlocks {
            kind: Kind::Q8,
            ..base.clone()
        },
    );
    blocks(
        "quadratic, non-matching",
        "quadratic edges",
        TwoBlocks {
            kind: Kind::Q8,
            nx: 2,
            nxs: 3,
            ..base.clone()
        },
    );
    blocks(
        "quadratic, force",
        "quadratic edges",
        TwoBlocks {
            kind: Kind::Q8,
            nx: 3,
            nxs: 2,
            drive: Drive::Force(20.0),
            ..base.clone()
        },
    );
    // Unloading: up, down and lifted off.
    blocks(
        "unloading to lift-off",
        "unloading",
        TwoBlocks {
            steps: vec![0.5, 1.0, 0.5, 0.0, -0.5],
            ..base.clone()
        },
    );
    blocks(
        "unloading under force",
        "unloading",
        TwoBlocks {
            drive: Drive::Force(20.0),
            steps: vec![0.5, 1.0, 0.5, 0.1],
            ..base.clone()
        },
    );
    // Large deformation to 30 % strain in 20 steps.
    blocks(
        "nlgeo blocks to 30 % strain",
        "large deformation",
        TwoBlocks {
            nlgeo: true,
            nxs: 5,
            drive: Drive::Displacement {
                down: 0.6,
                side: 0.0,
            },
            steps: (1..=20).map(|i| i as f64 / 20.0).collect(),
            ..base.clone()
        },
    );
    // Nodes that slide off the master's end: the block's corners bulge past a die as wide as it.
    // Its last step holds a corner at the die's corner: a penalty error of order 1/3.
    out.push(Setup {
        order: 1.0 / 3.0,
        ..Setup::new(
            "die as wide as the block, nlgeo",
            "sliding",
            DIE_PENALTY,
            |l| die_as_wide_as_the_block(2, false, l),
        )
    });
    // The same with mortar: the corner's support on the die falls as the square of its overlap
    // (∫ N_j over the sliver), as node-to-segment's weight near the end: the same order.
    out.push(Setup {
        order: 1.0 / 3.0,
        ..Setup::new(
            "die as wide as the block, mortar, nlgeo",
            "sliding",
            DIE_PENALTY,
            |l| die_as_wide_as_the_block(2, true, l),
        )
    });
    // The same in 3D (a quarter model): rows of nodes slide off two of the die's edges and the
    // far corner off its corner.
    out.push(Setup {
        order: 1.0 / 3.0,
        ..Setup::new(
            "die as wide as the block, mortar, 3D, nlgeo",
            "sliding",
            DIE_PENALTY,
            |l| die_as_wide_as_the_block(3, true, l),
        )
    });
    // Friction along a fixed block of a 3D plate held at u_z = 0 on every node (the friction
    // force's z component acts on held DOFs only), node-to-face and mortar; μ = 0.3, sliding.
    for (mortar, name) in [(false, "node-to-face"), (true, "mortar")] {
        out.push(Setup::new(
            format!("3D plate held at u_z = 0 drawn along a block, friction, {name}"),
            "friction",
            1e5,
            move |l| {
                let (keyword, params) = match (l, mortar) {
                    (Law::Multiplier, false) => {
                        ("n2slagrangianmultipliercontact", "friction 0.3".to_string())
                    }
                    (Law::Multiplier, true) => {
                        ("s2slagrangianmultipliercontact", "friction 0.3".to_string())
                    }
                    (Law::Penalty(p), m) => (
                        if m {
                            "s2spenaltycontact"
                        } else {
                            "n2spenaltycontact"
                        },
                        format!("penalty {p} friction 0.3 pt {p}"),
                    ),
                };
                plate_drawn_on_a_block(3, keyword, &params, mortar)
            },
        ));
    }
    // The shallow ironing benchmark extruded to 3D, two elements through the depth (the slave
    // faces' sides lie along the master's), every node held in y; pressed, then slid 0.2.
    for kind in [Solid::Hex, Solid::Tet] {
        out.push(Setup::new(
            format!("shallow ironing extruded to 3D, two layers, {kind:?}, friction"),
            "friction",
            1e5,
            move |l| {
                let base = crate::verify::ShallowIroning {
                    nx: 40,
                    ny: 6,
                    n_arc: 4,
                    n_die: 4,
                    slide_dt: 0.01,
                    end: 1.02,
                    mu: 0.3,
                };
                crate::verify::ShallowIroning3d {
                    base,
                    kind,
                    layers: 2,
                    plane_strain: true,
                }
                .input_with(l)
            },
        ));
    }
    // A rigid plane and circle moving with a node compress a neo-Hookean block 50 %.
    for (circle, name) in [(false, "plane"), (true, "circle")] {
        out.push(Setup::new(
            format!("{name} moving with a node, 50 %, nlgeo"),
            "large deformation",
            PENALTY,
            move |l| compressed_by_a_moving_rigid(circle, true, l),
        ));
    }
    // Large penalties (1e12 with E = 1000, as OOFEM's inputs use).
    for (name, drive) in [
        ("penalty 1e12, displacement", base.drive),
        ("penalty 1e12, force", Drive::Force(20.0)),
    ] {
        let tb = TwoBlocks {
            drive,
            ..base.clone()
        };
        out.push(Setup::new(name, "large penalty", 1e12, move |l| {
            tb.input(l)
        }));
    }
    out.push(Setup::new(
        "node-to-node 2D",
        "node-to-node",
        PENALTY,
        |l| node_to_node(2, l),
    ));
    out.push(Setup::new(
        "node-to-node 3D, penalty 1e12",
        "large penalty",
        1e12,
        |l| node_to_node(3, l),
    ));
    // Rigid shapes, starting penetration (the nodes start 0.01 inside), then pushed.
    let rigid = |name: &str, seg: &'static str, dim: usize, force: Option<f64>| {
        Setup::new(name, "starting penetration", PENALTY, move |l| {
            against_rigid(dim, l, seg, 0.02, &[0.0, 1.0], force)
        })
    };
    out.push(rigid(
        "circle, starting inside",
        "circlecontactsegment 1 centerpoint 2 1.0 1.99 radius 2.0 node REF",
        2,
        None,
    ));
    out.push(rigid(
        "circle, 1e-9 overlap",
        "circlecontactsegment 1 centerpoint 2 1.0 1.999999999 radius 2.0 node REF",
        2,
        None,
    ));
    out.push(rigid(
        "plane, starting inside",
        "planecontactsegment 1 point 2 1.0 -0.01 normal 2 0 -1 node REF",
        2,
        None,
    ));
    out.push(rigid(
        "polynomial, starting inside",
        "polynomialcontactsegment 1 coeffs 3 -0.1 0.2 -0.11 bodyabove",
        2,
        None,
    ));
    out.push(rigid(
        "cavity, starting outside it",
        "circlecontactsegment 1 centerpoint 2 1.0 -3.0 radius 2.99 cavity node REF",
        2,
        None,
    ));
    out.push(rigid(
        "plane, touching, force",
        "planecontactsegment 1 point 2 1.0 0 normal 2 0 -1 node REF",
        2,
        Some(50.0),
    ));
    out.push(rigid(
        "sphere 3D, starting inside",
        "circlecontactsegment 1 centerpoint 3 0.5 0.5 1.99 radius 2.0 node REF",
        3,
        None,
    ));
    out.push(rigid(
        "plane 3D, starting inside",
        "planecontactsegment 1 point 3 0.5 0.5 -0.01 normal 3 0 0 -1 node REF",
        3,
        None,
    ));
    out.push(rigid(
        "plane 3D, touching, force",
        "planecontactsegment 1 point 3 0.5 0.5 0 normal 3 0 0 -1 node REF",
        3,
        Some(50.0),
    ));
    // The elastic cylinder at five mesh sizes, and in large deformation.
    for h in [0.1, 0.07, 0.05, 0.035, 0.025] {
        out.push(Setup::new(
            format!("elastic cylinder, h = {h}"),
            "elastic cylinder",
            PENALTY,
            move |l| cylinder_on_block(h, l, false),
        ));
    }
    out.push(Setup::new(
        "elastic cylinder, h = 0.05, nlgeo",
        "elastic cylinder",
        PENALTY,
        |l| cylinder_on_block(0.05, l, true),
    ));
    // Tetrahedra on tetrahedra, the cap's whole bottom face the slave side, as a user meshing
    // both bodies with a tetrahedral mesher would.
    for (mortar, name, penalty) in [
        (false, "node-to-face", 1e5),
        // Per unit area: 10³ E/h.
        (true, "mortar", 1e3 * crate::verify::E / TET_SPHERE_H),
    ] {
        out.push(Setup::new(
            format!("3D Hertz, tetrahedra, whole face, {name}"),
            "3D tetrahedra",
            penalty,
            move |l| {
                crate::verify::HertzSphere {
                    kind: Solid::Tet,
                    sym: 0,
                    h: TET_SPHERE_H,
                    delta: 0.15,
                    nlgeo: false,
                    law: l,
                    mortar,
                }
                .input_within(crate::verify::HERTZ_CAP)
            },
        ));
    }
    out
}

/// Element spacing of the suite's tetrahedral Hertz setups.
const TET_SPHERE_H: f64 = 0.3;

/// What a run of one twin gave.
#[derive(Debug, Clone, Default)]
pub struct Outcome {
    pub iterations: Vec<usize>,
    pub substeps: Vec<usize>,
    /// Sum of the contact forces, per step.
    pub force: Vec<f64>,
    /// Node displacements (3 components) per step.
    pub displacement: Vec<Vec<[f64; 3]>>,
    /// Deepest penetration of a closed contact node, per step.
    pub penetration: Vec<f64>,
    /// Number of closed contact nodes, per step.
    pub closed: Vec<usize>,
    /// Diagonal of the model's bounding box.
    pub size: f64,
    pub warnings: Vec<String>,
    pub seconds: f64,
}

/// Solve an input text.
pub fn run(text: &str) -> Result<Outcome> {
    static COUNTER: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let k = COUNTER.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let path = std::env::temp_dir().join(format!("hertz-suite-{}-{k}.in", std::process::id()));
    std::fs::write(&path, text)
        .map_err(|e| Error::Output(format!("cannot write {}: {e}", path.display())))?;
    let read = hertz::input::read_model(&path);
    let _ = std::fs::remove_file(&path);
    let model = read?.model;
    let mut o = Outcome {
        size: hertz::model::queries::model_size(&model),
        ..Default::default()
    };
    let t = Instant::now();
    run_analysis(
        &model,
        &SolveParams {
            max_cutbacks: 3,
            ..Default::default()
        },
        |r| {
            o.iterations.push(r.info.iterations);
            o.substeps.push(r.info.substeps);
            o.force.push(r.contact.iter().map(|c| c.force).sum());
            o.closed.push(r.contact.iter().filter(|c| c.active).count());
            o.penetration.push(
                r.contact
                    .iter()
                    .filter(|c| c.active && c.gap < 0.0)
                    .fold(0.0f64, |m, c| m.max(-c.gap)),
            );
            o.displacement.push(
                (0..model.nodes.len())
                    .map(|n| {
                        let mut d = [0.0; 3];
                        for (i, di) in d.iter_mut().enumerate() {
                            *di = r.displacement(n, i as u8 + 1).unwrap_or(0.0);
                        }
                        d
                    })
                    .collect(),
            );
            o.warnings.extend(r.info.warnings.iter().cloned());
            Ok(())
        },
    )?;
    o.seconds = t.elapsed().as_secs_f64();
    Ok(o)
}

/// How far a penalty run (penalty p) is from its multiplier twin, against the penalty's own
/// error. That error is O(p^(−r)): a second run with p/10 estimates it by Richardson's rule,
/// e ≈ |q(p/10) − q(p)| / `richardson` (10^r − 1, 9 for r = 1). For the node displacements (largest difference) and the total
/// contact force of every step, the ratio |q(p) − q_multipliers| / tolerance is returned
/// (displacement, force), both ≤ 1 when the twins agree. The tolerance is 2 e, plus 10⁻⁶ of the
/// largest value over the steps, plus for the force the round-off of the penalty forces (ε·p·L
/// per closed node, L the model size).
pub fn twin_mismatch(
    penalty: f64,
    richardson: f64,
    pen: &Outcome,
    tenth: &Outcome,
    lm: &Outcome,
) -> (f64, f64) {
    let (mut ru, mut rf) = (0.0f64, 0.0f64);
    let max_diff = |a: &[[f64; 3]], b: &[[f64; 3]]| {
        a.iter()
            .zip(b)
            .flat_map(|(x, y)| (0..3).map(move |i| (x[i] - y[i]).abs()))
            .fold(0.0f64, f64::max)
    };
    let umax = lm
        .displacement
        .iter()
        .flatten()
        .flatten()
        .fold(0.0f64, |m, v| m.max(v.abs()));
    let fmax = lm.force.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let steps = pen
        .displacement
        .len()
        .min(tenth.displacement.len())
        .min(lm.displacement.len());
    for s in 0..steps {
        let e = max_diff(&pen.displacement[s], &tenth.displacement[s]) / richardson;
        let d = max_diff(&pen.displacement[s], &lm.displacement[s]);
        ru = ru.max(d / (2.0 * e + 1e-6 * umax + 1e-300));
        let ef = (pen.force[s] - tenth.force[s]).abs() / richardson;
        let floor = f64::EPSILON * penalty * pen.size * pen.closed[s] as f64;
        let df = (pen.force[s] - lm.force[s]).abs();
        rf = rf.max(df / (2.0 * ef + 1e-6 * fmax + floor + 1e-300));
    }
    (ru, rf)
}

/// A setup run with penalty p and p/10 and with multipliers.
pub struct Twins {
    pub penalty: Outcome,
    /// With a tenth of the penalty (the estimate of the penalty's error).
    pub penalty10: Outcome,
    pub multipliers: Outcome,
}

impl Setup {
    /// Run the three variants.
    pub fn run_twins(&self) -> Result<Twins> {
        Ok(Twins {
            penalty: run(&self.input(Law::Penalty(self.penalty)))?,
            penalty10: run(&self.input(Law::Penalty(0.1 * self.penalty)))?,
            multipliers: run(&self.input(Law::Multiplier))?,
        })
    }
}

/// `hertz bench --suite`: run every setup with both laws and print a Markdown table.
pub fn print_table() -> Result<()> {
    println!("| setup | class | penalty: iterations per step | multipliers: iterations per step | cut-backs | force, penalty vs multipliers | mismatch / penalty error (u, F) |");
    println!("|---|---|---|---|---|---|---|");
    for s in setups() {
        let t = s.run_twins()?;
        let (ru, rf) = s.mismatch(&t);
        let its = |o: &Outcome| {
            o.iterations
                .iter()
                .map(|i| i.to_string())
                .collect::<Vec<_>>()
                .join(" ")
        };
        let cuts = [&t.penalty, &t.multipliers]
            .iter()
            .flat_map(|o| o.substeps.iter())
            .filter(|&&n| n > 1)
            .count();
        let (fp, fm) = (
            t.penalty.force.iter().fold(0.0f64, |m, v| m.max(v.abs())),
            t.multipliers
                .force
                .iter()
                .fold(0.0f64, |m, v| m.max(v.abs())),
        );
        println!(
            "| {} | {} | {} | {} | {cuts} | {fp:.5} vs {fm:.5} | {ru:.2}, {rf:.2} |",
            s.name,
            s.class,
            its(&t.penalty),
            its(&t.multipliers)
        );
    }
    Ok(())
}

/// Write every setup's input files (penalty and multipliers) into `dir`, named after the setup.
pub fn write_inputs(dir: &std::path::Path) -> Result<Vec<std::path::PathBuf>> {
    std::fs::create_dir_all(dir)
        .map_err(|e| Error::Output(format!("cannot create {}: {e}", dir.display())))?;
    let mut out = Vec::new();
    for s in setups() {
        let stem: String = s
            .name
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() {
                    c.to_ascii_lowercase()
                } else {
                    '_'
                }
            })
            .collect::<String>()
            .split('_')
            .filter(|w| !w.is_empty())
            .collect::<Vec<_>>()
            .join("_");
        for (law, tag) in [
            (Law::Penalty(s.penalty), "penalty"),
            (Law::Multiplier, "multipliers"),
        ] {
            let path = dir.join(format!("{stem}.{tag}.in"));
            let text = s.input(law).replacen(
                "suite.out\nsuite\n",
                &format!("{stem}.{tag}.out\n{} ({tag})\n", s.name),
                1,
            );
            std::fs::write(&path, text)
                .map_err(|e| Error::Output(format!("cannot write {}: {e}", path.display())))?;
            out.push(path);
        }
    }
    Ok(out)
}

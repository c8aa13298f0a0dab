#![allow(clippy::needless_range_loop, clippy::type_complexity)]
//! Element verification: finite-difference tangents, rigid-body motion under nlgeo 1, and patch
//! tests (a linear displacement field prescribed on the boundary of a distorted patch is
//! reproduced exactly inside, small strain and total Lagrangian alike) for every element type.

use crate::common;

use hertz::fem::shape::HEXA8_CORNERS;
use hertz::fem::{rule, Shape};
use hertz::material::hyperelastic::{HyperelasticLaw, MooneyRivlin, Ogden, SimoPister};
use hertz::material::{Elasticity, Law};
use hertz::model::StressMode;
use hertz::solid::{ContinuumKernel, ElementKernel, GpState};
use hertz::solve::run_analysis;
use std::fmt::Write;

/// Young's modulus and Poisson's ratio of the linear elastic material of these tests.
const YOUNG: f64 = 100.0;
const POISSON: f64 = 0.3;

/// The laws an element is checked with: linear elasticity, and in large deformation the
/// hyperelastic laws (in plane stress with the out-of-plane stretch solved at each point).
pub(crate) fn laws(mode: StressMode, nlgeo: bool) -> Vec<Law> {
    let mut v: Vec<Law> = vec![std::sync::Arc::new(Elasticity::new(YOUNG, POISSON, mode))];
    if nlgeo {
        let wrap = |h: Box<dyn hertz::material::hyperelastic::Energy>| -> Law {
            std::sync::Arc::new(HyperelasticLaw::new(h, mode))
        };
        v.push(wrap(Box::new(MooneyRivlin {
            c1: 20.0,
            c2: 5.0,
            k: 80.0,
        })));
        v.push(wrap(Box::new(Ogden {
            alpha: vec![1.3, -2.0],
            mu: vec![30.0, -10.0],
            k: 80.0,
        })));
        v.push(wrap(Box::new(SimoPister { g: 40.0, k: 80.0 })));
    }
    v
}

/// (shape, stress mode, default nip) of every continuum element type.
pub(crate) const CONTINUUM: [(&str, Shape, StressMode, usize); 10] = [
    ("PlaneStress2d", Shape::Quad4, StressMode::PlaneStress, 4),
    ("Quad1PlaneStrain", Shape::Quad4, StressMode::PlaneStrain, 4),
    ("TrPlaneStress2d", Shape::Tri3, StressMode::PlaneStress, 1),
    ("TrPlaneStrain", Shape::Tri3, StressMode::PlaneStrain, 1),
    ("QPlaneStress2d", Shape::Quad8, StressMode::PlaneStress, 4),
    ("LSpace", Shape::Hexa8, StressMode::ThreeD, 8),
    ("LTRSpace", Shape::Tet4, StressMode::ThreeD, 1),
    ("LWedge", Shape::Wedge6, StressMode::ThreeD, 6),
    ("QTRSpace", Shape::Tet10, StressMode::ThreeD, 4),
    ("QSpace", Shape::Hexa20, StressMode::ThreeD, 27),
];

/// The point states `law` starts from at the `npoints` points of kernel `k`, and those a first
/// step to displacements `u1` leaves (its committed state): (virgin, committed).
pub(crate) fn first_step_state(
    k: &dyn ElementKernel,
    law: &dyn hertz::material::PointLaw,
    npoints: usize,
    x: &[[f64; 3]],
    u1: &[f64],
) -> (Vec<f64>, Vec<f64>) {
    let n = law.state_len();
    let mut virgin = vec![0.0; n * npoints];
    for g in 0..npoints {
        law.initial_state(&mut virgin[g * n..(g + 1) * n]);
    }
    let mut old = vec![0.0; virgin.len()];
    let mut f = vec![0.0; u1.len()];
    k.evaluate_into(x, u1, (&virgin, &mut old), &mut f, None, None)
        .unwrap();
    (virgin, old)
}

/// The largest difference between `k`'s tangent at displacements `u` (from the committed point
/// states `old`) and central differences of its force with step `h`, relative to the tangent's
/// largest entry.
pub(crate) fn tangent_error(
    k: &dyn ElementKernel,
    x: &[[f64; 3]],
    u: &[f64],
    old: &[f64],
    h: f64,
) -> f64 {
    let nd = u.len();
    let mut new = vec![0.0; old.len()];
    let (mut f, mut kt) = (vec![0.0; nd], vec![0.0; nd * nd]);
    k.evaluate_into(x, u, (old, &mut new), &mut f, Some(&mut kt), None)
        .unwrap();
    let scale = kt.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut worst: f64 = 0.0;
    for j in 0..nd {
        let (mut up, mut um) = (u.to_vec(), u.to_vec());
        up[j] += h;
        um[j] -= h;
        let (mut fp, mut fm) = (vec![0.0; nd], vec![0.0; nd]);
        k.evaluate_into(x, &up, (old, &mut new), &mut fp, None, None)
            .unwrap();
        k.evaluate_into(x, &um, (old, &mut new), &mut fm, None, None)
            .unwrap();
        for i in 0..nd {
            let fd = (fp[i] - fm[i]) / (2.0 * h);
            worst = worst.max((fd - kt[i * nd + j]).abs() / scale);
        }
    }
    worst
}

/// `corners` followed by the midpoints of `edges` (the quadratic element's mid-edge nodes).
fn with_mid_edges(corners: Vec<[f64; 3]>, edges: &[&[usize]]) -> Vec<[f64; 3]> {
    let mut v = corners.clone();
    for e in edges {
        v.push(std::array::from_fn(|k| {
            0.5 * (corners[e[0]][k] + corners[e[1]][k])
        }));
    }
    v
}

/// The node positions of a reference element (quadratic ones with straight edges).
fn reference_nodes(shape: Shape) -> Vec<[f64; 3]> {
    match shape {
        Shape::Quad4 => vec![
            [1.0, 1.0, 0.0],
            [-1.0, 1.0, 0.0],
            [-1.0, -1.0, 0.0],
            [1.0, -1.0, 0.0],
        ],
        Shape::Tri3 => vec![[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 0.0]],
        Shape::Quad8 => vec![
            [1.0, 1.0, 0.0],
            [-1.0, 1.0, 0.0],
            [-1.0, -1.0, 0.0],
            [1.0, -1.0, 0.0],
            [0.0, 1.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.0, -1.0, 0.0],
            [1.0, 0.0, 0.0],
        ],
        Shape::Hexa8 => vec![
            [-1.0, -1.0, 1.0],
            [-1.0, 1.0, 1.0],
            [1.0, 1.0, 1.0],
            [1.0, -1.0, 1.0],
            [-1.0, -1.0, -1.0],
            [-1.0, 1.0, -1.0],
            [1.0, 1.0, -1.0],
            [1.0, -1.0, -1.0],
        ],
        Shape::Tet4 => vec![
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, 0.0],
        ],
        Shape::Hexa20 => with_mid_edges(reference_nodes(Shape::Hexa8), Shape::Hexa8.edges()),
        Shape::Tet10 => with_mid_edges(reference_nodes(Shape::Tet4), Shape::Tet4.edges()),
        Shape::Wedge6 => vec![
            [0.0, 0.0, -1.0],
            [1.0, 0.0, -1.0],
            [0.0, 1.0, -1.0],
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 1.0],
            [0.0, 1.0, 1.0],
        ],
        _ => unreachable!(),
    }
}

/// A distorted reference element: node positions of the shape perturbed a little.
pub(crate) fn distorted_nodes(shape: Shape) -> Vec<[f64; 3]> {
    reference_nodes(shape)
        .iter()
        .enumerate()
        .map(|(a, x)| {
            let s = 0.07 * ((a as f64 * 1.7).sin());
            let z = if shape.dim() == 3 {
                x[2] + 0.05 * ((a as f64 * 2.3).cos())
            } else {
                0.0
            };
            [x[0] + s, x[1] - 0.6 * s, z]
        })
        .collect()
}

fn kernel<'a>(
    shape: Shape,
    _mode: StressMode,
    q: &'a [hertz::fem::QuadPoint],
    law: &'a Law,
    nlgeo: bool,
) -> ContinuumKernel<'a> {
    ContinuumKernel {
        shape,
        nsd: shape.dim(),
        rule: q,
        material: law.as_ref(),
        thick: 0.7,
        nlgeo,
        bbar: false,
        hoop: None,
    }
}

/// The tangent of every continuum element is the Jacobian of its internal force (central
/// differences), in small strain and in total Lagrangian large deformation, with linear
/// elasticity (St. Venant–Kirchhoff) and the hyperelastic laws.
#[test]
fn continuum_tangent_is_jacobian_of_internal_force() {
    for (name, shape, mode, nip) in CONTINUUM {
        for nlgeo in [false, true] {
            for law in laws(mode, nlgeo) {
                let q = rule(shape, nip).unwrap();
                let k = kernel(shape, mode, &q, &law, nlgeo);
                let x = distorted_nodes(shape);
                let nd = shape.n_nodes() * shape.dim();
                let u: Vec<f64> = (0..nd)
                    .map(|i| 0.15 * ((i as f64 * 0.9 + 0.3).sin()))
                    .collect();
                let mut f = vec![0.0; nd];
                let mut kt = vec![0.0; nd * nd];
                k.evaluate_into(&x, &u, (&[], &mut []), &mut f, Some(&mut kt), None)
                    .unwrap();
                let h = 1e-6;
                let scale = kt.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                let mut worst: f64 = 0.0;
                for j in 0..nd {
                    let (mut up, mut um) = (u.clone(), u.clone());
                    up[j] += h;
                    um[j] -= h;
                    let (mut fp, mut fm) = (vec![0.0; nd], vec![0.0; nd]);
                    k.evaluate_into(&x, &up, (&[], &mut []), &mut fp, None, None)
                        .unwrap();
                    k.evaluate_into(&x, &um, (&[], &mut []), &mut fm, None, None)
                        .unwrap();
                    for i in 0..nd {
                        let fd = (fp[i] - fm[i]) / (2.0 * h);
                        worst = worst.max((fd - kt[i * nd + j]).abs() / scale);
                    }
                }
                assert!(
                    worst < 1e-7,
                    "{name} nlgeo {nlgeo} {law:?}: relative tangent error {worst:e}"
                );
                // The tangent is symmetric (the laws are hyperelastic).
                for i in 0..nd {
                    for j in 0..nd {
                        assert!(
                            (kt[i * nd + j] - kt[j * nd + i]).abs() < 1e-10 * scale,
                            "{name} {law:?} symmetric"
                        );
                    }
                }
            }
        }
    }
}

/// A large rigid rotation plus translation gives zero Green–Lagrange strain, zero stress and
/// zero internal force under nlgeo 1 (and, as a control, non-zero strain in small strain).
#[test]
fn rigid_body_motion_gives_zero_strain_under_nlgeo() {
    for (name, shape, mode, nip) in CONTINUUM {
        let q = rule(shape, nip).unwrap();
        let el: Law = std::sync::Arc::new(Elasticity::new(YOUNG, POISSON, mode));
        let x = distorted_nodes(shape);
        let (c, s) = (1.1f64.cos(), 1.1f64.sin());
        // 3D: rotation about an inclined axis; 2D: about z.
        let r: [[f64; 3]; 3] = if shape.dim() == 2 {
            [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]
        } else {
            let a = [1.0 / 3f64.sqrt(); 3];
            let mut r = [[0.0; 3]; 3];
            for i in 0..3 {
                for j in 0..3 {
                    let cross = match (i, j) {
                        (0, 1) => -a[2],
                        (0, 2) => a[1],
                        (1, 0) => a[2],
                        (1, 2) => -a[0],
                        (2, 0) => -a[1],
                        (2, 1) => a[0],
                        _ => 0.0,
                    };
                    r[i][j] = c * f64::from(u8::from(i == j)) + s * cross + (1.0 - c) * a[i] * a[j];
                }
            }
            r
        };
        let d = shape.dim();
        let mut u = Vec::new();
        for p in &x {
            for i in 0..d {
                u.push((0..d).map(|j| r[i][j] * p[j]).sum::<f64>() - p[i] + 0.3 * (i as f64 + 1.0));
            }
        }
        let nd = u.len();
        for nlgeo in [true, false] {
            let k = kernel(shape, mode, &q, &el, nlgeo);
            let mut f = vec![0.0; nd];
            let mut st: Vec<GpState> = Vec::new();
            k.evaluate_into(&x, &u, (&[], &mut []), &mut f, None, Some(&mut st))
                .unwrap();
            let emax = st
                .iter()
                .flat_map(|g| g.strain)
                .fold(0.0f64, |m, v| m.max(v.abs()));
            if nlgeo {
                assert!(emax < 1e-14, "{name}: Green–Lagrange strain {emax:e}");
                assert!(
                    f.iter().all(|v| v.abs() < 1e-12),
                    "{name}: internal force of a rigid motion"
                );
            } else {
                assert!(
                    emax > 0.1,
                    "{name}: small strain is not rotation invariant ({emax})"
                );
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Patch tests through the whole program (reader, DOF numbering, assembly, solver).

struct Patch {
    domain: &'static str,
    nodes: Vec<[f64; 3]>,
    /// (element keyword, node numbers 1-based, extra keywords)
    elements: Vec<(&'static str, Vec<usize>, String)>,
    boundary: Vec<bool>,
    dofs: Vec<u8>,
    /// DOFs prescribed on interior nodes too (a straight bar chain has no transverse stiffness).
    interior_fixed: Vec<u8>,
    cs: &'static str,
}

fn grid(
    n: [usize; 3],
) -> (
    Vec<[f64; 3]>,
    impl Fn(usize, usize, usize) -> usize,
    Vec<bool>,
) {
    let idx = move |i: usize, j: usize, k: usize| (k * (n[1] + 1) + j) * (n[0] + 1) + i;
    let mut x = Vec::new();
    let mut bnd = Vec::new();
    for k in 0..=n[2] {
        for j in 0..=n[1] {
            for i in 0..=n[0] {
                let on = |v: usize, m: usize| v == 0 || v == m;
                let interior = !on(i, n[0]) && !on(j, n[1]) && (n[2] == 0 || !on(k, n[2]));
                // Distort interior nodes so the elements are not parallelograms.
                let d = if interior {
                    [0.13, -0.11, 0.09]
                } else {
                    [0.0; 3]
                };
                x.push([
                    i as f64 + d[0],
                    j as f64 + d[1],
                    k as f64 + if n[2] == 0 { 0.0 } else { d[2] },
                ]);
                bnd.push(!interior);
            }
        }
    }
    (x, idx, bnd)
}

fn patch_2d(kind: &'static str) -> Patch {
    let (mut nodes, idx, mut boundary) = grid([2, 2, 0]);
    let mut elements = Vec::new();
    let domain = if kind.contains("Strain") {
        "PlaneStrain"
    } else {
        "2dPlaneStress"
    };
    for j in 0..2 {
        for i in 0..2 {
            // OOFEM quad order: (x1,y1), (x0,y1), (x0,y0), (x1,y0).
            let q = [
                idx(i + 1, j + 1, 0),
                idx(i, j + 1, 0),
                idx(i, j, 0),
                idx(i + 1, j, 0),
            ];
            match kind {
                "TrPlaneStress2d" | "TrPlaneStrain" => {
                    elements.push((kind, vec![q[0] + 1, q[1] + 1, q[2] + 1], String::new()));
                    elements.push((kind, vec![q[0] + 1, q[2] + 1, q[3] + 1], String::new()));
                }
                "QPlaneStress2d" => {
                    let mut ids: Vec<usize> = q.iter().map(|v| v + 1).collect();
                    for s in 0..4 {
                        let (a, b) = (q[s], q[(s + 1) % 4]);
                        let m = [0, 1, 2].map(|c| 0.5 * (nodes[a][c] + nodes[b][c]));
                        let found = nodes
                            .iter()
                            .position(|p| (0..3).all(|c| (p[c] - m[c]).abs() < 1e-12));
                        let id = found.unwrap_or_else(|| {
                            nodes.push(m);
                            let on = |v: f64| v.abs() < 1e-12 || (v - 2.0).abs() < 1e-12;
                            boundary.push((on(m[0]) || on(m[1])) && boundary[a] && boundary[b]);
                            nodes.len() - 1
                        });
                        ids.push(id + 1);
                    }
                    elements.push((kind, ids, "nip 9".into()));
                }
                _ => elements.push((kind, q.iter().map(|v| v + 1).collect(), String::new())),
            }
        }
    }
    Patch {
        domain,
        nodes,
        elements,
        boundary,
        dofs: vec![1, 2],
        interior_fixed: vec![],
        cs: "thick 0.5",
    }
}

/// Append to the element `ids` (1-based, its corners) the mid-edge nodes of its `edges`, shared
/// between elements: found among `nodes` or added, on the patch's boundary when they lie on a
/// face of the cube [0, 2]³.
fn add_mid_edges(
    nodes: &mut Vec<[f64; 3]>,
    boundary: &mut Vec<bool>,
    ids: &mut Vec<usize>,
    edges: &[&[usize]],
) {
    let corners = ids.clone();
    for e in edges {
        let (pa, pb) = (corners[e[0]] - 1, corners[e[1]] - 1);
        let m = [0, 1, 2].map(|k| 0.5 * (nodes[pa][k] + nodes[pb][k]));
        let found = nodes
            .iter()
            .position(|p| (0..3).all(|k| (p[k] - m[k]).abs() < 1e-12));
        let id = found.unwrap_or_else(|| {
            nodes.push(m);
            let on = |v: f64| v.abs() < 1e-12 || (v - 2.0).abs() < 1e-12;
            boundary.push(m.iter().any(|&v| on(v)));
            nodes.len() - 1
        });
        ids.push(id + 1);
    }
}

fn patch_3d(kind: &'static str) -> Patch {
    let (mut nodes, idx, mut boundary) = grid([2, 2, 2]);
    let mut elements = Vec::new();
    for k in 0..2 {
        for j in 0..2 {
            for i in 0..2 {
                let c = |a: usize, b: usize, d: usize| idx(i + a, j + b, k + d) + 1;
                match kind {
                    "LSpace" => elements.push((
                        kind,
                        HEXA8_CORNERS.iter().map(|p| c(p[0], p[1], p[2])).collect(),
                        String::new(),
                    )),
                    "QSpace" => {
                        let mut ids: Vec<usize> =
                            HEXA8_CORNERS.iter().map(|p| c(p[0], p[1], p[2])).collect();
                        add_mid_edges(&mut nodes, &mut boundary, &mut ids, Shape::Hexa8.edges());
                        elements.push((kind, ids, String::new()));
                    }
                    "LWedge" => {
                        elements.push((
                            kind,
                            vec![
                                c(0, 0, 0),
                                c(1, 0, 0),
                                c(1, 1, 0),
                                c(0, 0, 1),
                                c(1, 0, 1),
                                c(1, 1, 1),
                            ],
                            String::new(),
                        ));
                        elements.push((
                            kind,
                            vec![
                                c(0, 0, 0),
                                c(1, 1, 0),
                                c(0, 1, 0),
                                c(0, 0, 1),
                                c(1, 1, 1),
                                c(0, 1, 1),
                            ],
                            String::new(),
                        ));
                    }
                    _ => {
                        // Kuhn split of the cube into 6 tetrahedra along the (0,0,0)-(1,1,1) diagonal.
                        for p in [
                            [0, 1, 2],
                            [0, 2, 1],
                            [1, 0, 2],
                            [1, 2, 0],
                            [2, 0, 1],
                            [2, 1, 0],
                        ] {
                            let mut v = [0usize; 3];
                            let mut ids = vec![c(0, 0, 0)];
                            for &ax in &p[..2] {
                                v[ax] = 1;
                                ids.push(c(v[0], v[1], v[2]));
                            }
                            ids.push(c(1, 1, 1));
                            if kind == "QTRSpace" {
                                let edges = Shape::Tet4.edges();
                                add_mid_edges(&mut nodes, &mut boundary, &mut ids, edges);
                            }
                            elements.push((kind, ids, String::new()));
                        }
                    }
                }
            }
        }
    }
    Patch {
        domain: "3d",
        nodes,
        elements,
        boundary,
        dofs: vec![1, 2, 3],
        interior_fixed: vec![],
        cs: "",
    }
}

fn patch_truss(kind: &'static str) -> Patch {
    // A straight chain of 3 bars with an inclined axis (Truss2d cs 1: x–y plane).
    let dir = if kind == "Truss1d" {
        [1.0, 0.0, 0.0]
    } else {
        [0.8, 0.6, 0.0]
    };
    let nodes: Vec<[f64; 3]> = [0.0, 0.7, 1.9, 3.0]
        .iter()
        .map(|s| [s * dir[0], s * dir[1], 0.0])
        .collect();
    let extra = if kind == "Truss2d" {
        "cs 1".to_string()
    } else {
        String::new()
    };
    let elements = (0..3)
        .map(|e| (kind, vec![e + 1, e + 2], extra.clone()))
        .collect();
    let (domain, dofs, interior_fixed) = if kind == "Truss1d" {
        ("1dTruss", vec![1], vec![])
    } else {
        ("PlaneStrain", vec![1, 2], vec![2])
    };
    Patch {
        domain,
        nodes,
        elements,
        boundary: vec![true, false, false, true],
        dofs,
        interior_fixed,
        cs: "area 0.3",
    }
}

/// Solve the patch with u = field(X) prescribed on boundary nodes; return (u per node, GP states).
fn solve_patch(
    p: &Patch,
    field: &dyn Fn([f64; 3]) -> [f64; 3],
    nlgeo: bool,
) -> (Vec<[f64; 3]>, Vec<Vec<GpState>>) {
    let prescribed = |i: usize| {
        if p.boundary[i] {
            p.dofs.clone()
        } else {
            p.interior_fixed.clone()
        }
    };
    let nb = (0..p.nodes.len())
        .filter(|&i| !prescribed(i).is_empty())
        .count();
    let mut s = String::from(
        "patch.out\ngenerated patch test\nStaticStructural nsteps 1 rtolf 1e-13 maxiter 20\n",
    );
    let _ = writeln!(s, "domain {}\nOutputManager", p.domain);
    let _ = writeln!(
        s,
        "ndofman {} nelem {} ncrosssect 1 nmat 1 nbc {nb} nic 0 nltf 1 nset {}",
        p.nodes.len(),
        p.elements.len(),
        nb + 1
    );
    for (i, x) in p.nodes.iter().enumerate() {
        let _ = writeln!(s, "node {} coords 3 {} {} {}", i + 1, x[0], x[1], x[2]);
    }
    for (e, (kind, ids, extra)) in p.elements.iter().enumerate() {
        let ids: Vec<String> = ids.iter().map(|v| v.to_string()).collect();
        let nl = if nlgeo { "nlgeo 1" } else { "" };
        let _ = writeln!(
            s,
            "{kind} {} nodes {} {} {extra} {nl}",
            e + 1,
            ids.len(),
            ids.join(" ")
        );
    }
    let _ = writeln!(s, "SimpleCS 1 {} material 1 set 1", p.cs);
    let _ = writeln!(s, "IsoLE 1 d 0 E {} n {} tAlpha 0", YOUNG, POISSON);
    let mut k = 0;
    let mut sets = String::from("Set 1 allelements\n");
    for (i, x) in p.nodes.iter().enumerate() {
        let fixed = prescribed(i);
        if fixed.is_empty() {
            continue;
        }
        k += 1;
        let u = field(*x);
        let ids: Vec<String> = fixed.iter().map(|d| d.to_string()).collect();
        let vals: Vec<String> = fixed
            .iter()
            .map(|&d| format!("{:e}", u[d as usize - 1]))
            .collect();
        let n = fixed.len();
        let _ = writeln!(
            s,
            "BoundaryCondition {k} loadTimeFunction 1 dofs {n} {} values {n} {} set {}",
            ids.join(" "),
            vals.join(" "),
            k + 1
        );
        let _ = writeln!(sets, "Set {} nodes 1 {}", k + 1, i + 1);
    }
    s.push_str("ConstantFunction 1 f(t) 1.0\n");
    s.push_str(&sets);
    let model = common::model_from_text(&s).unwrap_or_else(|e| panic!("{e}"));
    let mut out = (Vec::new(), Vec::new());
    run_analysis(&model, &common::quiet(), |r| {
        out.0 = (0..model.nodes.len())
            .map(|n| [1u8, 2, 3].map(|d| r.displacement(n, d).unwrap_or(0.0)))
            .collect();
        out.1 = r.states.to_vec();
        Ok(())
    })
    .unwrap_or_else(|e| panic!("{e}"));
    out
}

/// Linear field u = c + G·X; small-strain patch: every node and every GP is exact.
#[test]
fn patch_test_small_strain_every_element_type() {
    let g = [
        [0.012, -0.007, 0.004],
        [0.003, -0.009, 0.006],
        [-0.005, 0.002, 0.011],
    ];
    let field = |x: [f64; 3]| {
        [0, 1, 2].map(|i| 0.01 * (i as f64 + 1.0) + (0..3).map(|j| g[i][j] * x[j]).sum::<f64>())
    };
    let kinds = [
        "PlaneStress2d",
        "Quad1PlaneStrain",
        "TrPlaneStress2d",
        "TrPlaneStrain",
        "QPlaneStress2d",
        "LSpace",
        "LTRSpace",
        "LWedge",
        "QTRSpace",
        "QSpace",
        "Truss1d",
        "Truss2d",
    ];
    for kind in kinds {
        let p = match kind {
            "LSpace" | "LTRSpace" | "LWedge" | "QTRSpace" | "QSpace" => patch_3d(kind),
            "Truss1d" | "Truss2d" => patch_truss(kind),
            _ => patch_2d(kind),
        };
        let dim = p.dofs.len();
        let gl = |i: usize, j: usize| if i < dim && j < dim { g[i][j] } else { 0.0 };
        let field_d = |x: [f64; 3]| {
            let f = field(x);
            [0, 1, 2].map(|i| if i < dim { f[i] } else { 0.0 })
        };
        let (u, states) = solve_patch(&p, &field_d, false);
        for (n, x) in p.nodes.iter().enumerate() {
            let e = field_d(*x);
            for i in 0..dim {
                assert!(
                    (u[n][i] - e[i]).abs() < 1e-12,
                    "{kind}: node {} dof {} = {} expected {}",
                    n + 1,
                    i + 1,
                    u[n][i],
                    e[i]
                );
            }
        }
        let expected_strain: [f64; 6] = if kind.starts_with("Truss") {
            let d = [p.nodes[1][0] - p.nodes[0][0], p.nodes[1][1] - p.nodes[0][1]];
            let l = (d[0] * d[0] + d[1] * d[1]).sqrt();
            let e = [d[0] / l, d[1] / l];
            let mut eps = 0.0;
            for i in 0..dim {
                for j in 0..dim {
                    eps += e[i] * gl(i, j) * e[j];
                }
            }
            [eps, 0.0, 0.0, 0.0, 0.0, 0.0]
        } else {
            let mut v = [
                gl(0, 0),
                gl(1, 1),
                gl(2, 2),
                gl(1, 2) + gl(2, 1),
                gl(0, 2) + gl(2, 0),
                gl(0, 1) + gl(1, 0),
            ];
            if dim == 2 {
                v[2] = 0.0;
            }
            v
        };
        for (e, st) in states.iter().enumerate() {
            for (gp, s) in st.iter().enumerate() {
                for c in 0..6 {
                    assert!(
                        (s.strain[c] - expected_strain[c]).abs() < 1e-12,
                        "{kind}: element {} gp {} strain {} = {} expected {}",
                        e + 1,
                        gp + 1,
                        c + 1,
                        s.strain[c],
                        expected_strain[c]
                    );
                }
            }
        }
    }
}

/// Pure bending (curvature κ about y) is a quadratic displacement field that solves linear
/// elasticity exactly: u = κxz, v = −νκyz, w = −κ(x² + ν(z² − y²))/2, σ_xx = Eκz and no other
/// stress. Prescribed on the boundary of the distorted patch, the 10-node tetrahedra reproduce
/// it at every interior node and integration point; the 4-node ones cannot (their error here is
/// what the quadratic element removes).
#[test]
fn quadratic_tetrahedra_are_exact_in_pure_bending() {
    let k = 0.01;
    let field = |x: [f64; 3]| {
        [
            k * x[0] * x[2],
            -POISSON * k * x[1] * x[2],
            -0.5 * k * (x[0] * x[0] + POISSON * (x[2] * x[2] - x[1] * x[1])),
        ]
    };
    let worst = |kind: &'static str| {
        let p = patch_3d(kind);
        let (u, states) = solve_patch(&p, &field, false);
        let nodal = p
            .nodes
            .iter()
            .zip(&u)
            .flat_map(|(x, un)| {
                let e = field(*x);
                (0..3).map(move |i| (un[i] - e[i]).abs())
            })
            .fold(0.0, f64::max);
        // σ_yy, σ_zz and the shears vanish; σ_xx = Eκz lies within the patch's z range.
        let stress = states
            .iter()
            .flatten()
            .flat_map(|s| s.stress[1..].to_vec())
            .map(f64::abs)
            .fold(0.0, f64::max);
        if kind == "QTRSpace" {
            for s in states.iter().flatten() {
                assert!(s.stress[0] >= -1e-9 && s.stress[0] <= YOUNG * k * 2.0 + 1e-9);
            }
        }
        (nodal, stress / (YOUNG * k))
    };
    let (nodal, stress) = worst("QTRSpace");
    assert!(
        nodal < 1e-12 && stress < 1e-10,
        "QTRSpace: {nodal:e}, {stress:e}"
    );
    let (nodal, _) = worst("LTRSpace");
    assert!(nodal > 1e-5, "LTRSpace: {nodal:e}");
}

/// A uniform traction p on the faces x = 2 of the distorted QTRSpace and QSpace patches (a
/// `ConstantSurfaceLoad` on those 6- and 8-node faces: the consistent loads of quadratic faces),
/// with rollers on x = 0, y = 0 and z = 0: uniaxial stress, u = p/E · (x, −νy, −νz) at every
/// node, exact.
#[test]
fn a_surface_load_on_quadratic_3d_elements_gives_uniaxial_stress() {
    for (kind, shape, corners, n_faces) in [
        ("QTRSpace", Shape::Tet10, 3, 8),
        ("QSpace", Shape::Hexa20, 4, 4),
    ] {
        traction_on_quadratic_faces(kind, shape, corners, n_faces);
    }
}

fn traction_on_quadratic_faces(kind: &'static str, shape: Shape, corners: usize, n_faces: usize) {
    let p = patch_3d(kind);
    let pressure = 3.0;
    let on = |v: f64, w: f64| (v - w).abs() < 1e-12;
    let mut faces = Vec::new();
    for (e, (_, ids, _)) in p.elements.iter().enumerate() {
        for (b, local) in shape.boundaries().iter().enumerate() {
            if local[..corners]
                .iter()
                .all(|&a| on(p.nodes[ids[a] - 1][0], 2.0))
            {
                faces.push(format!("{} {}", e + 1, b + 1));
            }
        }
    }
    assert_eq!(faces.len(), n_faces, "{kind}: the faces at x = 2");
    let mut s = String::from(
        "traction.out\nuniaxial traction\nLinearStatic nsteps 1\ndomain 3d\nOutputManager\n",
    );
    let _ = writeln!(
        s,
        "ndofman {} nelem {} ncrosssect 1 nmat 1 nbc 4 nic 0 nltf 1 nset 5",
        p.nodes.len(),
        p.elements.len()
    );
    for (i, x) in p.nodes.iter().enumerate() {
        let _ = writeln!(s, "node {} coords 3 {} {} {}", i + 1, x[0], x[1], x[2]);
    }
    for (e, (kind, ids, _)) in p.elements.iter().enumerate() {
        let ids: Vec<String> = ids.iter().map(|v| v.to_string()).collect();
        let _ = writeln!(s, "{kind} {} nodes {} {}", e + 1, ids.len(), ids.join(" "));
    }
    let _ = writeln!(
        s,
        "SimpleCS 1 material 1 set 1\nIsoLE 1 d 0 E {YOUNG} n {POISSON} tAlpha 0"
    );
    for d in 1..=3 {
        let _ = writeln!(
            s,
            "BoundaryCondition {d} loadTimeFunction 1 dofs 1 {d} values 1 0 set {}",
            d + 1
        );
    }
    let _ = writeln!(
        s,
        "ConstantSurfaceLoad 4 loadTimeFunction 1 dofs 3 1 2 3 components 3 {pressure} 0 0 set 5"
    );
    s.push_str("ConstantFunction 1 f(t) 1.0\nSet 1 allelements\n");
    for d in 0..3 {
        let ids: Vec<String> = (0..p.nodes.len())
            .filter(|&i| on(p.nodes[i][d], 0.0))
            .map(|i| (i + 1).to_string())
            .collect();
        let _ = writeln!(s, "Set {} nodes {} {}", d + 2, ids.len(), ids.join(" "));
    }
    let _ = writeln!(
        s,
        "Set 5 elementboundaries {} {}",
        2 * faces.len(),
        faces.join(" ")
    );
    let model = common::model_from_text(&s).unwrap_or_else(|e| panic!("{e}"));
    let mut worst = f64::NAN;
    run_analysis(&model, &common::quiet(), |r| {
        worst = 0.0;
        for (n, x) in p.nodes.iter().enumerate() {
            let e = [x[0], -POISSON * x[1], -POISSON * x[2]].map(|v| pressure / YOUNG * v);
            for d in 0..3 {
                worst = worst.max((r.displacement(n, d as u8 + 1).unwrap() - e[d]).abs());
            }
        }
        Ok(())
    })
    .unwrap();
    assert!(worst < 1e-12, "{kind}: error {worst:e}");
}

/// Where contact on quadratic faces is not supported, a condition on them is an input error at
/// its record, never read as linear faces: mortar from the 6-node faces of QTRSpace against a
/// rigid plane (mortar on quadratic faces meets element faces only), and node-to-segment contact of the nodes of QSpace's 8-node faces (a uniform pressure
/// pulls on their corners, which no node-to-face constraint can hold).
#[test]
fn contact_on_quadratic_faces_is_refused_where_unsupported() {
    for (kind, shape, condition, expect) in [
        (
            "QTRSpace",
            Shape::Tet10,
            "s2spenaltycontact 2 loadTimeFunction 1 penalty 10 slavesegment 1 segmentset 1 2",
            "meets element faces, not rigid shapes",
        ),
        (
            "QSpace",
            Shape::Hexa20,
            "n2spenaltycontact 2 loadTimeFunction 1 penalty 10 nodeset 8 1 2 3 4 9 10 11 12 \
             segmentset 1 2",
            "node-to-segment contact cannot hold its corners",
        ),
    ] {
        let nodes = distorted_nodes(shape);
        let n = nodes.len();
        let mut s = format!(
            "t.out\none {kind}\nStaticStructural nsteps 1\ndomain 3d\nOutputManager\n\
             ndofman {} nelem 1 ncrosssect 1 nmat 1 nbc 2 nic 0 nltf 1 nset 3 ncontactseg 2\n",
            n + 1
        );
        for (i, x) in nodes.iter().enumerate() {
            let _ = writeln!(s, "node {} coords 3 {} {} {}", i + 1, x[0], x[1], x[2]);
        }
        let list: Vec<String> = (1..=n).map(|k| k.to_string()).collect();
        let _ = write!(
            s,
            "node {} coords 3 0.3 0.3 -0.5\n\
             {kind} 1 nodes {n} {}\n\
             linear3delementsurfacecontactsegment 1 boundaryset 3\n\
             planecontactsegment 2 point 3 0 0 -1 normal 3 0 0 1\n\
             SimpleCS 1 material 1 set 1\nIsoLE 1 d 0 E 1 n 0.3 tAlpha 0\n\
             BoundaryCondition 1 loadTimeFunction 1 dofs 3 1 2 3 values 3 0 0 0 set 2\n\
             {condition}\n\
             ConstantFunction 1 f(t) 1.0\nSet 1 allelements\nSet 2 nodes 1 1\n\
             Set 3 elementboundaries 2 1 1\n",
            n + 1,
            list.join(" ")
        );
        let e = common::model_from_text(&s)
            .and_then(|m| hertz::contact::ContactSystem::new(&m).map(|_| ()))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains(expect) && e.contains(condition.split_whitespace().next().unwrap()),
            "{kind}: {e}"
        );
    }
}

/// Homogeneous large deformation x = F·X prescribed on the boundary: under nlgeo 1 the interior
/// nodes follow F·X exactly and every GP carries E = ½(FᵀF − I).
#[test]
fn patch_test_total_lagrangian_every_continuum_element() {
    let f3 = [[1.25, 0.18, -0.07], [-0.12, 0.9, 0.1], [0.05, -0.08, 1.15]];
    for (kind, shape, _, _) in CONTINUUM {
        let p = if shape.dim() == 3 {
            patch_3d(kind)
        } else {
            patch_2d(kind)
        };
        let d = shape.dim();
        let f = |i: usize, j: usize| {
            if i < d && j < d {
                f3[i][j]
            } else if i == j {
                1.0
            } else {
                0.0
            }
        };
        let field = |x: [f64; 3]| {
            [0, 1, 2].map(|i| {
                if i < d {
                    (0..d).map(|j| f(i, j) * x[j]).sum::<f64>() - x[i]
                } else {
                    0.0
                }
            })
        };
        let (u, states) = solve_patch(&p, &field, true);
        for (n, x) in p.nodes.iter().enumerate() {
            let e = field(*x);
            for i in 0..d {
                assert!(
                    (u[n][i] - e[i]).abs() < 1e-10,
                    "{kind}: node {} dof {}: {} vs {}",
                    n + 1,
                    i + 1,
                    u[n][i],
                    e[i]
                );
            }
        }
        let mut ee = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                ee[i][j] = 0.5
                    * ((0..3).map(|k| f(k, i) * f(k, j)).sum::<f64>()
                        - if i == j { 1.0 } else { 0.0 });
            }
        }
        let expected = [
            ee[0][0],
            ee[1][1],
            if d == 3 { ee[2][2] } else { 0.0 },
            2.0 * ee[1][2],
            2.0 * ee[0][2],
            2.0 * ee[0][1],
        ];
        for st in &states {
            for s in st {
                for c in 0..6 {
                    assert!(
                        (s.strain[c] - expected[c]).abs() < 1e-10,
                        "{kind}: E{} = {} expected {}",
                        c + 1,
                        s.strain[c],
                        expected[c]
                    );
                }
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Edge tractions on 2D element boundaries.

/// A 2 × 1 plate of two quadrilaterals (or four triangles), thickness 0.5, E = 100, ν = 0.3,
/// held at x = 0 and pulled by the traction p = 3 on its right edge, given by `set3` (the edge
/// set). Uniform stress σ_xx = p: u_x = p·x/E and u_y = −ν·p·y/E, exact on any such mesh.
fn traction_plate(kind: &str, set3: &str) -> String {
    let elements = match kind {
        "PlaneStress2d" => "PlaneStress2d 1 nodes 4 5 4 1 2\nPlaneStress2d 2 nodes 4 6 5 2 3\n",
        _ => {
            "TrPlaneStress2d 1 nodes 3 5 4 1\nTrPlaneStress2d 2 nodes 3 5 1 2\n\
              TrPlaneStress2d 3 nodes 3 6 5 2\nTrPlaneStress2d 4 nodes 3 6 2 3\n"
        }
    };
    let nelem = elements.lines().count();
    format!(
        "plate.out\nedge traction on a plate\nLinearStatic nsteps 1\ndomain 2dPlaneStress\n\
         OutputManager\n\
         ndofman 6 nelem {nelem} ncrosssect 1 nmat 1 nbc 3 nic 0 nltf 1 nset 4\n\
         node 1 coords 2 0 0\nnode 2 coords 2 1 0\nnode 3 coords 2 2 0\n\
         node 4 coords 2 0 1\nnode 5 coords 2 1 1\nnode 6 coords 2 2 1\n\
         {elements}SimpleCS 1 thick 0.5 material 1 set 1\nIsoLE 1 d 0 E {YOUNG} n {POISSON} tAlpha 0\n\
         BoundaryCondition 1 loadTimeFunction 1 dofs 1 1 values 1 0 set 2\n\
         BoundaryCondition 2 loadTimeFunction 1 dofs 1 2 values 1 0 set 4\n\
         ConstantEdgeLoad 3 loadTimeFunction 1 dofs 2 1 2 components 2 3.0 0 set 3\n\
         ConstantFunction 1 f(t) 1.0\n\
         Set 1 allelements\nSet 2 nodes 2 1 4\n{set3}\nSet 4 nodes 1 1\n"
    )
}

/// An edge load on `elementboundaries` of 2D elements acts on those edges, exactly as on
/// `elementedges` (a Gmsh physical curve becomes `elementboundaries`).
#[test]
fn edge_load_on_2d_element_boundaries_acts_on_the_edges() {
    // The right edge: nodes 3 and 6. Quadrilateral 2 (6 5 2 3): boundary 4 (3 -> 6); triangle 4
    // (6 2 3): boundary 3 (3 -> 6).
    for (kind, edge) in [("PlaneStress2d", "2 4"), ("TrPlaneStress2d", "4 3")] {
        for key in ["elementboundaries", "elementedges"] {
            let text = traction_plate(kind, &format!("Set 3 {key} 2 {edge}"));
            let model = common::model_from_text(&text).unwrap_or_else(|e| panic!("{e}"));
            let mut u = Vec::new();
            run_analysis(&model, &common::quiet(), |r| {
                u = (0..6)
                    .map(|n| [r.displacement(n, 1).unwrap(), r.displacement(n, 2).unwrap()])
                    .collect();
                Ok(())
            })
            .unwrap();
            for (n, x) in [
                [0.0, 0.0],
                [1.0, 0.0],
                [2.0, 0.0],
                [0.0, 1.0],
                [1.0, 1.0],
                [2.0, 1.0],
            ]
            .iter()
            .enumerate()
            {
                let exact = [3.0 * x[0] / YOUNG, -POISSON * 3.0 * x[1] / YOUNG];
                for d in 0..2 {
                    assert!(
                        (u[n][d] - exact[d]).abs() < 1e-12,
                        "{kind} {key}: node {} u{} = {} (exact {})",
                        n + 1,
                        d + 1,
                        u[n][d],
                        exact[d]
                    );
                }
            }
        }
    }
}

/// A load whose set has nothing it can act on is an input error at the load's line, never a
/// run that applies nothing.
#[test]
fn a_load_that_would_act_on_nothing_is_an_input_error() {
    for (set3, expected) in [
        (
            "Set 3 nodes 2 3 6",
            "ConstantEdgeLoad 3 acts on set 3, which has no element edges",
        ),
        (
            "Set 3 elements 1 2",
            "ConstantEdgeLoad 3 acts on set 3, which has no element edges",
        ),
    ] {
        let text = traction_plate("PlaneStress2d", set3);
        let err = common::model_from_text(&text).unwrap_err();
        assert!(err.to_string().contains(expected), "{err}");
        assert!(
            err.to_string().contains(":19:"),
            "names the load's line: {err}"
        );
    }
    let surface = traction_plate("PlaneStress2d", "Set 3 elementboundaries 2 2 4")
        .replace("ConstantEdgeLoad 3", "ConstantSurfaceLoad 3");
    let err = common::model_from_text(&surface).unwrap_err();
    assert!(
        err.to_string().contains(
            "ConstantSurfaceLoad 3 acts on set 3, which names boundaries of 2D element 2"
        ),
        "{err}"
    );
    let bc = traction_plate("PlaneStress2d", "Set 3 elementboundaries 2 2 4")
        .replace("Set 4 nodes 1 1", "Set 4 nodes 0");
    let err = common::model_from_text(&bc).unwrap_err();
    assert!(
        err.to_string()
            .contains("BoundaryCondition 2 acts on set 4, which has no nodes"),
        "{err}"
    );
}

/// A load on element boundaries shared by two elements (inside the mesh) is read with a warning
/// naming the load and the elements: a traction inside a body is rarely meant.
#[test]
fn a_load_on_interior_boundaries_is_warned_about() {
    // Quadrilateral 1 (5 4 1 2), boundary 4: the edge 2-5 it shares with quadrilateral 2.
    let text = traction_plate("PlaneStress2d", "Set 3 elementboundaries 2 1 4");
    let path = std::env::temp_dir().join(format!("hertz-interior-{}.in", std::process::id()));
    std::fs::write(&path, text).unwrap();
    let read = hertz::input::read_model(&path).unwrap();
    std::fs::remove_file(&path).ok();
    assert!(
        read.warnings.iter().any(|w| w
            .contains(":19: ConstantEdgeLoad 3 lies on 1 element boundary shared by two elements")),
        "{:?}",
        read.warnings
    );
    let outer = traction_plate("PlaneStress2d", "Set 3 elementboundaries 2 2 4");
    std::fs::write(&path, outer).unwrap();
    let read = hertz::input::read_model(&path).unwrap();
    std::fs::remove_file(&path).ok();
    assert!(read.warnings.is_empty(), "{:?}", read.warnings);
}

/// A plane-stress Mooney–Rivlin sheet (2 × 1, four PlaneStress2d, `nlgeo 1`) stretched by 30 %
/// and compressed by 20 % along x on rollers is in uniaxial stress: its nominal stress is the
/// closed form's at that stretch (P₂₂ = P₃₃ = 0) and its width follows the lateral stretch.
#[test]
fn plane_stress_hyperelastic_sheet_is_in_uniaxial_stress() {
    use hertz_bench::verify::uniaxial_stress;
    let law = MooneyRivlin {
        c1: 20.0,
        c2: 5.0,
        k: 80.0,
    };
    for stretch in [1.3, 0.8] {
        let text = format!(
            "sheet.out\nsheet\nNonLinearStatic nsteps 4 controlmode 1 rtolf 1e-12 maxiter 20\n\
             domain 2dPlaneStress\nOutputManager\n\
             ndofman 15 nelem 8 ncrosssect 1 nmat 1 nbc 3 nic 0 nltf 1 nset 4\n{}{}\
             SimpleCS 1 thick 0.5 material 1 set 1\n\
             MooneyRivlinCompressibleMat 1 d 0 c1 20 c2 5 k 80\n\
             BoundaryCondition 1 loadTimeFunction 1 dofs 1 1 values 1 0 set 2\n\
             BoundaryCondition 2 loadTimeFunction 1 dofs 1 2 values 1 0 set 3\n\
             BoundaryCondition 3 loadTimeFunction 1 dofs 1 1 values 1 {} set 4\n\
             PiecewiseLinFunction 1 npoints 2 t 2 0 3 f(t) 2 0 1\n\
             Set 1 allelements\nSet 2 nodes 3 1 6 11\nSet 3 nodes 5 1 2 3 4 5\n\
             Set 4 nodes 3 5 10 15\n",
            (0..15)
                .map(|k| format!(
                    "node {} coords 2 {} {}\n",
                    k + 1,
                    0.5 * (k % 5) as f64,
                    0.5 * (k / 5) as f64
                ))
                .collect::<String>(),
            (0..8)
                .map(|e| {
                    let (i, j) = (e % 4, e / 4);
                    let n = |i: usize, j: usize| j * 5 + i + 1;
                    format!(
                        "PlaneStress2d {} nodes 4 {} {} {} {} nlgeo 1\n",
                        e + 1,
                        n(i + 1, j + 1),
                        n(i, j + 1),
                        n(i, j),
                        n(i + 1, j)
                    )
                })
                .collect::<String>(),
            2.0 * (stretch - 1.0)
        );
        let model = common::model_from_text(&text).unwrap_or_else(|e| panic!("{e}"));
        let (lateral, nominal) = uniaxial_stress(&law, stretch);
        let mut last = (0.0, 0.0);
        run_analysis(&model, &common::quiet(), |r| {
            // The pulled edge's reaction over the reference section (height 1, thickness 0.5).
            let pulled: f64 = r
                .dofs
                .prescribed
                .iter()
                .zip(r.reactions)
                .filter(|((_, d, bc), _)| *d == 1 && model.dirichlet[*bc].number == 3)
                .map(|(_, f)| f)
                .sum();
            let top = model.nodes.iter().position(|n| n.label == 15).unwrap();
            last = (pulled / 0.5, 1.0 + r.displacement(top, 2).unwrap());
            Ok(())
        })
        .unwrap();
        assert!(
            (last.0 - nominal).abs() < 1e-8 * nominal.abs(),
            "{stretch}: P {} vs {nominal}",
            last.0
        );
        assert!(
            (last.1 - lateral).abs() < 1e-10,
            "{stretch}: width {} vs {lateral}",
            last.1
        );
    }
}

/// The barred quadrilateral and brick (B-bar in small strain, F-bar in large deformation):
/// the tangent is the Jacobian of the internal force with every law, the plastic one from a
/// committed plastic state; a homogeneous deformation gives the plain element's answer (the
/// centre's volume change is every point's), so the patch test holds.
#[test]
fn barred_tangents_are_jacobians_and_homogeneous_fields_are_unchanged() {
    use hertz::material::plasticity::mises_law;
    let plastic = hertz::model::Mises {
        young: YOUNG,
        poisson: POISSON,
        hardening: hertz::model::Hardening::Linear {
            sig0: 2.0,
            modulus: 5.0,
        },
        kinematic: 0.0,
        damage: None,
    };
    for (shape, mode, nip) in [
        (Shape::Quad4, StressMode::PlaneStrain, 4),
        (Shape::Hexa8, StressMode::ThreeD, 8),
    ] {
        for nlgeo in [false, true] {
            let mut all = laws(mode, nlgeo);
            all.push(mises_law(&plastic, mode, nlgeo));
            for law in all {
                let q = rule(shape, nip).unwrap();
                let mut k = kernel(shape, mode, &q, &law, nlgeo);
                k.bbar = true;
                let x = distorted_nodes(shape);
                let nd = shape.n_nodes() * shape.dim();
                let n = law.state_len();
                let mut virgin = vec![0.0; n * q.len()];
                for g in 0..q.len() {
                    law.initial_state(&mut virgin[g * n..(g + 1) * n]);
                }
                let u1: Vec<f64> = (0..nd)
                    .map(|i| 0.05 * ((i as f64 * 0.9 + 0.3).sin()))
                    .collect();
                let mut old = vec![0.0; virgin.len()];
                let mut f = vec![0.0; nd];
                k.evaluate_into(&x, &u1, (&virgin, &mut old), &mut f, None, None)
                    .unwrap();
                let u: Vec<f64> = u1.iter().map(|v| 1.3 * v).collect();
                let worst = tangent_error(&k, &x, &u, &old, 1e-7);
                assert!(
                    worst < 1e-6,
                    "{shape:?} nlgeo {nlgeo} {law:?}: relative tangent error {worst:e}"
                );
                // A homogeneous deformation: the barred element's forces are the plain one's.
                let grad = [
                    [0.02, 0.01, -0.005],
                    [-0.004, -0.01, 0.003],
                    [0.006, 0.002, 0.01],
                ];
                let uh: Vec<f64> = x
                    .iter()
                    .flat_map(|p| {
                        (0..shape.dim())
                            .map(|i| (0..shape.dim()).map(|j| grad[i][j] * p[j]).sum::<f64>())
                            .collect::<Vec<_>>()
                    })
                    .collect();
                let (mut fb, mut fplain) = (vec![0.0; nd], vec![0.0; nd]);
                let mut new = vec![0.0; virgin.len()];
                k.evaluate_into(&x, &uh, (&virgin, &mut new), &mut fb, None, None)
                    .unwrap();
                k.bbar = false;
                k.evaluate_into(&x, &uh, (&virgin, &mut new), &mut fplain, None, None)
                    .unwrap();
                let fs = fplain.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                for i in 0..nd {
                    assert!(
                        (fb[i] - fplain[i]).abs() < 1e-12 * fs,
                        "{shape:?} nlgeo {nlgeo} {law:?}: homogeneous field changed"
                    );
                }
            }
        }
    }
}

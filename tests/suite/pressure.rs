//! Pressure normal to a surface (`csType 1`) on 3D faces, and follower pressure (`follower`) on
//! the current boundary in large deformation: 2D edges, axisymmetric edges and 3D faces against
//! Lamé's shells and the closed-form inflation of an incompressible neo-Hookean tube.

use hertz::fem::shape::{Shape, HEXA8_CORNERS};
use std::collections::HashMap;

const YOUNG: f64 = 1000.0;
const NU: f64 = 0.3;

/// A map of the unit cube [0,1]³ onto a curved block.
type Patch = Box<dyn Fn([f64; 3]) -> [f64; 3]>;

/// A mesh of QSpace (20-node) bricks over `patches`, each cut into n[0] × n[1] × n[2] cells of
/// its unit cube, every node (mid-sides too) placed by the map: curved faces where the map
/// curves. Nodes the patches share are merged by position.
struct Bricks {
    nodes: Vec<[f64; 3]>,
    cells: Vec<Vec<usize>>,
}

impl Bricks {
    fn new(patches: &[Patch], n: [usize; 3]) -> Bricks {
        let mut nodes: Vec<[f64; 3]> = Vec::new();
        let mut index: HashMap<[i64; 3], usize> = HashMap::new();
        let mut node = |x: [f64; 3]| {
            let key = x.map(|c| (c * 1e8).round() as i64);
            *index.entry(key).or_insert_with(|| {
                nodes.push(x);
                nodes.len() - 1
            })
        };
        let mut cells = Vec::new();
        for map in patches {
            for i in 0..n[0] {
                for j in 0..n[1] {
                    for k in 0..n[2] {
                        let at = |c: [f64; 3]| {
                            map([
                                (i as f64 + c[0]) / n[0] as f64,
                                (j as f64 + c[1]) / n[1] as f64,
                                (k as f64 + c[2]) / n[2] as f64,
                            ])
                        };
                        let corner = |a: usize| HEXA8_CORNERS[a].map(|v| v as f64);
                        let mut cell: Vec<usize> = (0..8).map(|a| node(at(corner(a)))).collect();
                        for edge in Shape::Hexa8.edges() {
                            let (p, q) = (corner(edge[0]), corner(edge[1]));
                            cell.push(node(at(std::array::from_fn(|d| 0.5 * (p[d] + q[d])))));
                        }
                        cells.push(cell);
                    }
                }
            }
        }
        Bricks { nodes, cells }
    }

    /// The faces (element label, boundary number) whose nodes all satisfy `on`.
    fn faces_where(&self, on: impl Fn([f64; 3]) -> bool) -> Vec<(usize, usize)> {
        let mut out = Vec::new();
        for (e, cell) in self.cells.iter().enumerate() {
            for (b, local) in Shape::Hexa20.boundaries().iter().enumerate() {
                if local.iter().all(|&a| on(self.nodes[cell[a]])) {
                    out.push((e + 1, b + 1));
                }
            }
        }
        out
    }

    /// The input: `material`, `analysis` with time function 1, rollers on the planes x = 0,
    /// y = 0 and z = 0 (and u_z = 0 everywhere when `plane_strain`), and `load` (a
    /// ConstantSurfaceLoad record without its set) on the faces on the sphere (or cylinder) of
    /// radius `bore`.
    fn input(&self, setup: &Setup, load: &str, bore: f64, plane_strain: bool) -> String {
        let Setup {
            material,
            analysis,
            function,
            nlgeo,
        } = setup;
        let radius = |x: [f64; 3]| {
            if plane_strain {
                x[0].hypot(x[1])
            } else {
                (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt()
            }
        };
        let faces = self.faces_where(|x| (radius(x) - bore).abs() < 1e-9);
        let on_plane = |d: usize| -> Vec<String> {
            (0..self.nodes.len())
                .filter(|&k| plane_strain && d == 2 || self.nodes[k][d].abs() < 1e-9)
                .map(|k| (k + 1).to_string())
                .collect()
        };
        let mut text = format!(
            "shell.out\npressurized shell\n{analysis}\ndomain 3d\nOutputManager\n\
             ndofman {} nelem {} ncrosssect 1 nmat 1 nbc 4 nic 0 nltf 1 nset 5\n",
            self.nodes.len(),
            self.cells.len()
        );
        for (k, x) in self.nodes.iter().enumerate() {
            text += &format!(
                "node {} coords 3 {:.15} {:.15} {:.15}\n",
                k + 1,
                x[0],
                x[1],
                x[2]
            );
        }
        let nl = if *nlgeo { " nlgeo 1" } else { "" };
        for (e, cell) in self.cells.iter().enumerate() {
            let list: Vec<String> = cell.iter().map(|v| (v + 1).to_string()).collect();
            text += &format!(
                "QSpace {} nodes 20 {} crossSect 1 mat 1{nl}\n",
                e + 1,
                list.join(" ")
            );
        }
        text += &format!("SimpleCS 1 material 1 set 1\n{material}\n");
        for d in 0..3 {
            text += &format!(
                "BoundaryCondition {} loadTimeFunction 1 dofs 1 {} values 1 0 set {}\n",
                d + 1,
                d + 1,
                d + 2
            );
        }
        text += &format!("{load} set 5\n{function}\nSet 1 allelements\n");
        for d in 0..3 {
            let list = on_plane(d);
            text += &format!("Set {} nodes {} {}\n", d + 2, list.len(), list.join(" "));
        }
        let list: Vec<String> = faces.iter().map(|(e, b)| format!("{e} {b}")).collect();
        text += &format!(
            "Set 5 elementboundaries {} {}\n",
            2 * faces.len(),
            list.join(" ")
        );
        text
    }
}

/// What a shell model is made of besides its mesh and load.
struct Setup {
    material: String,
    analysis: String,
    /// Time function 1's record.
    function: String,
    nlgeo: bool,
}

/// The octant of a thick spherical shell (radii a and b) as three patches, each the directions
/// around one axis (a cubed sphere), n cells a side.
fn sphere_octant(a: f64, b: f64) -> Vec<Patch> {
    (0..3)
        .map(|axis| -> Patch {
            Box::new(move |c: [f64; 3]| {
                let r = a + (b - a) * c[0];
                // The direction: 1 along `axis`, tan of angles up to 45° along the others.
                let mut d = [0.0; 3];
                d[axis] = 1.0;
                d[(axis + 1) % 3] = (0.25 * std::f64::consts::PI * c[1]).tan();
                d[(axis + 2) % 3] = (0.25 * std::f64::consts::PI * c[2]).tan();
                let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                d.map(|v| r * v / len)
            })
        })
        .collect()
}

/// A quarter of a thick cylinder (radii a and b), one unit long.
fn cylinder_quarter(a: f64, b: f64) -> Vec<Patch> {
    vec![Box::new(move |c: [f64; 3]| {
        let r = a + (b - a) * c[0];
        let t = 0.5 * std::f64::consts::PI * c[1];
        [r * t.cos(), r * t.sin(), c[2]]
    })]
}

/// The largest relative error of the outer surface's displacement (radius `b`, in the plane
/// z = const when `planar`) against the radial `exact`, tangential parts counted as errors.
fn outer_error(text: &str, b: f64, planar: bool, exact: f64) -> f64 {
    let model = crate::common::model_from_text(text).unwrap();
    let mut worst: f64 = 0.0;
    hertz::solve::run_analysis(&model, &crate::common::quiet(), |r| {
        for (k, node) in model.nodes.iter().enumerate() {
            let mut x = node.coords;
            if planar {
                x[2] = 0.0;
            }
            let len = (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt();
            if (len - b).abs() > 1e-9 {
                continue;
            }
            let u: Vec<f64> = (1..=3).map(|d| r.displacement(k, d).unwrap()).collect();
            let radial = (0..3).map(|d| u[d] * x[d] / b).sum::<f64>();
            let along: Vec<f64> = (0..3).map(|d| u[d] - radial * x[d] / b).collect();
            let tangential = (along.iter().map(|v| v * v).sum::<f64>()).sqrt();
            worst = worst
                .max((radial / exact - 1.0).abs())
                .max(tangential / exact);
        }
        Ok(())
    })
    .unwrap();
    worst
}

/// A pressure normal to curved 3D faces (`csType 1`, components (0, 0, −p): against the outward
/// normal) on 20-node bricks: a thick sphere's octant (a cubed sphere, three patches) and a
/// quarter of a thick cylinder in plane strain under internal pressure 10 move their outer
/// surface radially by Lamé's u(b) (as the axisymmetric and plane strain tests), the error
/// falling at the element's order from 2 to 4 cells a side. Measured: sphere 4.3e-3, 3.6e-4;
/// cylinder 7.0e-4, 5.2e-5.
#[test]
fn a_pressure_normal_to_curved_faces_inflates_shells_as_lame() {
    let (p, a, b) = (10.0f64, 1.0f64, 2.0f64);
    let g = YOUNG / (2.0 * (1.0 + NU));
    let k = YOUNG / (3.0 * (1.0 - 2.0 * NU));
    let sphere = p * a.powi(3) * (b / (3.0 * k) + b / (4.0 * g)) / (b.powi(3) - a.powi(3));
    let cylinder = 2.0 * p * a * a * b * (1.0 - NU * NU) / (YOUNG * (b * b - a * a));
    let setup = Setup {
        material: format!("IsoLE 1 d 0 E {YOUNG} n {NU} tAlpha 0"),
        analysis: "LinearStatic nsteps 1".into(),
        function: "ConstantFunction 1 f(t) 1".into(),
        nlgeo: false,
    };
    let load = format!(
        "ConstantSurfaceLoad 4 loadTimeFunction 1 components 3 0 0 {} csType 1",
        -p
    );
    for (name, exact) in [("sphere", sphere), ("cylinder", cylinder)] {
        let error = |n: usize| {
            let cylinder = name == "cylinder";
            let (patches, cells) = match cylinder {
                false => (sphere_octant(a, b), [n, n, n]),
                true => (cylinder_quarter(a, b), [n, 2 * n, 1]),
            };
            let text = Bricks::new(&patches, cells).input(&setup, &load, a, cylinder);
            outer_error(&text, b, name == "cylinder", exact)
        };
        let (coarse, fine) = (error(2), error(4));
        assert!(
            fine < 1e-3 && fine < coarse / 8.0,
            "{name}: {coarse:e}, {fine:e}"
        );
    }
}

/// A 2D mesh of 8-node quadrilaterals of `keyword` over the unit square's map `map`, n[0] × n[1]
/// cells, as node and element records (OOFEM's node order), with the edges (element,
/// boundary number) on the square's side ξ₀ = 0 and the nodes where `held(ξ, d)` holds DOF d.
struct Quads {
    nodes: Vec<String>,
    elements: Vec<String>,
    bore: Vec<(usize, usize)>,
    held: [Vec<usize>; 2],
}

impl Quads {
    fn new(
        keyword: &str,
        map: impl Fn([f64; 2]) -> [f64; 2],
        n: [usize; 2],
        held: impl Fn([f64; 2], usize) -> bool,
    ) -> Quads {
        let m = [2 * n[0], 2 * n[1]];
        let id = |i: usize, j: usize| i * (m[1] + 1) + j + 1;
        let on = |i: usize, j: usize| !(i % 2 == 1 && j % 2 == 1);
        let mut q = Quads {
            nodes: Vec::new(),
            elements: Vec::new(),
            bore: Vec::new(),
            held: [Vec::new(), Vec::new()],
        };
        for i in 0..=m[0] {
            for j in (0..=m[1]).filter(|&j| on(i, j)) {
                let xi = [i as f64 / m[0] as f64, j as f64 / m[1] as f64];
                let [x, y] = map(xi);
                q.nodes
                    .push(format!("node {} coords 2 {x:.15} {y:.15}", id(i, j)));
                for d in 0..2 {
                    if held(xi, d) {
                        q.held[d].push(id(i, j));
                    }
                }
            }
        }
        for i in 0..n[0] {
            for j in 0..n[1] {
                let c = |a: usize, b: usize| id(2 * i + a, 2 * j + b);
                let label = q.elements.len() + 1;
                q.elements
                    .extend(crate::common::cell_records(keyword, label, 8, c));
                if i == 0 {
                    // Edge 4 of OOFEM's quadrilateral runs from its node 4 to 1: the cell's ξ₀ = 0.
                    q.bore.push((label, 4));
                }
            }
        }
        q
    }

    /// The input: like [`Bricks::input`], on `domain`, `load` a ConstantEdgeLoad record without
    /// its set (`#` for its number), on the bore.
    fn input(&self, setup: &Setup, domain: &str, load: &str) -> String {
        let nl = if setup.nlgeo { " nlgeo 1" } else { "" };
        let list = |v: &[usize]| {
            let s: Vec<String> = v.iter().map(|x| x.to_string()).collect();
            format!("{} {}", v.len(), s.join(" "))
        };
        let bore: Vec<String> = self.bore.iter().map(|(e, b)| format!("{e} {b}")).collect();
        let (mut bcs, mut sets) = (Vec::new(), Vec::new());
        for (d, nodes) in self.held.iter().enumerate().filter(|(_, v)| !v.is_empty()) {
            let set = sets.len() + 3;
            bcs.push(format!(
                "BoundaryCondition {} loadTimeFunction 1 dofs 1 {} values 1 0 set {set}",
                bcs.len() + 1,
                d + 1
            ));
            sets.push(format!("Set {set} nodes {}", list(nodes)));
        }
        let load = load.replacen('#', &(bcs.len() + 1).to_string(), 1);
        format!(
            "tube.out\ntube\n{}\ndomain {domain}\nOutputManager\n\
             ndofman {} nelem {} ncrosssect 1 nmat 1 nbc {} nic 0 nltf 1 nset {}\n{}\n{}\n\
             SimpleCS 1 thick 1 material 1 set 1\n{}\n{}\n\
             {load} set 2\n{}\nSet 1 allelements\nSet 2 elementboundaries {} {}\n{}\n",
            setup.analysis,
            self.nodes.len(),
            self.elements.len(),
            bcs.len() + 1,
            sets.len() + 2,
            self.nodes.join("\n"),
            self.elements
                .iter()
                .map(|e| format!("{e}{nl}"))
                .collect::<Vec<_>>()
                .join("\n"),
            setup.material,
            bcs.join("\n"),
            setup.function,
            2 * bore.len(),
            bore.join(" "),
            sets.join("\n"),
        )
    }
}

/// The pressure that inflates an incompressible neo-Hookean tube (shear modulus μ, radii A and
/// B, plane strain) to the bore stretch λ_a = a/A: p = μ/2 [ln(λ_a²/λ_b²) + 1/λ_b² − 1/λ_a²]
/// with λ_b² = 1 + (λ_a² − 1) A²/B² (σ_θ − σ_r = μ(λ² − λ⁻²) integrated over the wall).
fn tube_pressure(mu: f64, (a, b): (f64, f64), stretch: f64) -> f64 {
    let la2 = stretch * stretch;
    let lb2 = 1.0 + (la2 - 1.0) * a * a / (b * b);
    0.5 * mu * ((la2 / lb2).ln() + 1.0 / lb2 - 1.0 / la2)
}

/// The inflated tube's inputs (plane strain, axisymmetric, 3D), its pressure a follower load or
/// not, with the pressure `p` of the closed form at a bore stretch of 1.6.
pub(crate) fn inflated_tube(follower: bool) -> (f64, [(&'static str, String); 3]) {
    let (a, b, mu) = (1.0, 2.0, 1.0);
    let p = tube_pressure(mu, (a, b), 1.6);
    let steps = 8;
    let setup = Setup {
        material: format!(
            "MooneyRivlinCompressibleMat 1 d 0 c1 {} c2 0 k {}",
            mu / 2.0,
            2000.0 * mu
        ),
        analysis: format!(
            "NonLinearStatic nsteps {steps} controlmode 1 rtolf 1e-10 maxiter 20 manrmsteps 1 \
             refloadmode 1 deltat 1"
        ),
        function: format!(
            "PiecewiseLinFunction 1 t 2 -1 {steps} f(t) 2 0 {}",
            (steps + 1) as f64 / steps as f64
        ),
        nlgeo: true,
    };
    let quarter = |xi: [f64; 2]| {
        let r = a + (b - a) * xi[0];
        let t = 0.5 * std::f64::consts::PI * xi[1];
        [r * t.cos(), r * t.sin()]
    };
    let tail = if follower { " follower" } else { "" };
    let edge = format!(
        "ConstantEdgeLoad # loadTimeFunction 1 components 2 0 {} csType 1{tail}",
        -p
    );
    let face = format!(
        "ConstantSurfaceLoad 4 loadTimeFunction 1 components 3 0 0 {} csType 1{tail}",
        -p
    );
    let models = [
        (
            "plane strain",
            Quads::new("QPlaneStrain", quarter, [4, 4], |xi, d| {
                (d == 0 && xi[1] == 1.0) || (d == 1 && xi[1] == 0.0)
            })
            .input(&setup, "PlaneStrain", &edge),
        ),
        (
            "axisymmetric",
            Quads::new(
                "Q4Axisymm",
                |xi| [a + (b - a) * xi[0], 0.25 * xi[1]],
                [4, 1],
                |_, d| d == 1,
            )
            .input(&setup, "2dPlaneStress", &edge),
        ),
        (
            "3D",
            Bricks::new(&cylinder_quarter(a, b), [3, 4, 1]).input(&setup, &face, a, true),
        ),
    ];
    (p, models)
}

/// A follower pressure inflates a nearly incompressible neo-Hookean tube (Mooney–Rivlin with
/// c₂ = 0, K = 2000 μ; radii 1 and 2) in plane strain to 1.6 times its bore in large
/// deformation, modelled three ways: a quarter section of 8-node plane strain quadrilaterals,
/// an axisymmetric slice with the axial displacement held (8-node), and a quarter of 20-node
/// bricks with u_z held. Each bore stretch gives back the applied pressure through the
/// closed form within 0.5 %, Newton converging quadratically (at most 6 iterations a step to
/// rtolf 1e-10); the same pressure on the reference boundary (no `follower`) is far off (it
/// pushes on the reference bore, shorter by the stretch). Measured: plane strain 3.0e-4,
/// axisymmetric 2.4e-4, 3D −6.0e-4, 4–6 iterations a step (residuals 3e-2, 3e-4, 1e-9); without
/// `follower` −26 % (stretch 1.35). The reactions of the plane x = 0 balance the pressure on the
/// current bore.
#[test]
fn a_follower_pressure_inflates_a_rubber_tube_as_the_closed_form() {
    let (a, b, mu) = (1.0, 2.0, 1.0);
    for follower in [true, false] {
        let (p, models) = inflated_tube(follower);
        for (name, text) in models {
            let model = crate::common::model_from_text(&text).unwrap();
            let mut bore = 0.0;
            let mut iterations = Vec::new();
            let mut pull = 0.0;
            hertz::solve::run_analysis(&model, &crate::common::quiet(), |r| {
                iterations.push(r.info.iterations);
                pull = (r.dofs.prescribed.iter().zip(r.reactions))
                    .filter(|((_, d, _), _)| *d == 1)
                    .map(|(_, f)| f)
                    .sum();
                let k = model
                    .nodes
                    .iter()
                    .position(|n| n.coords[0] == a && n.coords[1] == 0.0)
                    .unwrap();
                bore = r.displacement(k, 1).unwrap();
                Ok(())
            })
            .unwrap();
            let stretch = 1.0 + bore / a;
            let error = tube_pressure(mu, (a, b), stretch) / p - 1.0;
            // The x = 0 plane holds the quarter against the bore's pressure, p times the bore's
            // radius (current with `follower`, reference without) per unit length.
            if name != "axisymmetric" {
                let expected = -p * if follower { stretch * a } else { a };
                assert!(
                    (pull / expected - 1.0).abs() < 1e-8,
                    "{name}: {pull} vs {expected}"
                );
            }
            if follower {
                assert!(error.abs() < 5e-3, "{name}: {error:e}");
                assert!(iterations.iter().all(|&i| i <= 6), "{name}: {iterations:?}");
            } else {
                assert!(error.abs() > 0.1, "{name}: {error:e}");
            }
        }
    }
}

//! Generated hertz problems, for the tests and `hertz bench`: meshes of blocks ([`mesh`]), the
//! contact robustness suite ([`suite`]), the 3D verification problems in any element kind and
//! orientation ([`verify`]) and the inputs of `examples/` ([`examples`]); and the benchmark
//! block: a generated linear-elastic block (2D plane-strain quads or 3D bricks) under a uniform
//! traction, solved once with the production code path, with sizes, the time of every phase and
//! the peak memory. The block has roller supports on the faces x = 0, y = 0 (z = 0), so the
//! exact solution is the uniform uniaxial-stress field: its maximum nodal error is the
//! benchmark's self-check.

// Mesh generators index several arrays with one loop variable.
#![allow(clippy::needless_range_loop)]

use hertz::assembly::Assembler;
pub mod examples;
pub mod mesh;
pub mod suite;
pub mod verify;

use hertz::error::{Error, Result};
use hertz::fem::shape::HEXA8_CORNERS;
use hertz::input::read_model;
use hertz::solve::linear::{FaerSolver, LinearSolver, SolverSettings};
use hertz::solve::load_history::reference_load_vectors;
use hertz::solve::ordering::OrderingKind;
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

/// Material and load of the bench block.
pub const YOUNG: f64 = 210e3;
pub const POISSON: f64 = 0.3;
pub const TRACTION: f64 = 100.0;

/// Write the OOFEM input of a block of unit elements: 2D `2n × n` quads, 3D `n × n × n` bricks.
pub fn write_block_input(path: &Path, dim: usize, n: usize) -> Result<()> {
    let mut s = String::new();
    let (nx, ny, nz) = if dim == 2 { (2 * n, n, 0) } else { (n, n, n) };
    let nnodes = (nx + 1) * (ny + 1) * (nz + 1);
    let nel = if dim == 2 { nx * ny } else { nx * ny * nz };
    let id = |i: usize, j: usize, k: usize| (k * (ny + 1) + j) * (nx + 1) + i + 1;
    let _ = writeln!(
        s,
        "block.out\nbenchmark block {nx}x{ny}x{nz}\nStaticStructural nsteps 1"
    );
    let _ = writeln!(
        s,
        "domain {}\nOutputManager",
        if dim == 2 { "PlaneStrain" } else { "3d" }
    );
    let _ = writeln!(
        s,
        "ndofman {nnodes} nelem {nel} ncrosssect 1 nmat 1 nbc {} nic 0 nltf 1 nset {}",
        dim + 1,
        dim + 2
    );
    for k in 0..=nz {
        for j in 0..=ny {
            for i in 0..=nx {
                let _ = writeln!(s, "node {} coords 3 {i} {j} {k}", id(i, j, k));
            }
        }
    }
    let mut e = 0;
    let mut loaded = Vec::new();
    for k in 0..nz.max(1) {
        for j in 0..ny {
            for i in 0..nx {
                e += 1;
                if dim == 2 {
                    let _ = writeln!(
                        s,
                        "Quad1PlaneStrain {e} nodes 4 {} {} {} {}",
                        id(i + 1, j + 1, 0),
                        id(i, j + 1, 0),
                        id(i, j, 0),
                        id(i + 1, j, 0)
                    );
                    if i + 1 == nx {
                        // Quad edge 4 = nodes (4, 1): the x = max side.
                        loaded.push(format!("{e} 4"));
                    }
                } else {
                    let ids: Vec<String> = HEXA8_CORNERS
                        .iter()
                        .map(|c| id(i + c[0], j + c[1], k + c[2]).to_string())
                        .collect();
                    let _ = writeln!(s, "LSpace {e} nodes 8 {}", ids.join(" "));
                    if i + 1 == nx {
                        // Hexa surface 5 = nodes (3, 4, 8, 7): the x = max face.
                        loaded.push(format!("{e} 5"));
                    }
                }
            }
        }
    }
    let _ = writeln!(s, "SimpleCS 1 thick 1.0 material 1 set 1");
    let _ = writeln!(s, "IsoLE 1 d 0. E {YOUNG} n {POISSON} tAlpha 0.");
    for d in 1..=dim {
        let _ = writeln!(
            s,
            "BoundaryCondition {d} loadTimeFunction 1 dofs 1 {d} values 1 0.0 set {}",
            d + 1
        );
    }
    let dofs: Vec<String> = (1..=dim).map(|d| d.to_string()).collect();
    let comps: Vec<String> = (1..=dim)
        .map(|d| {
            if d == 1 {
                TRACTION.to_string()
            } else {
                "0".into()
            }
        })
        .collect();
    let kind = if dim == 2 {
        "ConstantEdgeLoad"
    } else {
        "ConstantSurfaceLoad"
    };
    let _ = writeln!(
        s,
        "{kind} {} loadTimeFunction 1 dofs {dim} {} components {dim} {} set {}",
        dim + 1,
        dofs.join(" "),
        comps.join(" "),
        dim + 2
    );
    let _ = writeln!(
        s,
        "ConstantFunction 1 f(t) 1.0\nSet 1 elementranges {{(1 {nel})}}"
    );
    for d in 0..dim {
        let mut nodes = Vec::new();
        for k in 0..=nz {
            for j in 0..=ny {
                for i in 0..=nx {
                    if [i, j, k][d] == 0 {
                        nodes.push(id(i, j, k).to_string());
                    }
                }
            }
        }
        let _ = writeln!(s, "Set {} nodes {} {}", d + 2, nodes.len(), nodes.join(" "));
    }
    let key = if dim == 2 {
        "elementedges"
    } else {
        "elementboundaries"
    };
    let _ = writeln!(
        s,
        "Set {} {key} {} {}",
        dim + 2,
        2 * loaded.len(),
        loaded.join(" ")
    );
    std::fs::write(path, s)
        .map_err(|e| Error::Output(format!("cannot write {}: {e}", path.display())))
}

/// Write the contact benchmark: a plane-strain block of `2n × n` unit quads whose bottom is pushed
/// up by `delta` against a fixed rigid circle of radius `2n` touching the middle of its top, with
/// node-to-segment contact on all top nodes, penalty (p = 1000 E) or `multipliers` (n = 200 gives
/// 161k unknowns).
pub fn write_contact_block_input(
    path: &Path,
    n: usize,
    delta: f64,
    multipliers: bool,
) -> Result<()> {
    let (nx, ny) = (2 * n, n);
    let id = |i: usize, j: usize| j * (nx + 1) + i + 1;
    let mut s = String::new();
    let _ = writeln!(s, "contact_block.out\ncontact benchmark block {nx}x{ny}\nStaticStructural nsteps 1 rtolf 1e-8 manrmsteps 1 maxiter 30");
    let _ = writeln!(s, "domain PlaneStrain\nOutputManager");
    let _ = writeln!(
        s,
        "ndofman {} nelem {} ncrosssect 1 nmat 1 nbc 2 nic 0 nltf 1 nset 2 ncontactseg 1",
        (nx + 1) * (ny + 1),
        nx * ny
    );
    for j in 0..=ny {
        for i in 0..=nx {
            let _ = writeln!(s, "node {} coords 2 {i} {j}", id(i, j));
        }
    }
    let mut e = 0;
    for j in 0..ny {
        for i in 0..nx {
            e += 1;
            let _ = writeln!(
                s,
                "Quad1PlaneStrain {e} nodes 4 {} {} {} {}",
                id(i + 1, j + 1),
                id(i, j + 1),
                id(i, j),
                id(i + 1, j)
            );
        }
    }
    let r = nx as f64;
    let _ = writeln!(
        s,
        "circlecontactsegment 1 centerpoint 2 {} {} radius {r}",
        n as f64 * 2.0 / 2.0 * 1.0 + (nx as f64 / 2.0 - n as f64),
        ny as f64 + r
    );
    let _ = writeln!(
        s,
        "SimpleCS 1 thick 1.0 material 1 set 1\nIsoLE 1 d 0. E {YOUNG} n {POISSON} tAlpha 0."
    );
    let _ = writeln!(
        s,
        "BoundaryCondition 1 loadTimeFunction 1 dofs 2 1 2 values 2 0.0 {delta} set 2"
    );
    let top: Vec<String> = (0..=nx).map(|i| id(i, ny).to_string()).collect();
    let law = if multipliers {
        "n2slagrangianmultipliercontact 2 loadTimeFunction 1".to_string()
    } else {
        format!(
            "n2spenaltycontact 2 loadTimeFunction 1 penalty {}",
            1e3 * YOUNG
        )
    };
    let _ = writeln!(
        s,
        "{law} nodeset {} {} segmentset 1 1",
        top.len(),
        top.join(" ")
    );
    let bottom: Vec<String> = (0..=nx).map(|i| id(i, 0).to_string()).collect();
    let _ = writeln!(
        s,
        "ConstantFunction 1 f(t) 1.0\nSet 1 elementranges {{(1 {})}}",
        nx * ny
    );
    let _ = writeln!(s, "Set 2 nodes {} {}", bottom.len(), bottom.join(" "));
    std::fs::write(path, s)
        .map_err(|e| Error::Output(format!("cannot write {}: {e}", path.display())))
}

/// Read a generated input file and remove it, whether it reads or not.
fn read_generated(path: &Path) -> Result<hertz::model::Model> {
    let read = read_model(path);
    let _ = std::fs::remove_file(path);
    Ok(read?.model)
}

/// Figures of the contact benchmark.
#[derive(Debug, Clone, Default)]
pub struct ContactBenchFigures {
    pub unknowns: usize,
    pub iterations: usize,
    pub active: usize,
    pub solve_s: f64,
    pub residual_history: Vec<f64>,
}

/// Run the contact benchmark of size `n` (block `2n × n`), with penalty or `multipliers`.
pub fn run_contact(n: usize, multipliers: bool) -> Result<ContactBenchFigures> {
    let path = std::env::temp_dir().join(format!("hertz-cbench-{}-{n}.in", std::process::id()));
    // Push by 1/40 of the block height: a contact zone of a few dozen nodes.
    write_contact_block_input(&path, n, n as f64 / 40.0, multipliers)?;
    let model = read_generated(&path)?;
    let mut f = ContactBenchFigures::default();
    let t = Instant::now();
    hertz::solve::run_analysis(
        &model,
        &hertz::solve::SolveParams {
            ..Default::default()
        },
        |r| {
            f.unknowns = r.dofs.n_free;
            f.iterations = r.info.iterations;
            f.active = r.contact.iter().filter(|c| c.active).count();
            f.residual_history = r.info.residual_history.clone();
            Ok(())
        },
    )?;
    f.solve_s = t.elapsed().as_secs_f64();
    Ok(f)
}

/// A 3D contact benchmark model (`hertz bench --sphere H` or `--patch N`).
#[derive(Debug, Clone, Copy)]
pub enum Model3d {
    /// The Hertz sphere of [`verify::HertzSphere`] of spacing h under the contact.
    Sphere(SphereBench),
    /// The patch test of [`verify::Patch`] (small strain, compressed by 0.01) with n × n × 2
    /// master bricks: a contact zone of (2n + 1)² nodes.
    Patch(PatchBench),
}

/// The Hertz sphere benchmark's mesh and contact.
#[derive(Debug, Clone, Copy)]
pub struct SphereBench {
    /// Element spacing under the contact.
    pub h: f64,
    /// Hexahedra or tetrahedra.
    pub kind: mesh::Solid,
    /// Mortar (the cap's bottom faces) instead of node-to-face (its bottom nodes).
    pub mortar: bool,
    /// The cap's whole bottom face as the slave side, else its part within 1.6 of the axis.
    pub whole_face: bool,
    /// Quadratic elements (10-node tetrahedra, 20-node bricks).
    pub quadratic: bool,
}

/// The patch benchmark's mesh and contact.
#[derive(Debug, Clone, Copy)]
pub struct PatchBench {
    /// Master bricks across (the slave has twice as many).
    pub n: usize,
    /// Mortar (the slave's bottom faces) instead of node-to-face (its bottom nodes).
    pub mortar: bool,
    /// 20-node bricks (QSpace).
    pub quadratic: bool,
}

/// Compression of the patch benchmark.
const PATCH_DELTA: f64 = 0.01;

impl Model3d {
    /// The penalty of the model's tests: 100 E per node on the sphere, 1000 E on the patch.
    pub fn penalty(self) -> f64 {
        match self {
            Model3d::Sphere(_) => 1e5,
            Model3d::Patch(_) => 1e6,
        }
    }

    pub fn input(self, law: suite::Law) -> String {
        match self {
            Model3d::Sphere(b) => verify::HertzSphere {
                kind: b.kind,
                sym: 0,
                h: b.h,
                delta: 0.15,
                nlgeo: false,
                law,
                mortar: b.mortar,
            }
            .input_of(
                if b.whole_face {
                    verify::HERTZ_CAP
                } else {
                    verify::HERTZ_NEAR
                },
                b.quadratic,
            ),
            Model3d::Patch(b) => {
                let patch = verify::Patch {
                    kind: mesh::Solid::Hex,
                    slave_kind: None,
                    sym: 0,
                    n: b.n,
                    nlgeo: false,
                    delta: PATCH_DELTA,
                    steps: 1,
                    law,
                    slave_n: None,
                    mortar: b.mortar,
                };
                if b.quadratic {
                    patch.input_quadratic()
                } else {
                    patch.input()
                }
            }
        }
    }

    fn describe(self) -> String {
        match self {
            Model3d::Sphere(b) => format!(
                "Hertz sphere on a block, {}{}, spacing {} under the contact, {}{}",
                if b.quadratic { "quadratic " } else { "" },
                if b.kind == mesh::Solid::Tet {
                    "tetrahedra"
                } else {
                    "hexahedra"
                },
                b.h,
                if b.mortar { "mortar" } else { "node-to-face" },
                if b.whole_face {
                    ", the whole cap face as slave"
                } else {
                    ""
                }
            ),
            Model3d::Patch(b) => format!(
                "contact patch test, {n} x {n} x 2 master {q}bricks, {m} x {m} x 2 slave bricks, {f}",
                n = b.n,
                m = 2 * b.n,
                q = if b.quadratic { "20-node " } else { "" },
                f = if b.mortar { "mortar" } else { "node-to-face" }
            ),
        }
    }

    /// The file name of the model's input.
    pub fn file(self) -> &'static str {
        match self {
            Model3d::Sphere(_) => "hertz3d.in",
            Model3d::Patch(_) => "patch3d.in",
        }
    }

    /// Relative errors against the exact solution, named.
    fn errors(
        self,
        model: &hertz::model::Model,
        states: &[hertz::contact::SlotState],
    ) -> Result<Vec<(&'static str, f64)>> {
        Ok(match self {
            Model3d::Sphere(_) => {
                let (e, nu) = (verify::E, verify::NU);
                let e_star = hertz::analytic::contact_modulus(e, nu, e, nu);
                let c =
                    hertz::analytic::compare_hertz_sphere(model, states, verify::HERTZ_R, e_star)
                        .ok_or_else(|| Error::Solve("the sphere made no contact".into()))?;
                vec![("p0 vs Hertz", c.p0_error()), ("a vs Hertz", c.a_error())]
            }
            Model3d::Patch(_) => {
                let exact = verify::E * PATCH_DELTA / (2.0 * verify::PATCH_H);
                let worst = states
                    .iter()
                    .map(|s| (s.pressure - exact).abs() / exact)
                    .fold(0.0, f64::max);
                vec![("worst nodal pressure vs exact", worst)]
            }
        })
    }
}

/// Figures of a 3D contact benchmark run.
#[derive(Debug, Clone, Default)]
pub struct Contact3dFigures {
    pub unknowns: usize,
    pub contact_nodes: usize,
    pub active: usize,
    pub iterations: usize,
    pub times: hertz::solve::PhaseTimes,
    /// GMRES iterations of the last linear solve (0: direct).
    pub krylov_iterations: usize,
    pub solve_s: f64,
    pub peak_rss_mb: f64,
    pub errors: Vec<(&'static str, f64)>,
}

/// Solve a 3D contact benchmark in one step with `law`.
pub fn run_contact3d(m: Model3d, law: suite::Law) -> Result<Contact3dFigures> {
    let path = std::env::temp_dir().join(format!("hertz-3dbench-{}.in", std::process::id()));
    std::fs::write(&path, m.input(law))
        .map_err(|e| Error::Output(format!("cannot write {}: {e}", path.display())))?;
    let model = read_generated(&path)?;
    let mut f = Contact3dFigures::default();
    let mut states = Vec::new();
    let t = Instant::now();
    hertz::solve::run_analysis(
        &model,
        &hertz::solve::SolveParams {
            ..Default::default()
        },
        |r| {
            f.unknowns = r.dofs.n_free;
            f.iterations = r.info.iterations;
            f.times = r.info.times;
            f.krylov_iterations = r.info.solver.krylov_iterations;
            states = r.contact.to_vec();
            Ok(())
        },
    )?;
    f.solve_s = t.elapsed().as_secs_f64();
    f.peak_rss_mb = peak_rss_mb();
    f.contact_nodes = states.len();
    f.active = states.iter().filter(|s| s.active).count();
    f.errors = m.errors(&model, &states)?;
    Ok(f)
}

pub fn print_contact3d(m: Model3d, law: suite::Law, f: &Contact3dFigures) {
    println!(
        "{}, {} (threads {})",
        m.describe(),
        match law {
            suite::Law::Multiplier => "multipliers".to_string(),
            suite::Law::Penalty(p) => format!("penalty {p:e}"),
        },
        rayon::current_num_threads()
    );
    let t = &f.times;
    println!("unknowns           {:>12}", f.unknowns);
    println!(
        "contact nodes      {:>12}   ({} active)",
        f.contact_nodes, f.active
    );
    println!("Newton iterations  {:>12}", f.iterations);
    println!("contact search     {:>12.3} s", t.search);
    println!("contact points     {:>12.3} s", t.contact);
    println!("assembly           {:>12.3} s", t.assembly);
    println!("factorization      {:>12.3} s", t.factor);
    println!("solves             {:>12.3} s", t.solve);
    if f.krylov_iterations > 0 {
        println!(
            "GMRES iterations   {:>12}   (last solve)",
            f.krylov_iterations
        );
    }
    println!("step (wall)        {:>12.3} s", f.solve_s);
    println!("peak memory        {:>12.1} MiB", f.peak_rss_mb);
    for (what, e) in &f.errors {
        println!("{what:<30} {:>+10.2e}", e);
    }
}

/// Figures of one bench run.
#[derive(Debug, Clone, Default)]
pub struct BenchFigures {
    pub unknowns: usize,
    pub matrix_nnz: usize,
    pub factor_nnz: usize,
    pub ordering: &'static str,
    pub read_s: f64,
    pub pattern_s: f64,
    pub assembly_s: f64,
    pub ordering_s: f64,
    pub symbolic_s: f64,
    pub numeric_s: f64,
    pub solve_s: f64,
    pub peak_rss_mb: f64,
    /// Largest |u − u_exact| over all DOFs, relative to the largest exact displacement.
    pub max_rel_error: f64,
}

/// Run the bench on a block of size `n` in `dim` dimensions.
pub fn run(dim: usize, n: usize, ordering: OrderingKind) -> Result<BenchFigures> {
    let path =
        std::env::temp_dir().join(format!("hertz-bench-{}-{dim}-{n}.in", std::process::id()));
    write_block_input(&path, dim, n)?;
    let mut f = BenchFigures::default();
    let t = Instant::now();
    let model = read_generated(&path)?;
    f.read_s = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let dofs = hertz::solve::number_dofs(&model)?;
    let asm = Assembler::new(&model, &dofs)?;
    f.pattern_s = t.elapsed().as_secs_f64();
    f.unknowns = dofs.n_free;
    f.matrix_nnz = 2 * asm.pattern.nnz() - asm.pattern.n;
    let u0 = vec![0.0; dofs.n_primary()];
    let t = Instant::now();
    let ev = asm.evaluate(&u0, true, false, None, &[])?;
    f.assembly_s = t.elapsed().as_secs_f64();
    let mut solver = FaerSolver::new(SolverSettings {
        ordering,
        groups: Some(dofs.free_eq_nodes()),
        ..Default::default()
    });
    let values = ev.k_values.as_ref().expect("tangent requested");
    solver.factorize(&asm.pattern, values, true, &|e| format!("equation {e}"))?;
    let mut rhs = vec![0.0; dofs.n_free];
    for (_, v) in reference_load_vectors(&model, &dofs)? {
        for (r, x) in rhs.iter_mut().zip(&v) {
            *r += x;
        }
    }
    solver.solve_in_place(&mut rhs)?;
    let st = solver.stats();
    f.ordering = st.ordering;
    f.ordering_s = st.ordering_seconds;
    f.symbolic_s = st.symbolic_seconds;
    f.numeric_s = st.numeric_seconds;
    f.solve_s = st.solve_seconds;
    f.factor_nnz = st.factor_nnz;
    f.peak_rss_mb = peak_rss_mb();
    // Exact uniaxial-stress field (plane strain in 2D).
    let (ex, et) = if dim == 2 {
        (
            (1.0 - POISSON * POISSON) * TRACTION / YOUNG,
            -POISSON * (1.0 + POISSON) * TRACTION / YOUNG,
        )
    } else {
        (TRACTION / YOUNG, -POISSON * TRACTION / YOUNG)
    };
    let mut u = vec![0.0; dofs.n_primary()];
    u[..dofs.n_free].copy_from_slice(&rhs);
    let (mut err, mut umax) = (0.0f64, 0.0f64);
    for (n, node) in model.nodes.iter().enumerate() {
        for &(d, code) in &dofs.node_dofs[n] {
            let exact = node.coords[d as usize - 1] * if d == 1 { ex } else { et };
            err = err.max((dofs.value(&u, code) - exact).abs());
            umax = umax.max(exact.abs());
        }
    }
    f.max_rel_error = err / umax;
    Ok(f)
}

/// Peak resident memory of this process (VmHWM), in MiB; 0 where /proc is unavailable.
pub fn peak_rss_mb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1)?.parse::<f64>().ok())
        })
        .map(|kb| kb / 1024.0)
        .unwrap_or(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bench_blocks_reproduce_the_exact_uniform_field_with_amd_and_metis() {
        for (dim, n) in [(2, 6), (3, 4)] {
            for ord in [OrderingKind::Amd, OrderingKind::Metis] {
                let f = run(dim, n, ord).unwrap();
                assert!(
                    f.max_rel_error < 1e-10,
                    "dim {dim} {ord:?}: {}",
                    f.max_rel_error
                );
                // All DOFs less one roller face per direction.
                let expected = if dim == 2 {
                    2 * (2 * n + 1) * (n + 1) - (n + 1) - (2 * n + 1)
                } else {
                    3 * n * (n + 1) * (n + 1)
                };
                assert_eq!(f.unknowns, expected);
            }
        }
    }
}

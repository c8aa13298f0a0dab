//! `hertz bench`: its arguments and the command, over the generators of `hertz-bench`.

use hertz::error::Error;
use hertz::solve::ordering::OrderingKind;
use hertz_bench::{
    examples, print_contact3d, run, run_contact, run_contact3d, suite, write_block_input,
    write_contact_block_input, Model3d,
};
use std::path::Path;
use std::process::ExitCode;

/// Orderings `hertz bench --ordering` accepts.
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub enum OrderingArg {
    Auto,
    Amd,
    Metis,
}

/// `hertz bench`: generated problems with sizes, phase times and errors against exact solutions.
#[derive(Debug, clap::Args)]
#[command(group(clap::ArgGroup::new("problem").args(["contact", "sphere", "patch", "suite", "examples", "ironing3d", "rigid_sphere", "pushed_block"])))]
pub struct BenchArgs {
    /// Dimension of the linear-elastic block
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u8).range(2..=3))]
    pub dim: u8,
    /// Elements per side of the block (2D: 2N x N for --contact)
    #[arg(long = "n", default_value_t = 100, value_parser = clap::value_parser!(u64).range(1..=100_000))]
    pub n: u64,
    /// Fill-reducing ordering of the sparse factorization
    #[arg(long, value_enum, default_value = "auto")]
    pub ordering: OrderingArg,
    /// The 2D contact benchmark: a 2N x N block pushed against a rigid circle (node-to-segment)
    #[arg(long)]
    pub contact: bool,
    /// Lagrange multipliers instead of a penalty (--contact, --sphere, --patch, --rigid-sphere,
    /// --pushed-block)
    #[arg(long)]
    pub multipliers: bool,
    /// 3D Hertz sphere on a block in bricks of spacing H under the contact (0.085: 10^5 unknowns)
    #[arg(long, value_name = "H")]
    pub sphere: Option<f64>,
    /// --sphere: tetrahedra instead of hexahedra
    #[arg(long, requires = "sphere")]
    pub tet: bool,
    /// --sphere, --patch: mortar contact of the slave's bottom faces instead of node-to-face
    #[arg(long)]
    pub mortar: bool,
    /// --sphere, --patch: quadratic elements (10-node tetrahedra with --tet, else 20-node
    /// bricks, whose faces are mortar slaves only)
    #[arg(long)]
    pub quadratic: bool,
    /// --sphere: the cap's whole bottom face as the slave side, as a user meshing the whole
    /// face would (else the part near the axis)
    #[arg(long, requires = "sphere")]
    pub whole_face: bool,
    /// 3D contact patch test with N x N master bricks ((2N+1)^2 contact nodes)
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..=100))]
    pub patch: Option<u64>,
    /// The robustness suite's table of setups
    #[arg(long)]
    pub suite: bool,
    /// With --write: the shallow ironing benchmark on its published mesh extruded to 3D, LAYERS
    /// bricks through a unit depth, every node held across it (solve it with `hertz run`)
    #[arg(long, value_name = "LAYERS", requires = "write",
          value_parser = clap::value_parser!(u64).range(1..=20))]
    pub ironing3d: Option<u64>,
    /// With --write: a rigid sphere pressed into a quarter block of N x N x N bricks, all of its
    /// (N+1)^2 top nodes slave nodes (30: 89 000 unknowns, 961 slave nodes; solve it with
    /// `hertz run`), and its section as a body of revolution (rigid_sphere_section.in)
    #[arg(long, value_name = "N", requires = "write",
          value_parser = clap::value_parser!(u64).range(2..=100))]
    pub rigid_sphere: Option<u64>,
    /// With --rigid-sphere: the sphere pressed in ten steps and lifted in ten into a perfectly
    /// plastic block of yield stress SIG0 on barred bricks, and its elastic twin
    /// (rigid_sphere_plastic.in, rigid_sphere_elastic.in)
    #[arg(long, value_name = "SIG0", requires = "rigid_sphere")]
    pub plastic: Option<f64>,
    /// With --write: a block of N x N x N/4 bricks on a rigid plane, pressed and then pushed
    /// obliquely, all of its (N+1)^2 bottom nodes slave nodes with friction 0.3 (every one
    /// slides; 40: 55 000 unknowns, 1 681 slave nodes; solve it with `hertz run`)
    #[arg(long, value_name = "N", requires = "write",
          value_parser = clap::value_parser!(u64).range(2..=100))]
    pub pushed_block: Option<u64>,
    /// Write the verification examples of examples/ to DIR
    #[arg(long, value_name = "DIR")]
    pub examples: Option<String>,
    /// Write the generated input(s) to DIR instead of solving (the block, --contact, --sphere,
    /// --patch, --suite, --ironing3d, --rigid-sphere, --pushed-block)
    #[arg(long, value_name = "DIR")]
    pub write: Option<String>,
}

/// Largest generated problem `hertz bench` accepts, in unknowns (2D, 3D): the direct solver's
/// memory grows faster in 3D.
const MAX_BENCH_UNKNOWNS: [f64; 2] = [2e7, 1e6];

/// Write one generated input as `dir`/`name` with `write`, saying where (exit 0) or why not.
fn write_generated(
    dir: &str,
    name: &str,
    write: impl FnOnce(&Path) -> hertz::error::Result<()>,
) -> ExitCode {
    let path = Path::new(dir).join(name);
    let written = std::fs::create_dir_all(dir)
        .map_err(|e| Error::Output(format!("cannot create {dir}: {e}")))
        .and_then(|()| write(&path));
    match written {
        Ok(()) => {
            println!("wrote {}", path.display());
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(e.exit_code() as u8)
        }
    }
}

/// [`write_generated`] of an input held as `text`.
fn write_text(dir: &str, name: &str, text: &str) -> ExitCode {
    write_generated(dir, name, |path| {
        std::fs::write(path, text)
            .map_err(|e| Error::Output(format!("cannot write {}: {e}", path.display())))
    })
}

/// CLI entry of `hertz bench` (see `hertz bench --help`).
pub fn main(args: BenchArgs) -> ExitCode {
    let (dim, n) = (args.dim as usize, args.n as usize);
    let ordering = match args.ordering {
        OrderingArg::Auto => OrderingKind::Auto,
        OrderingArg::Amd => OrderingKind::Amd,
        OrderingArg::Metis => OrderingKind::Metis,
    };
    let (contact, multipliers, suite, write, examples) = (
        args.contact,
        args.multipliers,
        args.suite,
        args.write,
        args.examples,
    );
    for (set, flag) in [(args.mortar, "--mortar"), (args.quadratic, "--quadratic")] {
        if set && args.sphere.is_none() && args.patch.is_none() {
            eprintln!("error: {flag} needs --sphere or --patch");
            return ExitCode::from(2);
        }
    }
    let model3d = match (args.sphere, args.patch) {
        // Spacing 0.03: about 10^6 unknowns.
        (Some(h), _) if !(0.03..=1.0).contains(&h) => {
            eprintln!("error: --sphere H takes 0.03 <= H <= 1, got {h}");
            return ExitCode::from(2);
        }
        (Some(h), _) => Some(Model3d::Sphere(hertz_bench::SphereBench {
            h,
            kind: if args.tet {
                hertz_bench::mesh::Solid::Tet
            } else {
                hertz_bench::mesh::Solid::Hex
            },
            mortar: args.mortar,
            whole_face: args.whole_face,
            quadratic: args.quadratic,
        })),
        (_, Some(p)) => Some(Model3d::Patch(hertz_bench::PatchBench {
            n: p as usize,
            mortar: args.mortar,
            quadratic: args.quadratic,
        })),
        _ => None,
    };
    if let Some(dir) = examples {
        return match examples::write_all(Path::new(&dir)) {
            Ok(files) => {
                println!("wrote {} example files to {dir}", files.len());
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::from(e.exit_code() as u8)
            }
        };
    }
    if let (Some(layers), Some(dir)) = (args.ironing3d, &write) {
        let text = hertz_bench::verify::ShallowIroning3d {
            base: examples::SHALLOW_IRONING,
            kind: hertz_bench::mesh::Solid::Hex,
            layers: layers as usize,
            plane_strain: true,
        }
        .input();
        return write_text(dir, "shallow_ironing3d.in", &text);
    }
    if let (Some(n), Some(dir)) = (args.rigid_sphere, &write) {
        let problem = hertz_bench::verify::RigidSphereBlock::uniform(n as usize, multipliers);
        if let Some(sig0) = args.plastic {
            let twin = write_text(
                dir,
                "rigid_sphere_elastic.in",
                &problem.pressed_and_lifted(None),
            );
            if twin != ExitCode::SUCCESS {
                return twin;
            }
            return write_text(
                dir,
                "rigid_sphere_plastic.in",
                &problem.pressed_and_lifted(Some(sig0)),
            );
        }
        let section = write_text(
            dir,
            "rigid_sphere_section.in",
            &problem.axisymmetric_section(),
        );
        if section != ExitCode::SUCCESS {
            return section;
        }
        return write_text(dir, "rigid_sphere_block.in", &problem.input());
    }
    if let (Some(n), Some(dir)) = (args.pushed_block, &write) {
        let law = if multipliers {
            "n2slagrangianmultipliercontact 3 loadTimeFunction 1 friction 0.3"
        } else {
            "n2spenaltycontact 3 loadTimeFunction 1 penalty 1e4 friction 0.3"
        };
        let n = n as usize;
        let text = hertz_bench::verify::pushed_block(n, (n / 4).max(1), law);
        return write_text(dir, "pushed_block.in", &text);
    }
    if let Some(m) = model3d {
        let law = if multipliers {
            suite::Law::Multiplier
        } else {
            suite::Law::Penalty(m.penalty())
        };
        if let Some(dir) = &write {
            let path = Path::new(dir).join(m.file());
            return match std::fs::create_dir_all(dir)
                .and_then(|()| std::fs::write(&path, m.input(law)))
            {
                Ok(()) => {
                    println!("wrote {}", path.display());
                    ExitCode::SUCCESS
                }
                Err(e) => {
                    eprintln!("error: cannot write {}: {e}", path.display());
                    ExitCode::from(4)
                }
            };
        }
        return match run_contact3d(m, law) {
            Ok(f) => {
                print_contact3d(m, law, &f);
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::from(e.exit_code() as u8)
            }
        };
    }
    if suite {
        let result = match &write {
            Some(dir) => suite::write_inputs(Path::new(dir)).map(|files| {
                println!("wrote {} input files to {dir}", files.len());
            }),
            None => suite::print_table(),
        };
        return match result {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::from(e.exit_code() as u8)
            }
        };
    }
    // Refuse sizes that cannot fit before generating anything; a written file is for another
    // solver (`hertz run --petsc`), and only its size bounds it.
    let (unknowns, limit) = if dim == 3 && !contact {
        let direct = if write.is_some() { 0 } else { 1 };
        (3.0 * (n as f64 + 1.0).powi(3), MAX_BENCH_UNKNOWNS[direct])
    } else {
        (4.0 * (n as f64 + 1.0).powi(2), MAX_BENCH_UNKNOWNS[0])
    };
    if unknowns > limit {
        eprintln!(
            "error: bench --n {n} means about {unknowns:.1e} unknowns in {}D; the largest accepted \
             is {limit:.0e}",
            if contact { 2 } else { dim }
        );
        return ExitCode::from(2);
    }
    if let (true, Some(dir)) = (contact, &write) {
        return write_generated(dir, &format!("contact_block_{n}.in"), |path| {
            write_contact_block_input(path, n, n as f64 / 40.0, multipliers)
        });
    }
    if let Some(dir) = &write {
        return write_generated(dir, &format!("block{dim}d_{n}.in"), |path| {
            write_block_input(path, dim, n)
        });
    }
    if contact {
        return match run_contact(n, multipliers) {
            Ok(f) => {
                println!(
                    "contact block {}x{n}, rigid circle, node-to-segment {} on the top nodes",
                    2 * n,
                    if multipliers {
                        "multipliers"
                    } else {
                        "penalty"
                    }
                );
                println!("unknowns           {:>12}", f.unknowns);
                println!("Newton iterations  {:>12}", f.iterations);
                println!("active contacts    {:>12}", f.active);
                println!("solve (all steps)  {:>12.3} s", f.solve_s);
                println!("residuals          {:?}", f.residual_history);
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::from(e.exit_code() as u8)
            }
        };
    }
    match run(dim, n, ordering) {
        Ok(f) => {
            println!("dim {dim}  n {n}  threads {}", rayon::current_num_threads());
            println!("unknowns           {:>12}", f.unknowns);
            println!("matrix nonzeros    {:>12}", f.matrix_nnz);
            println!(
                "factor nonzeros    {:>12}   ({} ordering)",
                f.factor_nnz, f.ordering
            );
            println!("read input         {:>12.3} s", f.read_s);
            println!("pattern            {:>12.3} s", f.pattern_s);
            println!("assembly           {:>12.3} s", f.assembly_s);
            println!("ordering           {:>12.3} s", f.ordering_s);
            println!("symbolic           {:>12.3} s", f.symbolic_s);
            println!("numeric factor     {:>12.3} s", f.numeric_s);
            println!("solve              {:>12.3} s", f.solve_s);
            println!("peak memory        {:>12.1} MiB", f.peak_rss_mb);
            println!("max error vs exact {:>12.2e} (relative)", f.max_rel_error);
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(e.exit_code() as u8)
        }
    }
}

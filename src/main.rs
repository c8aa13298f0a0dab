//! The `hertz` command: thin CLI over the library. Exit codes: 0 success, 1 failed check rules,
//! 2 bad input or usage, 3 solver failure, 4 output failure.

use clap::{CommandFactory, Parser, Subcommand};

use hertz::app::{run_file_observed, RunOptions};
use hertz::output::check::describe_failure;
use hertz::output::vtu::VtuFormat;
use hertz_cli::cli::observer::{CliObserver, Level};
use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;

const AFTER_HELP: &str = "\
Examples:
    hertz run examples/hertz_cylinder.in         solve; write .out, .vtu per step, .pvd
    hertz check tests.in                         solve and evaluate the #%BEGIN_CHECK% rules
    hertz import mesh.msh -o mesh.in             Gmsh mesh -> OOFEM records to @include
    hertz plot run.contact.csv --hertz 25.75,0.4686
                                                 contact pressure with the Hertz curve P0,A (SVG)

Exit codes: 0 success, 1 a check rule failed, 2 bad input or usage, 3 the solver failed,
4 output failed. User guide: docs/guide.md";

#[derive(Parser)]
#[command(
    name = "hertz",
    version,
    about = "Finite-element solver for contact mechanics that reads OOFEM input files",
    after_help = AFTER_HELP,
    arg_required_else_help = false
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// Verbosity shared by `run` and `check`.
#[derive(clap::Args)]
struct Verbosity {
    /// Nothing on stderr but errors (no progress, step lines, warnings); results stay on stdout
    #[arg(short, long, conflicts_with = "verbose")]
    quiet: bool,
    /// One line per Newton iteration: residual, contact nodes closed and opened, phase times
    #[arg(short, long)]
    verbose: bool,
}

#[derive(clap::Args, Default)]
struct PetscArgs {
    /// The linear solver: hertz's own (faer: sparse Cholesky/LU, condensed contact steps), or
    /// PETSc (a build with `--features petsc`): CG + GAMG for a positive definite tangent and for
    /// the systems left when multipliers are eliminated, GMRES + BoomerAMG for a penalty tangent
    /// of 20 000 unknowns or more, MUMPS otherwise; under `mpirun -n N` across N ranks, rank 0
    /// reporting and writing
    #[arg(long, value_enum, default_value_t = SolverName::Faer)]
    solver: SolverName,
    /// The same as --solver petsc
    #[arg(long, conflicts_with = "solver")]
    petsc: bool,
    /// PETSc options for --solver petsc, e.g. "-ksp_type cg -pc_type hypre" (PETSC_OPTIONS is
    /// read too)
    #[arg(long, value_name = "OPTIONS", allow_hyphen_values = true)]
    petsc_options: Option<String>,
}

/// The linear solvers `--solver` names.
#[derive(Clone, Copy, Default, PartialEq, Eq, clap::ValueEnum)]
enum SolverName {
    #[default]
    Faer,
    Petsc,
}

impl PetscArgs {
    /// PETSc was asked for (by --solver petsc or --petsc).
    fn wanted(&self) -> bool {
        self.petsc || self.solver == SolverName::Petsc
    }
}

#[derive(Subcommand)]
enum Command {
    /// Solve FILE; write its .out, a .vtu per step, a .pvd and, with contact, a .contact.csv;
    /// evaluate the #%BEGIN_CHECK% rules if the file has an errorcheck module
    Run {
        /// OOFEM input file
        file: PathBuf,
        /// Directory for the output files (default: next to the input file)
        #[arg(short, long, value_name = "DIR")]
        output: Option<PathBuf>,
        /// How the .vtu arrays are stored: text, or raw binary appended to the XML (smaller,
        /// exact, faster to write and to load in ParaView)
        #[arg(long, default_value = "ascii", value_parser = hertz_cli::import::vtu_parser())]
        vtu: VtuFormat,
        #[command(flatten)]
        petsc: PetscArgs,
        #[command(flatten)]
        verbosity: Verbosity,
    },
    /// Solve FILE and evaluate its check rules; write nothing else
    Check {
        /// OOFEM input file
        file: PathBuf,
        #[command(flatten)]
        verbosity: Verbosity,
    },
    /// Convert a Gmsh mesh (.msh 2.2 or 4.1) to OOFEM node, element and set records
    Import(hertz_cli::import::ImportArgs),
    /// Plot a run's results: contact pressure, load-displacement, Newton residuals (SVG or PNG)
    Plot(hertz_cli::plot::PlotArgs),
    /// Generated benchmark problems: sizes, phase times, errors against exact solutions
    Bench(hertz_cli::bench::BenchArgs),
    /// Print a shell completion script (bash, zsh, fish, elvish, powershell)
    Completions {
        #[arg(value_enum)]
        shell: clap_complete::Shell,
    },
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            // Help and version go to stdout with exit 0; usage errors exit 2.
            let _ = e.print();
            return ExitCode::from(if e.use_stderr() { 2 } else { 0 });
        }
    };
    match cli.command {
        Command::Run {
            file,
            output,
            vtu,
            petsc,
            verbosity,
        } => run_or_check(file, Some((output, vtu)), &petsc, &verbosity),
        Command::Check { file, verbosity } => {
            run_or_check(file, None, &PetscArgs::default(), &verbosity)
        }
        Command::Import(args) => report(
            hertz_cli::import::run(&args).map(|lines| lines.iter().for_each(|l| eprintln!("{l}"))),
        ),
        Command::Plot(args) => report(hertz_cli::plot::plot_files(&args).map(|files| {
            files
                .iter()
                .for_each(|p| eprintln!("wrote {}", p.display()))
        })),
        Command::Bench(args) => hertz_cli::bench::main(args),
        Command::Completions { shell } => {
            clap_complete::generate(shell, &mut Cli::command(), "hertz", &mut std::io::stdout());
            ExitCode::SUCCESS
        }
    }
}

/// Print an error as `error: ...` (with the record drawn for input errors) and map it to its
/// exit code.
fn report(result: hertz::error::Result<()>) -> ExitCode {
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!(
                "{}",
                hertz_cli::diagnostic::render(&e, std::io::stderr().is_terminal())
            );
            ExitCode::from(e.exit_code() as u8)
        }
    }
}

/// This process's rank and the number of processes when an MPI launcher (`mpirun`, `mpiexec`:
/// Open MPI's or MPICH's environment) started more than one; None for a single process.
fn launched_ranks() -> Option<(usize, usize)> {
    let var = |names: &[&str]| {
        names
            .iter()
            .find_map(|n| std::env::var(n).ok()?.trim().parse::<usize>().ok())
    };
    let size = var(&["OMPI_COMM_WORLD_SIZE", "PMI_SIZE"])?;
    let rank = var(&["OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK"]).unwrap_or(0);
    (size > 1).then_some((rank, size))
}

/// `run` (with `output` = Some((directory, VTU format)): write the results) or `check`.
fn run_or_check(
    file: PathBuf,
    output: Option<(Option<PathBuf>, VtuFormat)>,
    petsc: &PetscArgs,
    v: &Verbosity,
) -> ExitCode {
    // PETSc for the whole run (finalized when `session` drops, after the analysis).
    if petsc.petsc_options.is_some() && !petsc.wanted() {
        eprintln!("error: --petsc-options is for PETSc: add --solver petsc");
        return ExitCode::from(2);
    }
    if let Some((rank, size)) = launched_ranks().filter(|_| !petsc.wanted()) {
        // Each process would solve the whole model and write the same files.
        if rank == 0 {
            eprintln!(
                "error: hertz was started as {size} MPI processes without --solver petsc: each \
                 would solve the whole model and write the same files; add --solver petsc (a \
                 build with --features petsc) or run one process"
            );
        }
        return ExitCode::from(2);
    }
    let session = if petsc.wanted() {
        match hertz_petsc::Session::start(petsc.petsc_options.as_deref()) {
            Ok(s) => Some(s),
            Err(e) => {
                eprintln!("error: {e}");
                return ExitCode::from(2);
            }
        }
    } else {
        None
    };
    // Under MPI every rank solves; rank 0 alone reports and writes.
    let silent_rank = session.as_ref().is_some_and(|s| s.rank() > 0);
    let run = output.is_some() && !silent_rank;
    let (out_dir, vtu_format) = output.unwrap_or_default();
    let opts = RunOptions {
        write_outputs: run,
        out_dir,
        vtu_format,
        solver: session.as_ref().map(|s| s.solver()).unwrap_or_default(),
    };
    let quiet = v.quiet || silent_rank;
    let level = match (quiet, v.verbose) {
        (true, _) => Level::Quiet,
        (_, true) => Level::Verbose,
        _ => Level::Normal,
    };
    let observer = CliObserver::new(level);
    let result = run_file_observed(&file, &opts, &observer);
    // The progress bar is cleared before anything more is printed.
    drop(observer);
    if let Some(s) = session.as_ref().filter(|_| !quiet) {
        let unused = s.unused_options();
        if !unused.is_empty() {
            eprintln!(
                "warning: PETSc never read the options {} (misspelled, or for a method this \
                 run did not take)",
                unused.join(" ")
            );
        }
    }
    if silent_rank {
        let code = match &result {
            Ok(r) => u8::from(r.n_failed() > 0),
            Err(e) => e.exit_code() as u8,
        };
        return ExitCode::from(code);
    }
    let report_ = match result {
        Ok(r) => r,
        Err(e) => return report(Err(e)),
    };
    let failed = report_.n_failed();
    if report_.has_errorcheck {
        for o in report_.outcomes.iter().filter(|o| !o.passed) {
            println!("{}", describe_failure(o));
        }
        println!(
            "{} passed, {} failed",
            report_.outcomes.len() - failed,
            failed
        );
    } else if !run && !v.quiet {
        println!(
            "no errorcheck module in {}: nothing to check",
            file.display()
        );
    }
    if run && !v.quiet {
        for p in &report_.written {
            if p.extension()
                .is_some_and(|e| e == "out" || e == "pvd" || e == "csv")
            {
                eprintln!("wrote {}", p.display());
            }
        }
        if v.verbose {
            eprintln!(
                "output files formatted and written in {:.3} s",
                report_.output_seconds
            );
        }
    }
    if failed > 0 {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    }
}

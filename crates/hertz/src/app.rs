//! One run of an input file: read, solve, evaluate the check rules, write the outputs.
//! Shared by the `hertz` binary and the integration tests.

use crate::error::{Error, Result};
use crate::input::read_model_warning;
use crate::output::check;
use crate::output::vtu::VtuFormat;
use crate::output::writer::RunWriter;
use crate::solve::{run_analysis_observed, Observer, Phase, Silent, SolveParams, SolverChoice};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// What to do besides solving.
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// Write the `.out`, `.vtu` and `.pvd` files (else only evaluate the rules).
    pub write_outputs: bool,
    /// Directory for the outputs; default: next to the input file.
    pub out_dir: Option<PathBuf>,
    /// How the `.vtu` arrays are written.
    pub vtu_format: VtuFormat,
    /// The linear solver of the full tangents (PETSc's in the command's `petsc` feature).
    pub solver: SolverChoice,
}

/// What a run produced.
#[derive(Debug, Default)]
pub struct RunReport {
    pub warnings: Vec<String>,
    /// Whether the input has an `errorcheck` module.
    pub has_errorcheck: bool,
    pub outcomes: Vec<check::Outcome>,
    pub written: Vec<PathBuf>,
    /// Wall time spent formatting and writing the output files.
    pub output_seconds: f64,
}

impl RunReport {
    pub fn n_failed(&self) -> usize {
        self.outcomes.iter().filter(|o| !o.passed).count()
    }
}

impl RunReport {
    /// Keep a warning, and pass it on at once to the observer.
    fn warn(&mut self, observer: &dyn Observer, w: String) {
        observer.warning(&w);
        self.warnings.push(w);
    }
}

/// Read, solve and check `path`, reporting nothing on the way (see [`run_file_observed`]).
/// Warnings are collected in the report.
pub fn run_file(path: &Path, opts: &RunOptions) -> Result<RunReport> {
    run_file_observed(path, opts, &Silent)
}

/// [`run_file`], telling `observer` of each warning as it comes up (the reader's before
/// anything is solved, also when reading then fails) and of the solver's phases, iterations and
/// steps.
pub fn run_file_observed(
    path: &Path,
    opts: &RunOptions,
    observer: &dyn Observer,
) -> Result<RunReport> {
    let clock = Instant::now();
    observer.phase(&Phase::Reading);
    let mut read_warnings = Vec::new();
    let read = read_model_warning(path, &mut read_warnings);
    if read.is_err() {
        read_warnings.iter().for_each(|w| observer.warning(w));
    }
    let read = read?;
    let model = read.model;
    let mut report = RunReport {
        has_errorcheck: model.analysis.errorcheck,
        ..Default::default()
    };
    for w in read_warnings {
        report.warn(observer, w);
    }
    let rules = if model.analysis.errorcheck {
        let raw = std::fs::read(path).map_err(|e| Error::InputFile {
            file: path.display().to_string(),
            msg: e.to_string(),
        })?;
        let (rules, w) = check::parse_rules(&String::from_utf8_lossy(&raw));
        for m in w {
            report.warn(observer, format!("{}: {m}", path.display()));
        }
        let nsteps = model.step_times().len();
        for r in rules.iter().filter(|r| r.step == 0 || r.step > nsteps) {
            report.warn(
                observer,
                format!(
                    "{}:{}: check rule for step {} never applies (the analysis has {nsteps} steps)",
                    path.display(),
                    r.line,
                    r.step
                ),
            );
        }
        rules
    } else {
        Vec::new()
    };
    let dir = match &opts.out_dir {
        Some(d) => d.clone(),
        None => path
            .parent()
            .map(Path::to_path_buf)
            .unwrap_or_else(|| PathBuf::from(".")),
    };
    let mut writer = if opts.write_outputs {
        Some(RunWriter::new(
            &model,
            &dir,
            opts.vtu_format,
            &read.sources,
        )?)
    } else {
        None
    };
    let params = SolveParams {
        solver: opts.solver.clone(),
        ..SolveParams::default()
    };
    let mut steps_done = 0;
    let mut solver_warnings: Vec<String> = Vec::new();
    let result = run_analysis_observed(&model, &params, observer, |res| {
        steps_done += 1;
        // Each solver warning once, with the first step it came up in.
        for w in &res.info.warnings {
            if !solver_warnings.contains(w) {
                solver_warnings.push(w.clone());
                // The solver told the observer when it came up.
                report.warnings.push(format!("step {}: {w}", res.step));
            }
        }
        report
            .outcomes
            .extend(check::evaluate_step(&model, &rules, res));
        match writer.as_mut() {
            Some(w) => w.step(res),
            None => Ok(()),
        }
    });
    // A run that fails before its first step converged (a singular model, a step that cannot
    // converge) has no results: it leaves no files behind. After a converged step, the results so
    // far are written with the reason the analysis stopped.
    if let Some(w) = writer.filter(|_| result.is_ok() || steps_done > 0) {
        let stopped = result.as_ref().err().map(|e| e as &dyn std::fmt::Display);
        let written = w.finish(stopped, clock.elapsed().as_secs_f64())?;
        report.written = written.files;
        report.output_seconds = written.seconds;
    }
    result?;
    Ok(report)
}

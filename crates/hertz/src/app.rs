//! One run of an input file: read, solve, evaluate the check rules, write the outputs.
//! Shared by the `hertz` binary and the integration tests.

use crate::error::{Error, Result};
use crate::input::read_model_warning;
use crate::output::names::OutputNames;
use crate::output::vtu::{self, VtuFormat};
use crate::output::{check, outfile, write_atomic, write_atomic_parts};
use crate::solve::{run_analysis_observed, Observer, Phase, Silent, SolveParams};
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
    let names = OutputNames::new(dir.clone(), &model.output_name);
    if opts.write_outputs {
        names.check_inputs_kept(&read.sources)?;
        std::fs::create_dir_all(&dir)
            .map_err(|e| Error::Output(format!("cannot create {}: {e}", dir.display())))?;
    }
    let stem = names.stem.clone();
    let mut out_parts = vec![outfile::header(&model)];
    let mut output_clock = std::time::Duration::ZERO;
    let mut vtus: Vec<(f64, String)> = Vec::new();
    let mut csv = String::from(outfile::CONTACT_CSV_HEADER);
    csv.push('\n');
    let mut history = String::new();
    let mut newton = format!("{}\n", outfile::NEWTON_CSV_HEADER);
    let params = SolveParams::default();
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
        if opts.write_outputs {
            let start = Instant::now();
            // The .out block and the .vtu file side by side (each in parallel chunks too).
            let (block, name) = rayon::join(
                || {
                    model
                        .output
                        .step(res.step)
                        .then(|| outfile::step_block(&model, res))
                },
                || vtu::write_step(&model, res, &dir, &stem, opts.vtu_format),
            );
            out_parts.extend(block.into_iter().flatten());
            csv.push_str(&outfile::contact_csv_rows(&model, res));
            if history.is_empty() {
                history = outfile::history_csv_header(&model, res.dofs);
            }
            history.push_str(&outfile::history_csv_row(res));
            newton.push_str(&outfile::newton_csv_rows(res));
            let name = name?;
            report.written.push(dir.join(&name));
            vtus.push((res.time, name));
            output_clock += start.elapsed();
        }
        Ok(())
    });
    // A run that fails before its first step converged (a singular model, a step that cannot
    // converge) has no results: it leaves no files behind. After a converged step, the results so
    // far are written with the reason the analysis stopped.
    if opts.write_outputs && (result.is_ok() || steps_done > 0) {
        let start = Instant::now();
        if let Err(e) = &result {
            out_parts.push(format!("\nAnalysis stopped: {e}\n"));
        }
        out_parts.push(outfile::footer(clock.elapsed().as_secs_f64()));
        let out_path = names.out_path();
        let bytes: Vec<&[u8]> = out_parts.iter().map(|p| p.as_bytes()).collect();
        write_atomic_parts(&out_path, &bytes)?;
        report.written.push(out_path);
        if !model.contacts.is_empty() {
            let csv_path = names.path("contact.csv");
            write_atomic(&csv_path, csv.as_bytes())?;
            report.written.push(csv_path);
        }
        for (ext, text) in [("steps.csv", &history), ("newton.csv", &newton)] {
            let p = names.path(ext);
            write_atomic(&p, text.as_bytes())?;
            report.written.push(p);
        }
        if !vtus.is_empty() {
            vtu::write_collection(&dir, &stem, &vtus)?;
            report.written.push(names.path("pvd"));
        }
        output_clock += start.elapsed();
    }
    report.output_seconds = output_clock.as_secs_f64();
    result?;
    Ok(report)
}

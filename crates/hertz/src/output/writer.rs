//! [`RunWriter`]: the files of a run (`.out`, VTU per step and PVD, contact, step and Newton
//! CSV histories, and in dynamics the energies), fed step by step and written whole at the end. `hertz run` and the Python
//! module's `Result.write` share it, so both write the same files.

use super::names::OutputNames;
use super::vtu::{self, VtuFormat};
use super::{outfile, write_atomic, write_atomic_parts};
use crate::error::{Error, Result};
use crate::model::Model;
use crate::solve::StepResult;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// The output files of one run of `model`, in the making.
pub struct RunWriter<'m> {
    model: &'m Model,
    dir: PathBuf,
    names: OutputNames,
    format: VtuFormat,
    out_parts: Vec<String>,
    vtus: Vec<(f64, String)>,
    contact_csv: String,
    history_csv: String,
    newton_csv: String,
    /// Dynamics: the energies per step.
    energy_csv: String,
    written: Vec<PathBuf>,
    clock: Duration,
}

impl<'m> RunWriter<'m> {
    /// Files for `model` in `dir`. The input files `sources` must not be among them: a run never
    /// overwrites its input (an error names the file).
    pub fn new(
        model: &'m Model,
        dir: &Path,
        format: VtuFormat,
        sources: &[PathBuf],
    ) -> Result<RunWriter<'m>> {
        let names = OutputNames::new(dir.to_path_buf(), &model.output_name);
        names.check_inputs_kept(sources)?;
        std::fs::create_dir_all(dir)
            .map_err(|e| Error::Output(format!("cannot create {}: {e}", dir.display())))?;
        Ok(RunWriter {
            model,
            dir: dir.to_path_buf(),
            names,
            format,
            out_parts: vec![outfile::header(model)],
            vtus: Vec::new(),
            contact_csv: format!("{}\n", outfile::CONTACT_CSV_HEADER),
            history_csv: String::new(),
            newton_csv: format!("{}\n", outfile::NEWTON_CSV_HEADER),
            energy_csv: format!("{}\n", outfile::ENERGY_CSV_HEADER),
            written: Vec::new(),
            clock: Duration::ZERO,
        })
    }

    /// Add a converged step: its `.out` block, its VTU file (written now) and its CSV rows.
    pub fn step(&mut self, res: &StepResult) -> Result<()> {
        let start = Instant::now();
        let model = self.model;
        // The VTU files at the steps the output manager selects, at every step where it selects
        // none (thousands of dynamic steps need not make thousands of files).
        let o = &model.output;
        let selects = o.tstep_all || o.tstep_step.is_some() || !o.tsteps_out.is_empty();
        let vtu_now = !selects || o.step(res.step);
        // The .out block and the .vtu file side by side (each in parallel chunks too).
        let (block, name) = rayon::join(
            || o.step(res.step).then(|| outfile::step_block(model, res)),
            || {
                vtu_now
                    .then(|| vtu::write_step(model, res, &self.dir, &self.names.stem, self.format))
                    .transpose()
            },
        );
        self.out_parts.extend(block.into_iter().flatten());
        self.contact_csv
            .push_str(&outfile::contact_csv_rows(model, res));
        if self.history_csv.is_empty() {
            self.history_csv = outfile::history_csv_header(model, res.dofs);
        }
        self.history_csv.push_str(&outfile::history_csv_row(res));
        self.newton_csv.push_str(&outfile::newton_csv_rows(res));
        self.energy_csv.push_str(&outfile::energy_csv_row(res));
        if let Some(name) = name? {
            self.written.push(self.dir.join(&name));
            self.vtus.push((res.time, name));
        }
        self.clock += start.elapsed();
        Ok(())
    }

    /// Write the `.out` file (with the reason the analysis stopped, if it did, and the run's
    /// `wall_seconds`), the CSV files and the PVD collection. Returns every file written.
    pub fn finish(
        mut self,
        stopped: Option<&dyn std::fmt::Display>,
        wall_seconds: f64,
    ) -> Result<Written> {
        let start = Instant::now();
        if let Some(e) = stopped {
            self.out_parts.push(format!("\nAnalysis stopped: {e}\n"));
        }
        self.out_parts.push(outfile::footer(wall_seconds));
        let out_path = self.names.out_path();
        let bytes: Vec<&[u8]> = self.out_parts.iter().map(|p| p.as_bytes()).collect();
        write_atomic_parts(&out_path, &bytes)?;
        self.written.push(out_path);
        if !self.model.contacts.is_empty() {
            let csv_path = self.names.path("contact.csv");
            write_atomic(&csv_path, self.contact_csv.as_bytes())?;
            self.written.push(csv_path);
        }
        if self.model.analysis.dynamics.is_some() {
            let p = self.names.path("energy.csv");
            write_atomic(&p, self.energy_csv.as_bytes())?;
            self.written.push(p);
        }
        for (ext, text) in [
            ("steps.csv", &self.history_csv),
            ("newton.csv", &self.newton_csv),
        ] {
            let p = self.names.path(ext);
            write_atomic(&p, text.as_bytes())?;
            self.written.push(p);
        }
        if !self.vtus.is_empty() {
            vtu::write_collection(&self.dir, &self.names.stem, &self.vtus)?;
            self.written.push(self.names.path("pvd"));
        }
        self.clock += start.elapsed();
        Ok(Written {
            files: self.written,
            seconds: self.clock.as_secs_f64(),
        })
    }
}

/// What [`RunWriter::finish`] wrote.
#[derive(Debug, Default)]
pub struct Written {
    pub files: Vec<PathBuf>,
    /// Wall time spent formatting and writing.
    pub seconds: f64,
}

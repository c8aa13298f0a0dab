//! The observer a Python caller gives `Model.solve`: each report goes to it as a dict. Its
//! exceptions and Ctrl-C stop the analysis; warnings are kept for the result.

use hertz::solve::{IterationReport, Observer, StepReport};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::cell::RefCell;

pub struct PyObserver<'py> {
    py: Python<'py>,
    callback: Option<Py<PyAny>>,
    /// The first exception the callback raised, or KeyboardInterrupt.
    error: RefCell<Option<PyErr>>,
    warnings: RefCell<Vec<String>>,
}

impl<'py> PyObserver<'py> {
    pub fn new(py: Python<'py>, callback: Option<Py<PyAny>>) -> PyObserver<'py> {
        PyObserver {
            py,
            callback: callback.filter(|c| !c.is_none(py)),
            error: RefCell::new(None),
            warnings: RefCell::new(Vec::new()),
        }
    }

    pub fn take_error(&self) -> Option<PyErr> {
        self.error.borrow_mut().take()
    }

    pub fn take_warnings(&self) -> Vec<String> {
        std::mem::take(&mut self.warnings.borrow_mut())
    }

    /// Call the callback with a dict of `kind` and the items `fill` sets (once an exception has
    /// stopped the run, nothing more is sent).
    fn send(&self, kind: &str, fill: impl FnOnce(&Bound<'py, PyDict>) -> PyResult<()>) {
        let Some(cb) = &self.callback else { return };
        if self.error.borrow().is_some() {
            return;
        }
        let sent = (|| {
            let d = PyDict::new(self.py);
            d.set_item("kind", kind)?;
            fill(&d)?;
            cb.call1(self.py, (d,))?;
            Ok(())
        })();
        if let Err(e) = sent {
            *self.error.borrow_mut() = Some(e);
        }
    }
}

impl Observer for PyObserver<'_> {
    fn iteration(&self, r: &IterationReport) {
        self.send("iteration", |d| {
            d.set_item("step", r.step)?;
            d.set_item("iteration", r.iteration)?;
            d.set_item("residual", r.residual)?;
            d.set_item("contact_points", r.contact_points)?;
            d.set_item("closed", r.closed)?;
            d.set_item("closed_nodes", r.closed_nodes.clone())?;
            d.set_item("opened_nodes", r.opened_nodes.clone())?;
            d.set_item("slipping", r.slipping)?;
            d.set_item("switched_nodes", r.switched_nodes.clone())
        });
    }

    fn step(&self, r: &StepReport) {
        self.send("step", |d| {
            d.set_item("step", r.step)?;
            d.set_item("n_steps", r.n_steps)?;
            d.set_item("time", r.time)?;
            d.set_item("iterations", r.iterations)?;
            d.set_item("residual", r.residual)?;
            d.set_item("substeps", r.substeps)?;
            d.set_item("wall_seconds", r.wall_seconds)?;
            d.set_item("krylov_iterations", r.krylov_iterations)
        });
    }

    fn retry(&self, message: &str) {
        self.send("retry", |d| d.set_item("message", message));
    }

    fn warning(&self, message: &str) {
        self.warnings.borrow_mut().push(message.to_string());
        self.send("warning", |d| d.set_item("message", message));
    }

    /// Ctrl-C (Python's signal handlers run here) or an exception of the callback.
    fn interrupted(&self) -> bool {
        if self.error.borrow().is_some() {
            return true;
        }
        if let Err(e) = self.py.check_signals() {
            *self.error.borrow_mut() = Some(e);
            return true;
        }
        false
    }
}

//! `hertz._hertz`: the compiled part of the Python module `hertz`. Models are read by the
//! library's reader and solved by its solver; nothing is printed. Results come back as numpy
//! arrays built once from the solver's vectors.

mod arrays;
mod model;
mod observer;
mod result;

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

create_exception!(
    hertz,
    HertzError,
    PyException,
    "Base of the errors hertz raises."
);
create_exception!(
    hertz,
    InputError,
    HertzError,
    "A bad input: the message names the file, line and record; `.file`, `.line` and `.record` \
     hold them (`.line` is None for errors not tied to a line)."
);
create_exception!(
    hertz,
    SolveError,
    HertzError,
    "The analysis failed (no convergence, a singular system): the message is the command \
     line's diagnosis; `.result` holds the steps that converged before."
);
create_exception!(hertz, OutputError, HertzError, "Writing results failed.");

/// A Python exception for a library error (`result`: the converged steps, for solver errors).
pub(crate) fn to_py_err(
    py: Python<'_>,
    e: hertz::error::Error,
    result: Option<Py<PyAny>>,
) -> PyErr {
    use hertz::error::Error;
    match &e {
        Error::Input { span, .. } => {
            let err = InputError::new_err(e.to_string());
            let v = err.value(py);
            let _ = v.setattr("file", span.file.display().to_string());
            let _ = v.setattr("line", span.line);
            let _ = v.setattr("record", span.record.clone());
            err
        }
        Error::InputFile { file, .. } => {
            let err = InputError::new_err(e.to_string());
            let v = err.value(py);
            let _ = v.setattr("file", file.clone());
            let _ = v.setattr("line", py.None());
            let _ = v.setattr("record", py.None());
            err
        }
        Error::Solve(_) | Error::Singular(_) => {
            let err = SolveError::new_err(e.to_string());
            let _ = err
                .value(py)
                .setattr("result", result.unwrap_or_else(|| py.None()));
            err
        }
        Error::Output(_) => OutputError::new_err(e.to_string()),
        Error::Interrupted => pyo3::exceptions::PyKeyboardInterrupt::new_err("interrupted"),
    }
}

#[pymodule]
fn _hertz(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("HertzError", py.get_type::<HertzError>())?;
    m.add("InputError", py.get_type::<InputError>())?;
    m.add("SolveError", py.get_type::<SolveError>())?;
    m.add("OutputError", py.get_type::<OutputError>())?;
    m.add_class::<model::Model>()?;
    m.add_class::<result::Result>()?;
    m.add_class::<result::Step>()?;
    m.add_function(wrap_pyfunction!(model::read, m)?)?;
    m.add_function(wrap_pyfunction!(model::read_string, m)?)?;
    Ok(())
}

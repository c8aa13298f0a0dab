//! numpy arrays from the solver's row-major vectors.

use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2};
use pyo3::prelude::*;

/// A (rows × cols) float array from row-major values.
pub(crate) fn array2<'py>(
    py: Python<'py>,
    rows: usize,
    cols: usize,
    values: Vec<f64>,
) -> Bound<'py, PyArray2<f64>> {
    Array2::from_shape_vec((rows, cols), values)
        .expect("rows × cols values")
        .into_pyarray(py)
}

/// A (rows × cols) integer array from row-major values.
pub(crate) fn array2_i64<'py>(
    py: Python<'py>,
    rows: usize,
    cols: usize,
    values: Vec<i64>,
) -> Bound<'py, PyArray2<i64>> {
    Array2::from_shape_vec((rows, cols), values)
        .expect("rows × cols values")
        .into_pyarray(py)
}

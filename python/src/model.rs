//! `hertz.Model`: a model read by the library's reader, its arrays, the parameters a study
//! changes, and `solve`.

use crate::arrays::{array2, array2_i64};
use crate::observer::PyObserver;
use crate::result::{Result as PyResultObj, StepData};
use crate::to_py_err;
use hertz::model::{Enforcement, MaterialLaw, Model as HModel, PenaltySource};
use hertz::solve::{run_analysis_observed, SolveParams};
use numpy::{IntoPyArray, PyArray1, PyArray2};
use pyo3::exceptions::{PyKeyError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;

/// A model read from an OOFEM input: nodes, elements, sets, materials, conditions and the
/// analysis. Record numbers are those of the input (1-based); node and element ids are their
/// labels.
#[pyclass(module = "hertz", name = "Model")]
pub struct Model {
    pub(crate) model: HModel,
    /// The files the model was read from (outputs never overwrite them).
    pub(crate) sources: Vec<PathBuf>,
    /// The reader's warnings.
    #[pyo3(get)]
    warnings: Vec<String>,
}

/// Read the OOFEM input file `path`. A bad input raises `hertz.InputError`.
#[pyfunction]
pub fn read(py: Python<'_>, path: PathBuf) -> PyResult<Model> {
    let read = hertz::input::read_model(&path).map_err(|e| to_py_err(py, e, None))?;
    Ok(Model {
        model: read.model,
        sources: read.sources,
        warnings: read.warnings,
    })
}

/// Read an OOFEM input held in `text`, named `name` in messages (and as the output files' stem
/// when the text names none); `@include` and `@gmsh` paths are relative to `name`'s directory.
#[pyfunction]
#[pyo3(signature = (text, name = "model"))]
pub fn read_string(py: Python<'_>, text: &str, name: &str) -> PyResult<Model> {
    let read = hertz::input::read_model_str(text, name).map_err(|e| to_py_err(py, e, None))?;
    Ok(Model {
        model: read.model,
        sources: read.sources,
        warnings: read.warnings,
    })
}

/// A record addressed by its number or by the name of the set it acts on.
#[derive(FromPyObject)]
pub enum RecordKey {
    Number(usize),
    Name(String),
}

impl Model {
    /// The dict of set index `i` (see `sets`).
    fn set_dict<'py>(&self, py: Python<'py>, i: usize) -> PyResult<Bound<'py, PyDict>> {
        let s = &self.model.sets[i];
        let d = PyDict::new(py);
        d.set_item("nodes", self.label_array(py, &s.nodes))?;
        let elements: Vec<i64> = s
            .elements
            .iter()
            .map(|&e| self.model.elements[e].label as i64)
            .collect();
        d.set_item("elements", elements.into_pyarray(py))?;
        let b: Vec<i64> = s
            .boundaries
            .iter()
            .flat_map(|&(e, k)| [self.model.elements[e].label as i64, k as i64])
            .collect();
        d.set_item("boundaries", array2_i64(py, s.boundaries.len(), 2, b))?;
        if let Some(name) = &s.name {
            d.set_item("name", name)?;
        }
        Ok(d)
    }

    /// The number of the set named `name`, or a KeyError that lists the names there are.
    fn set_number(&self, name: &str) -> PyResult<usize> {
        self.model.set_named(name).ok_or_else(|| {
            let names: Vec<String> = self
                .model
                .sets
                .iter()
                .filter_map(|s| s.name.as_ref().map(|n| format!("{n:?}")))
                .collect();
            PyKeyError::new_err(if names.is_empty() {
                format!("no set is named {name:?}: the model's sets have no names")
            } else {
                format!("no set is named {name:?} (named: {})", names.join(", "))
            })
        })
    }

    /// The record number `key` gives: itself, or the one record of `records` ((number, set
    /// number) pairs, `what` in messages) on the set named so.
    fn record_number(
        &self,
        key: RecordKey,
        what: &str,
        records: impl Iterator<Item = (usize, usize)>,
    ) -> PyResult<usize> {
        let name = match key {
            RecordKey::Number(n) => return Ok(n),
            RecordKey::Name(name) => name,
        };
        let set = self.set_number(&name)?;
        let on: Vec<usize> = records.filter(|&(_, s)| s == set).map(|(n, _)| n).collect();
        match on[..] {
            [n] => Ok(n),
            [] => Err(PyKeyError::new_err(format!(
                "no {what} acts on set {set} ({name:?})"
            ))),
            _ => Err(PyValueError::new_err(format!(
                "{what}s {on:?} all act on set {set} ({name:?}): give the record number"
            ))),
        }
    }

    fn label_array<'py>(&self, py: Python<'py>, nodes: &[usize]) -> Bound<'py, PyArray1<i64>> {
        nodes
            .iter()
            .map(|&n| self.model.nodes[n].label as i64)
            .collect::<Vec<_>>()
            .into_pyarray(py)
    }
}

#[pymethods]
impl Model {
    /// Number of space dimensions (1, 2 or 3).
    #[getter]
    fn dim(&self) -> usize {
        self.model.domain.nsd()
    }

    /// The DOF ids (1 = x, 2 = y, 3 = z) of the result arrays' columns.
    #[getter]
    fn dof_ids(&self) -> Vec<u8> {
        self.model.domain.default_dofs().to_vec()
    }

    /// Node coordinates, n × 3 (the third column 0 in 2D), in the order of `node_labels`.
    #[getter]
    fn nodes<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let n = self.model.nodes.len();
        let xs = self.model.nodes.iter().flat_map(|p| p.coords).collect();
        array2(py, n, 3, xs)
    }

    /// Node labels (the numbers of the input), in the order of the rows of `nodes` and of the
    /// results' arrays.
    #[getter]
    fn node_labels<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        let all: Vec<usize> = (0..self.model.nodes.len()).collect();
        self.label_array(py, &all)
    }

    /// Per element keyword (OOFEM's, e.g. "LSpace", "LSpaceBB"): a dict with `labels` (m) and
    /// `connectivity` (m × nodes per element, node labels in OOFEM's order).
    #[getter]
    fn elements<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        // In the order of hertz's element types, each barred kind after its plain one.
        let mut groups: std::collections::BTreeMap<(usize, bool), Vec<&hertz::model::Element>> =
            Default::default();
        for e in &self.model.elements {
            let kind = hertz::model::ElementType::ALL
                .iter()
                .position(|&(_, t)| t == e.etype)
                .unwrap_or(usize::MAX);
            groups.entry((kind, e.bbar)).or_default().push(e);
        }
        let out = PyDict::new(py);
        for els in groups.into_values() {
            let keyword = els[0].keyword();
            let k = els[0].etype.n_nodes();
            let conn = els
                .iter()
                .flat_map(|e| e.nodes.iter().map(|&n| self.model.nodes[n].label as i64))
                .collect();
            let d = PyDict::new(py);
            let labels: Vec<i64> = els.iter().map(|e| e.label as i64).collect();
            d.set_item("labels", labels.into_pyarray(py))?;
            d.set_item("connectivity", array2_i64(py, els.len(), k, conn))?;
            out.set_item(keyword, d)?;
        }
        Ok(out)
    }

    /// Set number → dict with `nodes` (node labels), `elements` (element labels),
    /// `boundaries` (k × 2: element label, boundary number of OOFEM's numbering) and `name`
    /// (the set record's `name`, e.g. a Gmsh physical group's; only where it has one).
    #[getter]
    fn sets<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let out = PyDict::new(py);
        for i in 0..self.model.sets.len() {
            out.set_item(i + 1, self.set_dict(py, i)?)?;
        }
        Ok(out)
    }

    /// The set `key`: its number or its name, as a dict of `sets`.
    fn set<'py>(&self, py: Python<'py>, key: RecordKey) -> PyResult<Bound<'py, PyDict>> {
        let number = match key {
            RecordKey::Number(n) if (1..=self.model.sets.len()).contains(&n) => n,
            RecordKey::Number(n) => {
                return Err(PyKeyError::new_err(format!(
                    "no set {n} (1..={})",
                    self.model.sets.len()
                )))
            }
            RecordKey::Name(name) => self.set_number(&name)?,
        };
        self.set_dict(py, number - 1)
    }

    /// Material number → dict: `law` and, for `IsoLE` and `MisesMat`, `E` and `nu`.
    #[getter]
    fn materials<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let out = PyDict::new(py);
        for (i, m) in self.model.materials.iter().enumerate() {
            let d = PyDict::new(py);
            let (law, e) = match &m.law {
                MaterialLaw::LinearElastic { young, poisson } => ("IsoLE", Some((young, poisson))),
                MaterialLaw::Mises(hertz::model::Mises { young, poisson, .. }) => {
                    ("MisesMat", Some((young, poisson)))
                }
                MaterialLaw::MooneyRivlin { .. }
                | MaterialLaw::Ogden { .. }
                | MaterialLaw::SimoPister { .. } => ("hyperelastic", None),
                MaterialLaw::Dummy => ("DummyMat", None),
            };
            d.set_item("law", law)?;
            if let Some((young, poisson)) = e {
                d.set_item("E", *young)?;
                d.set_item("nu", *poisson)?;
            }
            out.set_item(i + 1, d)?;
        }
        Ok(out)
    }

    /// Contact condition (boundary-condition record number) → dict: `law` ("penalty" or
    /// "multipliers"), `penalty` (None when it comes from the mesh, or with multipliers) and
    /// `friction` (the coefficient, None without friction).
    #[getter]
    fn contacts<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let out = PyDict::new(py);
        for c in &self.model.contacts {
            let d = PyDict::new(py);
            let (law, penalty) = match c.enforcement {
                Enforcement::Penalty(PenaltySource::Given(p)) => ("penalty", Some(p)),
                Enforcement::Penalty(PenaltySource::FromMesh) => ("penalty", None),
                Enforcement::Multipliers => ("multipliers", None),
            };
            d.set_item("law", law)?;
            d.set_item("penalty", penalty)?;
            d.set_item("friction", c.friction.map(|f| f.mu))?;
            out.set_item(c.number, d)?;
        }
        Ok(out)
    }

    /// Boundary condition record number → dict: `dofs` (DOF ids, 1 = x, 2 = y, 3 = z), `values`
    /// and `set`.
    #[getter]
    fn boundary_conditions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let out = PyDict::new(py);
        for b in &self.model.dirichlet {
            let d = PyDict::new(py);
            d.set_item("dofs", b.dofs.clone())?;
            d.set_item("values", b.values.clone())?;
            d.set_item("set", b.set)?;
            out.set_item(b.number, d)?;
        }
        Ok(out)
    }

    /// Load record number → dict: `kind` (the record's name), `components` and `set`.
    #[getter]
    fn loads<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let out = PyDict::new(py);
        for l in &self.model.loads {
            let d = PyDict::new(py);
            d.set_item("kind", l.kind.record_name())?;
            d.set_item("components", l.components.clone())?;
            d.set_item("set", l.set)?;
            out.set_item(l.number, d)?;
        }
        Ok(out)
    }

    /// The times of the analysis' steps.
    #[getter]
    fn step_times(&self) -> Vec<f64> {
        self.model.step_times()
    }

    /// Change material `number`'s Young's modulus `E` and/or Poisson's ratio `nu` (`IsoLE` and
    /// `MisesMat`).
    #[pyo3(signature = (number, *, E = None, nu = None))]
    #[allow(non_snake_case)]
    fn set_material(&mut self, number: usize, E: Option<f64>, nu: Option<f64>) -> PyResult<()> {
        let n = self.model.materials.len();
        let m = number
            .checked_sub(1)
            .and_then(|i| self.model.materials.get_mut(i))
            .ok_or_else(|| PyKeyError::new_err(format!("no material {number} (1..={n})")))?;
        let (young, poisson) = match &mut m.law {
            MaterialLaw::LinearElastic { young, poisson } => (young, poisson),
            MaterialLaw::Mises(hertz::model::Mises { young, poisson, .. }) => (young, poisson),
            _ => {
                return Err(PyValueError::new_err(format!(
                    "material {number}: E and nu can be set on IsoLE and MisesMat only"
                )))
            }
        };
        if let Some(e) = E {
            if !(e > 0.0 && e.is_finite()) {
                return Err(PyValueError::new_err(format!("E must be > 0, not {e}")));
            }
            *young = e;
        }
        if let Some(v) = nu {
            if !(v > -1.0 && v < 0.5) {
                return Err(PyValueError::new_err(format!(
                    "nu must be in (-1, 0.5), not {v}"
                )));
            }
            *poisson = v;
        }
        Ok(())
    }

    /// Change contact condition `number`'s penalty (a penalty condition; its penalty then no
    /// longer comes from the mesh) and/or friction coefficient (a condition with friction).
    #[pyo3(signature = (number, *, penalty = None, friction = None))]
    fn set_contact(
        &mut self,
        number: usize,
        penalty: Option<f64>,
        friction: Option<f64>,
    ) -> PyResult<()> {
        let c = self
            .model
            .contacts
            .iter_mut()
            .find(|c| c.number == number)
            .ok_or_else(|| PyKeyError::new_err(format!("no contact condition {number}")))?;
        if let Some(p) = penalty {
            if !(p > 0.0 && p.is_finite()) {
                return Err(PyValueError::new_err(format!(
                    "penalty must be > 0, not {p}"
                )));
            }
            if c.enforcement == Enforcement::Multipliers {
                return Err(PyValueError::new_err(format!(
                    "contact condition {number} uses Lagrange multipliers: it has no penalty"
                )));
            }
            c.enforcement = Enforcement::Penalty(PenaltySource::Given(p));
        }
        if let Some(mu) = friction {
            if !(mu >= 0.0 && mu.is_finite()) {
                return Err(PyValueError::new_err(format!(
                    "friction must be >= 0, not {mu}"
                )));
            }
            match &mut c.friction {
                Some(f) => f.mu = mu,
                None => {
                    return Err(PyValueError::new_err(format!(
                        "contact condition {number} has no friction: give it a coefficient in \
                         the input first"
                    )))
                }
            }
        }
        Ok(())
    }

    /// Change boundary condition `key`'s prescribed values (its record number, or the name of
    /// the set it is the one boundary condition of): one per DOF it prescribes, or one number
    /// for all of them.
    fn set_boundary_condition(
        &mut self,
        key: RecordKey,
        values: &Bound<'_, PyAny>,
    ) -> PyResult<()> {
        let records = self
            .model
            .dirichlet
            .iter()
            .filter_map(|b| b.set.map(|s| (b.number, s)));
        let number = self.record_number(key, "boundary condition", records)?;
        let b = self
            .model
            .dirichlet
            .iter_mut()
            .find(|b| b.number == number)
            .ok_or_else(|| PyKeyError::new_err(format!("no boundary condition {number}")))?;
        b.values = values_for(values, b.values.len(), "boundary condition", number)?;
        Ok(())
    }

    /// Change load `key`'s components (its record number, or the name of the set it is the one
    /// load of): as many as the record has, or one number for all.
    fn set_load(&mut self, key: RecordKey, components: &Bound<'_, PyAny>) -> PyResult<()> {
        let records = self.model.loads.iter().map(|l| (l.number, l.set));
        let number = self.record_number(key, "load", records)?;
        let l = self
            .model
            .loads
            .iter_mut()
            .find(|l| l.number == number)
            .ok_or_else(|| PyKeyError::new_err(format!("no load {number}")))?;
        l.components = values_for(components, l.components.len(), "load", number)?;
        Ok(())
    }

    /// Run the analysis, printing nothing. `observer`, if given, is called with a dict for every
    /// Newton iteration (`kind` "iteration"), converged step ("step"), cut-back ("retry") and
    /// warning ("warning"); an exception it raises stops the analysis and is raised here.
    /// Ctrl-C stops the analysis (KeyboardInterrupt). A failure to converge raises
    /// `hertz.SolveError`, whose `.result` holds the steps that converged.
    #[pyo3(signature = (observer = None))]
    fn solve(&self, py: Python<'_>, observer: Option<Py<PyAny>>) -> PyResult<PyResultObj> {
        let obs = PyObserver::new(py, observer);
        let mut steps: Vec<StepData> = Vec::new();
        let mut dofs = None;
        let clock = std::time::Instant::now();
        let run = run_analysis_observed(&self.model, &SolveParams::default(), &obs, |res| {
            if dofs.is_none() {
                dofs = Some(res.dofs.clone());
            }
            steps.push(StepData::from_result(res, &self.model));
            Ok(())
        });
        let result = PyResultObj::new(
            py,
            self.model.clone(),
            self.sources.clone(),
            dofs,
            steps,
            obs.take_warnings(),
            run.as_ref().err().map(|e| e.to_string()),
            clock.elapsed().as_secs_f64(),
        )?;
        if let Some(e) = obs.take_error() {
            return Err(e);
        }
        match run {
            Ok(()) => Ok(result),
            Err(e) => {
                let result = Py::new(py, result)?.into_any();
                Err(to_py_err(py, e, Some(result)))
            }
        }
    }

    fn __repr__(&self) -> String {
        format!(
            "<hertz.Model {:?}: {} nodes, {} elements, {} contact conditions, {} steps>",
            self.model.input_path.display().to_string(),
            self.model.nodes.len(),
            self.model.elements.len(),
            self.model.contacts.len(),
            self.model.step_times().len()
        )
    }
}

/// `n` numbers from a Python number (repeated) or sequence of `n` numbers.
fn values_for(v: &Bound<'_, PyAny>, n: usize, what: &str, number: usize) -> PyResult<Vec<f64>> {
    let vals = if let Ok(x) = v.extract::<f64>() {
        vec![x; n]
    } else {
        v.extract::<Vec<f64>>()?
    };
    if vals.len() != n {
        return Err(PyValueError::new_err(format!(
            "{what} {number} has {n} values, not {}",
            vals.len()
        )));
    }
    if let Some(x) = vals.iter().find(|x| !x.is_finite()) {
        return Err(PyValueError::new_err(format!(
            "{what} {number}: {x} is not finite"
        )));
    }
    Ok(vals)
}

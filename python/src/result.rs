//! `hertz.Result` and `hertz.Step`: the converged steps of a run as numpy arrays, and the files
//! `hertz run` writes.

use crate::arrays::array2;
use crate::to_py_err;
use hertz::assembly::DofMap;
use hertz::contact::SlotState;
use hertz::model::Model as HModel;
use hertz::output::vtu::VtuFormat;
use hertz::output::writer::RunWriter;
use hertz::solid::GpState;
use hertz::solve::{Energy, Motion, StepInfo, StepResult};
use numpy::{IntoPyArray, PyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;

/// What a converged step leaves, owned (the solver's `StepResult` borrows).
pub struct StepData {
    step: usize,
    time: f64,
    u: Vec<f64>,
    reactions: Vec<f64>,
    states: Vec<Vec<GpState>>,
    contact: Vec<SlotState>,
    info: StepInfo,
    /// n_nodes × DOFs per node, row-major (taken for the numpy arrays).
    displacement: Vec<f64>,
    reaction: Vec<f64>,
    /// Dynamics: velocities and accelerations (primary DOFs, as `u`) and the energies.
    motion: Option<(Vec<f64>, Vec<f64>, Energy)>,
    /// Dynamics: nodal velocities and accelerations (as `displacement`).
    velocity: Option<Vec<f64>>,
    acceleration: Option<Vec<f64>>,
}

/// Values of the primary vector `x` at every node's DOFs (n_nodes × DOFs per node).
fn nodal(res: &StepResult, model: &HModel, x: &[f64]) -> Vec<f64> {
    let ids = model.domain.default_dofs();
    let nd = ids.len();
    let mut out = vec![0.0; model.nodes.len() * nd];
    for n in 0..model.nodes.len() {
        for (k, &d) in ids.iter().enumerate() {
            out[n * nd + k] = res.dofs.code(n, d).map_or(0.0, |c| res.dofs.value(x, c));
        }
    }
    out
}

impl StepData {
    pub fn from_result(res: &StepResult, model: &HModel) -> StepData {
        let ids = model.domain.default_dofs();
        let nd = ids.len();
        let displacement = nodal(res, model, res.u);
        let mut reaction = vec![0.0; model.nodes.len() * nd];
        for (i, &(n, d, _)) in res.dofs.prescribed.iter().enumerate() {
            if let Some(k) = ids.iter().position(|&id| id == d) {
                reaction[n * nd + k] += res.reactions[i];
            }
        }
        StepData {
            step: res.step,
            time: res.time,
            u: res.u.to_vec(),
            reactions: res.reactions.to_vec(),
            states: res.states.to_vec(),
            contact: res.contact.to_vec(),
            info: res.info.clone(),
            displacement,
            reaction,
            motion: res
                .motion
                .map(|m| (m.velocity.to_vec(), m.acceleration.to_vec(), m.energy)),
            velocity: res.motion.map(|m| nodal(res, model, m.velocity)),
            acceleration: res.motion.map(|m| nodal(res, model, m.acceleration)),
        }
    }
}

/// One converged step: `displacement` and `reaction` (n_nodes × DOFs per node, rows in the
/// order of `Model.node_labels`, columns x, y(, z); reactions are zero where nothing is
/// prescribed), in a dynamic analysis `velocity` and `acceleration` (the same shape; None in
/// statics) and `energy` (kinetic, internal, contact, damping, external, supports, balance: the
/// columns of the energy CSV), `iterations`, `substeps`, `contact`: the columns of the contact CSV as arrays
/// (one entry per contact node), and `points`: the integration points' results as arrays (one
/// row per point, see [`points_dict`]).
#[pyclass(module = "hertz", name = "Step", frozen)]
pub struct Step {
    #[pyo3(get)]
    step: usize,
    #[pyo3(get)]
    time: f64,
    #[pyo3(get)]
    iterations: usize,
    #[pyo3(get)]
    substeps: usize,
    #[pyo3(get)]
    displacement: Py<PyArray2<f64>>,
    #[pyo3(get)]
    reaction: Py<PyArray2<f64>>,
    #[pyo3(get)]
    velocity: Option<Py<PyArray2<f64>>>,
    #[pyo3(get)]
    acceleration: Option<Py<PyArray2<f64>>>,
    #[pyo3(get)]
    energy: Option<Py<PyDict>>,
    #[pyo3(get)]
    contact: Py<PyDict>,
    #[pyo3(get)]
    points: Py<PyDict>,
}

#[pymethods]
impl Step {
    fn __repr__(&self) -> String {
        format!(
            "<hertz.Step {} (t = {}): {} iterations>",
            self.step, self.time, self.iterations
        )
    }
}

/// The integration points of one step, element by element: `element` (label), `gp` (from 1),
/// `strain` and `stress` (n × 6, Voigt xx yy zz yz xz xy with engineering shears; the
/// Green–Lagrange strain and second Piola–Kirchhoff stress with `nlgeo 1`), and where a
/// material is plastic `plastic_strain` (n × 6), `kappa` and `damage` (0 at elastic points);
/// and their nodal averages `nodal_strain` and `nodal_stress` (n_nodes × 6, rows in the order
/// of `Model.node_labels`; see [`nodal_average`]).
fn points_dict<'py>(
    py: Python<'py>,
    model: &HModel,
    states: &[Vec<GpState>],
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let all = || {
        states
            .iter()
            .enumerate()
            .flat_map(|(e, pts)| pts.iter().enumerate().map(move |(g, p)| (e, g, p)))
    };
    let n = all().count();
    let element: Vec<i64> = all()
        .map(|(e, _, _)| model.elements[e].label as i64)
        .collect();
    let gp: Vec<i64> = all().map(|(_, g, _)| g as i64 + 1).collect();
    d.set_item("element", element.into_pyarray(py))?;
    d.set_item("gp", gp.into_pyarray(py))?;
    let six = |f: &dyn Fn(&GpState) -> [f64; 6]| all().flat_map(|(_, _, p)| f(p)).collect();
    d.set_item("strain", array2(py, n, 6, six(&|p| p.strain)))?;
    d.set_item("stress", array2(py, n, 6, six(&|p| p.stress)))?;
    let nn = model.nodes.len();
    let strain = nodal_average(model, states, |p| p.strain);
    let stress = nodal_average(model, states, |p| p.stress);
    d.set_item("nodal_strain", array2(py, nn, 6, strain))?;
    d.set_item("nodal_stress", array2(py, nn, 6, stress))?;
    if all().any(|(_, _, p)| p.plastic.is_some()) {
        let plastic = |p: &GpState| p.plastic.unwrap_or_default();
        d.set_item(
            "plastic_strain",
            array2(py, n, 6, six(&|p| plastic(p).strain)),
        )?;
        let col = |f: &dyn Fn(&GpState) -> f64| all().map(|(_, _, p)| f(p)).collect::<Vec<f64>>();
        d.set_item("kappa", col(&|p| plastic(p).kappa).into_pyarray(py))?;
        d.set_item("damage", col(&|p| plastic(p).damage).into_pyarray(py))?;
    }
    Ok(d)
}

/// A point quantity `f` averaged at every node (n_nodes × 6): the mean over the elements
/// around the node of each element's mean over its points (what the VTU's cell data hold),
/// NaN at a node of no element with points (a rigid body's reference node).
fn nodal_average(
    model: &HModel,
    states: &[Vec<GpState>],
    f: impl Fn(&GpState) -> [f64; 6],
) -> Vec<f64> {
    let mut sum = vec![0.0; model.nodes.len() * 6];
    let mut count = vec![0usize; model.nodes.len()];
    for (e, pts) in states.iter().enumerate() {
        if pts.is_empty() {
            continue;
        }
        let mean = GpState::mean(pts, &f);
        for &n in &model.elements[e].nodes {
            count[n] += 1;
            for (k, m) in mean.iter().enumerate() {
                sum[n * 6 + k] += m;
            }
        }
    }
    for (n, &c) in count.iter().enumerate() {
        for v in &mut sum[n * 6..n * 6 + 6] {
            *v = if c > 0 { *v / c as f64 } else { f64::NAN };
        }
    }
    sum
}

/// The contact CSV's columns of one step.
fn contact_dict<'py>(
    py: Python<'py>,
    model: &HModel,
    states: &[SlotState],
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let col = |f: &dyn Fn(&SlotState) -> f64| states.iter().map(f).collect::<Vec<f64>>();
    let icol = |f: &dyn Fn(&SlotState) -> i64| states.iter().map(f).collect::<Vec<i64>>();
    d.set_item("condition", icol(&|s| s.condition as i64).into_pyarray(py))?;
    d.set_item(
        "node",
        icol(&|s| model.nodes[s.node].label as i64).into_pyarray(py),
    )?;
    d.set_item("x", col(&|s| s.x[0]).into_pyarray(py))?;
    d.set_item("y", col(&|s| s.x[1]).into_pyarray(py))?;
    d.set_item("z", col(&|s| s.x[2]).into_pyarray(py))?;
    d.set_item("gap", col(&|s| s.gap).into_pyarray(py))?;
    d.set_item("force", col(&|s| s.force).into_pyarray(py))?;
    d.set_item("pressure", col(&|s| s.pressure).into_pyarray(py))?;
    let active: Vec<bool> = states.iter().map(|s| s.active).collect();
    d.set_item("active", active.into_pyarray(py))?;
    d.set_item(
        "friction",
        col(&|s| s.friction.map_or(0.0, |f| f.1)).into_pyarray(py),
    )?;
    let slip: Vec<bool> = states
        .iter()
        .map(|s| s.friction.is_some_and(|f| !f.0))
        .collect();
    d.set_item("slip", slip.into_pyarray(py))?;
    Ok(d)
}

/// The converged steps of an analysis (all of them, or those before it stopped: `converged`
/// is then False and `message` says why), the solver's `warnings`, and `write`.
#[pyclass(module = "hertz", name = "Result", frozen)]
pub struct Result {
    model: HModel,
    sources: Vec<PathBuf>,
    dofs: Option<DofMap>,
    data: Vec<StepData>,
    #[pyo3(get)]
    steps: Vec<Py<Step>>,
    #[pyo3(get)]
    warnings: Vec<String>,
    #[pyo3(get)]
    message: Option<String>,
    wall_seconds: f64,
}

impl Result {
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        py: Python<'_>,
        model: HModel,
        sources: Vec<PathBuf>,
        dofs: Option<DofMap>,
        mut data: Vec<StepData>,
        warnings: Vec<String>,
        message: Option<String>,
        wall_seconds: f64,
    ) -> PyResult<Result> {
        let nd = model.domain.default_dofs().len();
        let n = model.nodes.len();
        let mut steps = Vec::with_capacity(data.len());
        for s in &mut data {
            let energy = match &s.motion {
                Some((_, _, e)) => {
                    let d = PyDict::new(py);
                    for (k, x) in [
                        ("kinetic", e.kinetic),
                        ("internal", e.internal),
                        ("contact", e.contact),
                        ("damping", e.damping),
                        ("external", e.external),
                        ("supports", e.supports),
                        ("balance", e.balance()),
                    ] {
                        d.set_item(k, x)?;
                    }
                    Some(d.unbind())
                }
                None => None,
            };
            let step = Step {
                velocity: s.velocity.take().map(|v| array2(py, n, nd, v).unbind()),
                acceleration: s.acceleration.take().map(|a| array2(py, n, nd, a).unbind()),
                energy,
                step: s.step,
                time: s.time,
                iterations: s.info.iterations,
                substeps: s.info.substeps,
                displacement: array2(py, n, nd, std::mem::take(&mut s.displacement)).unbind(),
                reaction: array2(py, n, nd, std::mem::take(&mut s.reaction)).unbind(),
                contact: contact_dict(py, &model, &s.contact)?.unbind(),
                points: points_dict(py, &model, &s.states)?.unbind(),
            };
            steps.push(Py::new(py, step)?);
        }
        Ok(Result {
            model,
            sources,
            dofs,
            data,
            steps,
            warnings,
            message,
            wall_seconds,
        })
    }
}

#[pymethods]
impl Result {
    /// Whether every step of the analysis converged.
    #[getter]
    fn converged(&self) -> bool {
        self.message.is_none()
    }

    /// Write the files `hertz run` writes (the `.out` file, a VTU file per step and the PVD
    /// collection, the contact, step and Newton CSV files) into `dir`, named after the output
    /// file the input names; returns their paths. An input file is never overwritten.
    fn write(&self, py: Python<'_>, dir: PathBuf) -> PyResult<Vec<PathBuf>> {
        let err = |e| to_py_err(py, e, None);
        let mut writer =
            RunWriter::new(&self.model, &dir, VtuFormat::default(), &self.sources).map_err(err)?;
        if let Some(dofs) = &self.dofs {
            for s in &self.data {
                writer
                    .step(&StepResult {
                        step: s.step,
                        time: s.time,
                        dofs,
                        u: &s.u,
                        reactions: &s.reactions,
                        states: &s.states,
                        contact: &s.contact,
                        info: &s.info,
                        motion: s.motion.as_ref().map(|(v, a, e)| Motion {
                            velocity: v,
                            acceleration: a,
                            energy: *e,
                        }),
                    })
                    .map_err(err)?;
            }
        }
        let stopped = self.message.as_ref().map(|m| m as &dyn std::fmt::Display);
        Ok(writer
            .finish(stopped, self.wall_seconds)
            .map_err(err)?
            .files)
    }

    fn __len__(&self) -> usize {
        self.steps.len()
    }

    fn __repr__(&self) -> String {
        format!(
            "<hertz.Result: {} steps{}>",
            self.steps.len(),
            if self.message.is_some() {
                ", stopped"
            } else {
                ""
            }
        )
    }
}

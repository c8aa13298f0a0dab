//! The loads and prescribed values of a model over time: each load's reference vector (its
//! components at f = 1), scaled per step by its time function as the analysis accumulates it.

use crate::assembly::DofMap;
use crate::error::Result;
use crate::model::{AnalysisKind, Model};
use crate::solid::loads::reference_contributions;

/// The loads and prescribed values of a model over time.
pub(super) struct LoadHistory<'a> {
    model: &'a Model,
    dofs: &'a DofMap,
    /// Per time function, the load vector it scales.
    reference: Vec<(usize, Vec<f64>)>,
}

impl<'a> LoadHistory<'a> {
    pub(super) fn new(model: &'a Model, dofs: &'a DofMap) -> Result<LoadHistory<'a>> {
        Ok(LoadHistory {
            model,
            dofs,
            reference: reference_load_vectors(model, dofs)?,
        })
    }

    /// Σ scale(f)·(load vector of f).
    fn external(&self, scale: &dyn Fn(usize) -> f64) -> Vec<f64> {
        let mut f = vec![0.0; self.dofs.n_primary()];
        for (func, v) in &self.reference {
            let s = scale(*func);
            if s != 0.0 {
                for (a, b) in f.iter_mut().zip(v) {
                    *a += s * b;
                }
            }
        }
        f
    }

    /// The external forces at time `t`, `applied` those of the last step (NonLinearStatic
    /// `refloadmode 1` adds the increment to them).
    pub(super) fn external_at(&self, t: f64, applied: &[f64]) -> Vec<f64> {
        let (model, a) = (self.model, &self.model.analysis);
        match a.kind {
            AnalysisKind::NonLinearStatic => {
                let r = self.external(&|f| {
                    let func = &model.functions[f];
                    if a.refloadmode == 1 {
                        func.eval(t) - func.eval(t - a.deltat)
                    } else {
                        func.eval(t)
                    }
                });
                applied.iter().zip(&r).map(|(x, y)| x + y).collect()
            }
            _ => self.total_at(t),
        }
    }

    /// The external forces at time `t` when loads are total (f(t) times each load, as in
    /// dynamics), not accumulated over steps.
    pub(super) fn total_at(&self, t: f64) -> Vec<f64> {
        self.external(&|f| self.model.functions[f].eval(t))
    }

    /// The factor of every load at time `t` (`applied` those of the last step): what its time
    /// function scales it by, as [`Self::external_at`] sums them.
    pub(super) fn factors_at(&self, t: f64, applied: &[f64]) -> Vec<f64> {
        let (model, a) = (self.model, &self.model.analysis);
        model
            .loads
            .iter()
            .zip(applied)
            .map(|(load, &before)| {
                let func = &model.functions[load.function - 1];
                match a.kind {
                    AnalysisKind::NonLinearStatic if a.refloadmode == 1 => {
                        before + func.eval(t) - func.eval(t - a.deltat)
                    }
                    AnalysisKind::NonLinearStatic => before + func.eval(t),
                    _ => func.eval(t),
                }
            })
            .collect()
    }

    /// Every load's factor at time `t` when loads are total: its time function's value.
    pub(super) fn total_factors_at(&self, t: f64) -> Vec<f64> {
        let model = self.model;
        model
            .loads
            .iter()
            .map(|load| model.functions[load.function - 1].eval(t))
            .collect()
    }

    /// The prescribed values at time `t`.
    pub(super) fn prescribed_at(&self, t: f64) -> Vec<f64> {
        self.dofs
            .prescribed
            .iter()
            .map(|&(_, d, bi)| {
                let bc = &self.model.dirichlet[bi];
                bc.value_for(d) * self.model.functions[bc.function - 1].eval(t)
            })
            .collect()
    }
}

/// Reference load vector of every load (components at f = 1) in primary numbering, with the
/// index of its time function.
pub fn reference_load_vectors(model: &Model, dofs: &DofMap) -> Result<Vec<(usize, Vec<f64>)>> {
    let np = dofs.n_primary();
    let mut out = Vec::with_capacity(model.loads.len());
    for load in &model.loads {
        let mut v = vec![0.0; np];
        for (node, d, val) in reference_contributions(model, load)? {
            if let Some(code) = dofs.code(node, d) {
                for (p, w) in dofs.entries(code) {
                    v[p] += w * val;
                }
            }
        }
        out.push((load.function - 1, v));
    }
    Ok(out)
}

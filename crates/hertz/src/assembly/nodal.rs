//! [`NodalState`]: what contact sees of a primary state. Elements get their local values gathered
//! by the assembler; contact gets, node by node, the current and start positions, the location
//! codes of the displacement DOFs and the multipliers' values, and knows nothing of how the
//! global vectors are numbered.

use super::dofs::DofMap;
use crate::error::{Error, Result};
use crate::model::Model;
use std::ops::Range;

/// A primary state `u` seen through the nodes (and the start state of the step, if given).
#[derive(Clone, Copy)]
pub struct NodalState<'a> {
    model: &'a Model,
    dofs: &'a DofMap,
    u: &'a [f64],
    start: Option<&'a [f64]>,
    dim: usize,
}

impl<'a> NodalState<'a> {
    /// The state `u` of `model` numbered by `dofs`, with no start state (the reference
    /// configuration stands for it).
    pub fn new(model: &'a Model, dofs: &'a DofMap, u: &'a [f64]) -> NodalState<'a> {
        NodalState {
            model,
            dofs,
            u,
            start: None,
            dim: model.domain.nsd(),
        }
    }

    /// The same state with `start` as the last converged state (friction's history).
    pub fn with_start(self, start: Option<&'a [f64]>) -> NodalState<'a> {
        NodalState { start, ..self }
    }

    pub fn model(&self) -> &'a Model {
        self.model
    }

    /// Whether a start state was given.
    pub fn has_start(&self) -> bool {
        self.start.is_some()
    }

    /// Current position of node `n` and the location codes of its displacement DOFs; a node
    /// without one of them is an error (contact needs every component).
    pub fn position(&self, n: usize) -> Result<([f64; 3], [usize; 3])> {
        let mut x = self.model.nodes[n].coords;
        let mut codes = [0; 3];
        for d in 0..self.dim {
            let code = self.dofs.code(n, d as u8 + 1).ok_or_else(|| {
                Error::Solve(format!(
                    "contact node {} has no DOF {}",
                    self.model.nodes[n].label,
                    d + 1
                ))
            })?;
            x[d] += self.dofs.value(self.u, code);
            codes[d] = code;
        }
        Ok((x, codes))
    }

    /// Position of node `n` in the start state (its reference position without one).
    pub fn start_position(&self, n: usize) -> [f64; 3] {
        let mut x = self.model.nodes[n].coords;
        if let Some(u) = self.start {
            for (d, xd) in x.iter_mut().enumerate().take(self.dim) {
                if let Some(code) = self.dofs.code(n, d as u8 + 1) {
                    *xd += self.dofs.value(u, code);
                }
            }
        }
        x
    }

    /// The equation of the first contact multiplier (multipliers are numbered in the order of
    /// the conditions, after the displacement equations).
    pub fn first_multiplier(&self) -> usize {
        self.dofs.n_free - self.dofs.n_lambda
    }

    /// Whether location code `code` moves with a free displacement equation (else every primary
    /// DOF it follows is prescribed).
    pub fn is_free(&self, code: usize) -> bool {
        let first = self.first_multiplier();
        self.dofs.entries(code).any(|(p, _)| p < first)
    }

    /// The values of the multiplier equations `eqs`.
    pub fn multipliers(&self, eqs: Range<usize>) -> &'a [f64] {
        &self.u[eqs]
    }

    /// The free displacement equations of `nodes`' DOFs (through the weights of slave nodes),
    /// sorted and without repeats.
    pub fn displacement_equations(&self, nodes: impl IntoIterator<Item = usize>) -> Vec<usize> {
        let dofs = self.dofs;
        let mut eqs: Vec<usize> = nodes
            .into_iter()
            .flat_map(|n| {
                dofs.node_dofs[n]
                    .iter()
                    .flat_map(|&(_, c)| dofs.entries(c).map(|(p, _)| p))
            })
            .filter(|&p| p < self.first_multiplier())
            .collect();
        eqs.sort_unstable();
        eqs.dedup();
        eqs
    }
}

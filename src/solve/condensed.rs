//! Newton systems of linear elastic bodies in penalty contact, condensed on the contact DOFs.
//!
//! The elastic stiffness K_el is constant: it is factorized once with the contact-candidate DOFs c
//! eliminated last, so the trailing block L₂₂ of its factor gives the Schur complement
//! S = L₂₂L₂₂ᵀ and (K_el⁻¹)_cc = S⁻¹ without further solves. The contact tangent C lives on the
//! active contact DOFs A ⊂ c; by Woodbury's identity
//!   (K_el + PᵀCP)⁻¹ r = w − K_el⁻¹ Pᵀ y,  w = K_el⁻¹ r,  (I + C (S⁻¹)_AA) y = C w_A,
//! so a Newton iteration costs two sparse solves and a dense system of the size of the active set,
//! instead of a factorization.

use super::linear::LinearSolver;
use crate::assembly::{Contribution, DofMap, Pattern};
use crate::error::{Error, Result};
use faer::linalg::solvers::Solve;
use faer::Mat;
use std::collections::HashMap;

/// Largest candidate set handled densely (S⁻¹ is m × m).
pub const MAX_CANDIDATES: usize = 3000;

pub struct CondensedContact {
    base: LinearSolver,
    /// Position of each candidate equation in S⁻¹.
    pos: HashMap<usize, usize>,
    /// (K_el⁻¹)_cc.
    s_inv: Mat<f64>,
}

impl CondensedContact {
    /// Factorize K_el (upper triangle `values` on `pattern`) with `candidates` last. None when the
    /// factor is not supernodal with the candidates trailing, or K_el is singular on its own (a
    /// body held only by contact): the caller then factorizes the full tangent.
    pub fn new(
        pattern: &Pattern,
        values: &[f64],
        candidates: Vec<usize>,
        groups: Option<Vec<usize>>,
    ) -> Option<Self> {
        if candidates.is_empty() || candidates.len() > MAX_CANDIDATES {
            return None;
        }
        let mut base = LinearSolver::default();
        base.groups = groups;
        base.last_block = Some(candidates);
        base.factorize(pattern, values, true, &|_| String::new())
            .ok()?;
        let (eqs, l22) = base.trailing_factor_block()?;
        let m = eqs.len();
        // S⁻¹ = L₂₂⁻ᵀ L₂₂⁻¹.
        let mut linv = Mat::<f64>::identity(m, m);
        l22.as_ref().solve_lower_triangular_in_place(linv.as_mut());
        let s_inv = linv.transpose() * &linv;
        let pos = eqs.iter().enumerate().map(|(k, &e)| (e, k)).collect();
        Some(CondensedContact { base, pos, s_inv })
    }

    /// Solve (K_el + contact tangent of `contribs`) x = rhs in place. Ok(false) if a contribution
    /// touches a DOF outside the candidates (the caller then factorizes the full tangent).
    pub fn solve(
        &mut self,
        rhs: &mut [f64],
        contribs: &[Contribution],
        dofs: &DofMap,
    ) -> Result<bool> {
        let nf = dofs.n_free;
        // Dense contact tangent on the active equations A.
        let mut index: HashMap<usize, usize> = HashMap::new();
        let mut active: Vec<usize> = Vec::new();
        for c in contribs.iter().filter(|c| !c.ke.is_empty()) {
            for &code in &c.codes {
                for (p, _) in dofs.entries(code) {
                    if p < nf && !index.contains_key(&p) {
                        if !self.pos.contains_key(&p) {
                            return Ok(false);
                        }
                        index.insert(p, active.len());
                        active.push(p);
                    }
                }
            }
        }
        let m = active.len();
        let mut cmat = Mat::<f64>::zeros(m, m);
        for c in contribs.iter().filter(|c| !c.ke.is_empty()) {
            let nd = c.codes.len();
            for (a, &ca) in c.codes.iter().enumerate() {
                for (p, wp) in dofs.entries(ca).filter(|(p, _)| *p < nf) {
                    for (b, &cb) in c.codes.iter().enumerate() {
                        for (q, wq) in dofs.entries(cb).filter(|(q, _)| *q < nf) {
                            cmat[(index[&p], index[&q])] += wp * wq * c.ke[a * nd + b];
                        }
                    }
                }
            }
        }
        self.base.solve_in_place(rhs)?;
        if m == 0 {
            return Ok(true);
        }
        let sa = Mat::<f64>::from_fn(m, m, |i, j| {
            self.s_inv[(self.pos[&active[i]], self.pos[&active[j]])]
        });
        let wa = Mat::<f64>::from_fn(m, 1, |i, _| rhs[active[i]]);
        let mut mmat = &cmat * &sa;
        for i in 0..m {
            mmat[(i, i)] += 1.0;
        }
        let mut y = &cmat * &wa;
        mmat.as_ref().partial_piv_lu().solve_in_place(y.as_mut());
        let mut z = vec![0.0; nf];
        for (i, &e) in active.iter().enumerate() {
            z[e] = y[(i, 0)];
        }
        self.base.solve_in_place(&mut z)?;
        for (r, zi) in rhs.iter_mut().zip(&z) {
            *r -= zi;
        }
        if rhs.iter().any(|v| !v.is_finite()) {
            return Err(Error::Solve(
                "condensed contact update produced a non-finite step".into(),
            ));
        }
        Ok(true)
    }
}

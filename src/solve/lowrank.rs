//! Newton systems (K_el + Pᵀ C P) Δu = r for linear elastic bodies in penalty contact: K_el is
//! constant and factorized once per run; the contact tangent C lives on the few DOFs S that
//! contact touches. Woodbury's identity gives Δu = x₀ − Z y with x₀ = K_el⁻¹ r,
//! Z = K_el⁻¹ Pᵀ (cached column by column) and (I + C F) y = C x₀[S], F = P Z. Each Newton
//! iteration then costs one sparse solve and a small dense solve instead of a factorization.

use super::dofs::DofMap;
use super::linear::LinearSolver;
use crate::contact::Contribution;
use crate::error::Result;
use faer::linalg::solvers::Solve;
use faer::Mat;
use std::collections::HashMap;

/// Largest cache of Z columns, in matrix entries (8 bytes each): beyond it, the caller falls back
/// to factorizing the full tangent.
const MAX_CACHE_ENTRIES: usize = 150_000_000;

pub struct LowRankSolver {
    /// Factorization of K_el (free-free block).
    pub base: LinearSolver,
    n: usize,
    /// Z columns K_el⁻¹ e_eq by free equation.
    columns: HashMap<usize, Vec<f64>>,
}

impl LowRankSolver {
    pub fn new(base: LinearSolver, n: usize) -> Self {
        LowRankSolver {
            base,
            n,
            columns: HashMap::new(),
        }
    }

    /// Dense contact tangent on the free equations S touched by the contributions.
    fn contact_block(contribs: &[Contribution], dofs: &DofMap) -> (Vec<usize>, Vec<f64>) {
        let nf = dofs.n_free;
        let mut index: HashMap<usize, usize> = HashMap::new();
        let mut eqs = Vec::new();
        for c in contribs.iter().filter(|c| !c.ke.is_empty()) {
            for &code in &c.codes {
                for (p, _) in dofs.entries(code) {
                    if p < nf && !index.contains_key(&p) {
                        index.insert(p, eqs.len());
                        eqs.push(p);
                    }
                }
            }
        }
        let m = eqs.len();
        let mut cmat = vec![0.0; m * m];
        for c in contribs.iter().filter(|c| !c.ke.is_empty()) {
            let nd = c.codes.len();
            for (a, &ca) in c.codes.iter().enumerate() {
                for (p, wp) in dofs.entries(ca).filter(|(p, _)| *p < nf) {
                    for (b, &cb) in c.codes.iter().enumerate() {
                        for (q, wq) in dofs.entries(cb).filter(|(q, _)| *q < nf) {
                            cmat[index[&p] * m + index[&q]] += wp * wq * c.ke[a * nd + b];
                        }
                    }
                }
            }
        }
        (eqs, cmat)
    }

    /// Solve (K_el + contact tangent) x = rhs in place. Returns Ok(false), leaving `rhs` as it
    /// was, when the new columns would cost more than a factorization or overflow the cache.
    pub fn solve(
        &mut self,
        rhs: &mut [f64],
        contribs: &[Contribution],
        dofs: &DofMap,
    ) -> Result<bool> {
        let (eqs, cmat) = Self::contact_block(contribs, dofs);
        let m = eqs.len();
        let missing: Vec<usize> = eqs
            .iter()
            .copied()
            .filter(|e| !self.columns.contains_key(e))
            .collect();
        if (self.columns.len() + missing.len()) * self.n > MAX_CACHE_ENTRIES {
            return Ok(false);
        }
        // Each new column costs about one solve; more of them than one factorization is worth
        // and the caller factorizes the full tangent for this iteration instead.
        let st = &self.base.stats;
        if missing.len() as f64 * st.solve_seconds.max(1e-6) > st.numeric_seconds.max(1e-6) + 1e-3 {
            return Ok(false);
        }
        if !missing.is_empty() {
            let mut block = vec![0.0; self.n * missing.len()];
            for (k, &e) in missing.iter().enumerate() {
                block[k * self.n + e] = 1.0;
            }
            self.base.solve_columns(&mut block, missing.len())?;
            for (k, &e) in missing.iter().enumerate() {
                self.columns
                    .insert(e, block[k * self.n..(k + 1) * self.n].to_vec());
            }
        }
        self.base.solve_in_place(rhs)?;
        if m == 0 {
            return Ok(true);
        }
        // M = I + C F, t = C x0[S].
        let z: Vec<&Vec<f64>> = eqs.iter().map(|e| &self.columns[e]).collect();
        let mut mmat = Mat::<f64>::zeros(m, m);
        let mut t = Mat::<f64>::zeros(m, 1);
        for a in 0..m {
            for b in 0..m {
                let mut v = if a == b { 1.0 } else { 0.0 };
                for k in 0..m {
                    let c = cmat[a * m + k];
                    if c != 0.0 {
                        v += c * z[b][eqs[k]];
                    }
                }
                mmat[(a, b)] = v;
            }
            t[(a, 0)] = (0..m).map(|k| cmat[a * m + k] * rhs[eqs[k]]).sum();
        }
        let lu = mmat.as_ref().partial_piv_lu();
        lu.solve_in_place(t.as_mut());
        for (b, col) in z.iter().enumerate() {
            let y = t[(b, 0)];
            if y != 0.0 {
                for (r, zv) in rhs.iter_mut().zip(col.iter()) {
                    *r -= zv * y;
                }
            }
        }
        if rhs.iter().any(|v| !v.is_finite()) {
            return Err(crate::error::Error::Solve(
                "contact update produced a non-finite step".into(),
            ));
        }
        Ok(true)
    }
}

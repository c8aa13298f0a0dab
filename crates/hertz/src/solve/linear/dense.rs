//! A dense LU with partial pivoting behind [`LinearSolver`]: the reference against which the
//! sparse solvers are checked, and a solver for small systems. O(n³): not for large models.

use super::{singular, singular_at, LinearSolver, SolverStats, PIVOT_RATIO};
use crate::assembly::Pattern;
use crate::error::{Error, Result};
use faer::linalg::solvers::{PartialPivLu, SolveCore};
use faer::Mat;
use std::time::Instant;

/// Dense LU of the full matrix (a symmetric pattern's upper triangle mirrored).
#[derive(Default)]
pub struct DenseLu {
    lu: Option<PartialPivLu<f64>>,
    stats: SolverStats,
}

impl LinearSolver for DenseLu {
    fn factorize(
        &mut self,
        pattern: &Pattern,
        values: &[f64],
        _spd: bool,
        describe_eq: &dyn Fn(usize) -> String,
    ) -> Result<()> {
        let t = Instant::now();
        let n = pattern.n;
        let mut a = Mat::<f64>::zeros(n, n);
        for j in 0..n {
            for k in pattern.col_ptr[j]..pattern.col_ptr[j + 1] {
                let i = pattern.row_idx[k];
                a[(i, j)] += values[k];
                if pattern.symmetric && i != j {
                    a[(j, i)] += values[k];
                }
            }
        }
        let lu = a.as_ref().partial_piv_lu();
        // A pivot that keeps less than PIVOT_RATIO of the largest is a dependent column.
        let u = lu.U();
        let max = (0..n).map(|i| u[(i, i)].abs()).fold(0.0, f64::max);
        if let Some(k) = (0..n).find(|&i| !(u[(i, i)].abs() > PIVOT_RATIO * max)) {
            // Partial pivoting permutes rows only: pivot k is equation k's column.
            return Err(singular_at(&format!(" at {}", describe_eq(k))));
        }
        self.lu = Some(lu);
        self.stats = SolverStats {
            ordering: "none (dense)",
            numeric_seconds: t.elapsed().as_secs_f64(),
            factor_nnz: n * n,
            used_lu: true,
            ..Default::default()
        };
        Ok(())
    }

    fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<()> {
        let t = Instant::now();
        let lu = self
            .lu
            .as_ref()
            .ok_or_else(|| Error::Solve("solve called before factorize".into()))?;
        let n = rhs.len();
        let m = faer::MatMut::from_column_major_slice_mut(rhs, n, 1);
        lu.solve_in_place_with_conj(faer::Conj::No, m);
        self.stats.solve_seconds = t.elapsed().as_secs_f64();
        if rhs.iter().any(|v| !v.is_finite()) {
            return Err(singular());
        }
        Ok(())
    }

    fn stats(&self) -> &SolverStats {
        &self.stats
    }

    fn reset(&mut self) {
        self.lu = None;
    }
}

//! Sparse symmetric solver on faer: fill-reducing ordering and symbolic analysis once per
//! pattern, numeric LLᵀ per call; a sparse LU fallback when the matrix is not positive definite
//! (e.g. under compressive geometric stiffness).

use crate::assembly::Pattern;
use super::ordering::{self, OrderingKind};
use crate::error::{Error, Result};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::solvers::Solve;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LltRef, SymbolicCholesky,
    SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMat, SparseColMatRef, SymbolicSparseColMatRef, Triplet};
use faer::{Conj, MatMut, Par, Side};
use std::time::Instant;

/// Timings and sizes of the last factorization (for logs and benchmarks).
#[derive(Debug, Clone, Default)]
pub struct SolverStats {
    pub ordering: &'static str,
    pub ordering_seconds: f64,
    pub symbolic_seconds: f64,
    pub numeric_seconds: f64,
    pub solve_seconds: f64,
    pub factor_nnz: usize,
    pub used_lu: bool,
}

enum Factor {
    None,
    Llt(Vec<f64>),
    Lu(Box<faer::sparse::linalg::solvers::Lu<usize, f64>>),
}

/// Factorizes matrices that share one pattern.
pub struct LinearSolver {
    /// Fill-reducing ordering to use.
    pub ordering: OrderingKind,
    /// Node of every equation (lets METIS order the node graph).
    pub groups: Option<Vec<usize>>,
    /// Equations to eliminate last (their Schur complement is then the trailing factor block).
    pub last_block: Option<Vec<usize>>,
    symbolic: Option<SymbolicCholesky<usize>>,
    /// Parallelism chosen with the symbolic analysis.
    par: Par,
    factor: Factor,
    pub stats: SolverStats,
}

impl Default for LinearSolver {
    fn default() -> Self {
        LinearSolver {
            ordering: OrderingKind::Auto,
            groups: None,
            last_block: None,
            symbolic: None,
            par: Par::Seq,
            factor: Factor::None,
            stats: SolverStats::default(),
        }
    }
}

/// Parallelism for a pattern: faer's parallel supernodal kernels pay off on 3D-like patterns with
/// large supernodes; on 2D patterns the sequential factorization is faster (BENCHMARKS.md).
fn par_for(pattern: &Pattern) -> Par {
    if pattern.nnz() as f64 / pattern.n.max(1) as f64 > super::ordering::DENSE_PATTERN_PER_COLUMN {
        faer::get_global_parallelism()
    } else {
        Par::Seq
    }
}

impl LinearSolver {
    /// Factorize the symmetric matrix given by its upper triangle on `pattern`. When the matrix
    /// must be positive definite (`spd`: linear elasticity) a failed LLᵀ is a mechanism and is
    /// reported at its equation via `describe_eq`; otherwise a sparse LU takes over.
    pub fn factorize(
        &mut self,
        pattern: &Pattern,
        values: &[f64],
        spd: bool,
        describe_eq: &dyn Fn(usize) -> String,
    ) -> Result<()> {
        let n = pattern.n;
        let sym =
            SymbolicSparseColMatRef::new_checked(n, n, &pattern.col_ptr, None, &pattern.row_idx);
        if self.symbolic.is_none() {
            let t = Instant::now();
            let mut ord = ordering::compute(pattern, self.groups.as_deref(), self.ordering)?;
            if let Some(last) = &self.last_block {
                ord.move_to_end(last);
            }
            self.stats.ordering_seconds = t.elapsed().as_secs_f64();
            self.stats.ordering = ord.name;
            let t = Instant::now();
            let perm = faer::perm::PermRef::new_checked(&ord.fwd, &ord.inv, n);
            let s = factorize_symbolic_cholesky(
                sym,
                Side::Upper,
                SymmetricOrdering::Custom(perm),
                CholeskySymbolicParams {
                    supernodal_flop_ratio_threshold: if self.last_block.is_some() {
                        SupernodalThreshold::FORCE_SUPERNODAL
                    } else {
                        SupernodalThreshold::AUTO
                    },
                    ..Default::default()
                },
            )
            .map_err(|e| Error::Solve(format!("symbolic factorization failed: {e:?}")))?;
            self.stats.symbolic_seconds = t.elapsed().as_secs_f64();
            self.stats.factor_nnz = s.len_val();
            self.symbolic = Some(s);
            self.par = par_for(pattern);
        }
        let symbolic = self.symbolic.as_ref().expect("set above");
        let mat = SparseColMatRef::new(sym, values);
        let t = Instant::now();
        let mut l_values = match std::mem::replace(&mut self.factor, Factor::None) {
            Factor::Llt(v) => v,
            _ => vec![0.0; symbolic.len_val()],
        };
        let mut mem = MemBuffer::try_new(
            symbolic.factorize_numeric_llt_scratch::<f64>(self.par, Default::default()),
        )
        .map_err(|_| Error::Solve("out of memory for the factorization workspace".into()))?;
        let llt = symbolic.factorize_numeric_llt::<f64>(
            &mut l_values,
            mat,
            Side::Upper,
            Default::default(),
            self.par,
            MemStack::new(&mut mem),
            Default::default(),
        );
        if let Err(err) = &llt {
            if spd {
                let eq = match err {
                    // faer reports the failing pivot 1-based, in the permuted order.
                    faer::linalg::solvers::LltError::NonPositivePivot { index } => {
                        index.checked_sub(1).and_then(|k| match symbolic.perm() {
                            Some(p) => p.arrays().0.get(k).copied(),
                            None => Some(k).filter(|&i| i < n),
                        })
                    }
                };
                let at = eq
                    .map(|e| format!(" at {}", describe_eq(e)))
                    .unwrap_or_default();
                return Err(Error::Singular(format!(
                    "the stiffness matrix is singular{at}: a mechanism or an unrestrained rigid-body motion \
                     (check the supports and the elements connected there)"
                )));
            }
        }
        if llt.is_ok() {
            self.factor = Factor::Llt(l_values);
            self.stats.used_lu = false;
        } else {
            // Not positive definite: full LU on both triangles.
            let mut triplets = Vec::with_capacity(2 * values.len());
            for c in 0..n {
                for k in pattern.col_ptr[c]..pattern.col_ptr[c + 1] {
                    let r = pattern.row_idx[k];
                    triplets.push(Triplet::new(r, c, values[k]));
                    if r != c {
                        triplets.push(Triplet::new(c, r, values[k]));
                    }
                }
            }
            let full = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &triplets)
                .map_err(|e| Error::Solve(format!("cannot build the matrix: {e:?}")))?;
            let lu = full.sp_lu().map_err(|_| {
                Error::Singular(
                    "the stiffness matrix is singular: are all rigid-body motions restrained?"
                        .into(),
                )
            })?;
            self.factor = Factor::Lu(Box::new(lu));
            self.stats.used_lu = true;
        }
        self.stats.numeric_seconds = t.elapsed().as_secs_f64();
        Ok(())
    }

    /// Solve in place with the last factorization; fails on a singular matrix.
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<()> {
        let t = Instant::now();
        let n = rhs.len();
        let m = MatMut::from_column_major_slice_mut(rhs, n, 1);
        match &self.factor {
            Factor::None => return Err(Error::Solve("solve called before factorize".into())),
            Factor::Llt(values) => {
                let symbolic = self.symbolic.as_ref().expect("factorized");
                let mut mem = MemBuffer::new(symbolic.solve_in_place_scratch::<f64>(1, self.par));
                LltRef::new(symbolic, values).solve_in_place_with_conj(
                    Conj::No,
                    m,
                    self.par,
                    MemStack::new(&mut mem),
                );
            }
            Factor::Lu(lu) => lu.solve_in_place(m),
        }
        self.stats.solve_seconds = t.elapsed().as_secs_f64();
        if rhs.iter().any(|v| !v.is_finite()) {
            return Err(Error::Solve(
                "the stiffness matrix is singular: are all rigid-body motions restrained?".into(),
            ));
        }
        Ok(())
    }

    /// The trailing m × m block L₂₂ of the Cholesky factor (lower triangle, dense) and the equation
    /// at each of its positions, if the factor is supernodal and the `last_block` equations really
    /// are its last m positions. L₂₂L₂₂ᵀ is the Schur complement of the matrix on those equations.
    pub fn trailing_factor_block(&self) -> Option<(Vec<usize>, faer::Mat<f64>)> {
        use faer::sparse::linalg::cholesky::supernodal::SupernodalLltRef;
        use faer::sparse::linalg::cholesky::SymbolicCholeskyRaw;
        let last = self.last_block.as_ref()?;
        let symbolic = self.symbolic.as_ref()?;
        let Factor::Llt(values) = &self.factor else {
            return None;
        };
        let SymbolicCholeskyRaw::Supernodal(sn) = symbolic.raw() else {
            return None;
        };
        let n = symbolic.nrows();
        let m = last.len();
        let fwd: Vec<usize> = match symbolic.perm() {
            Some(p) => p.arrays().0.to_vec(),
            None => (0..n).collect(),
        };
        let eqs: Vec<usize> = fwd[n - m..].to_vec();
        let mut sorted_eqs = eqs.clone();
        sorted_eqs.sort_unstable();
        let mut sorted_last = last.clone();
        sorted_last.sort_unstable();
        if sorted_eqs != sorted_last {
            return None;
        }
        let llt = SupernodalLltRef::<usize, f64>::new(sn, values);
        let b = n - m;
        let mut l22 = faer::Mat::<f64>::zeros(m, m);
        for s in 0..sn.n_supernodes() {
            let node = llt.supernode(s);
            let start = node.start();
            let ncols = node.val().ncols();
            if start + ncols <= b {
                continue;
            }
            let pattern = node.pattern();
            let val = node.val();
            for jl in 0..ncols {
                let j = start + jl;
                if j < b {
                    continue;
                }
                for il in jl..ncols {
                    l22[(start + il - b, j - b)] = val[(il, jl)];
                }
                for (k, &r) in pattern.iter().enumerate() {
                    l22[(r - b, j - b)] = val[(ncols + k, jl)];
                }
            }
        }
        Some((eqs, l22))
    }

    /// Forget the symbolic analysis (the pattern changed).
    pub fn reset(&mut self) {
        self.symbolic = None;
        self.factor = Factor::None;
    }
}

//! Sparse solver on faer: for symmetric patterns a fill-reducing ordering and symbolic analysis
//! once per pattern and a numeric LLᵀ per call, with a sparse LU fallback when the matrix is not
//! positive definite (e.g. under compressive geometric stiffness); for general patterns (a
//! contribution that is not symmetric) a sparse LU. The LU's symbolic analysis is reused too.
//!
//! A Cholesky factorization succeeds on a matrix that is singular in exact arithmetic whenever
//! round-off leaves its zero pivots slightly positive; the solution is then arbitrary (a rigid
//! motion of an unsupported body). Every LLᵀ pivot is therefore compared with the diagonal entry
//! it came from: L_jj² < [`PIVOT_RATIO`]·A_jj means column j is a linear combination of the
//! columns before it, i.e. a mechanism.

use super::{singular, singular_at, LinearSolver, SolverSettings, SolverStats};
use crate::assembly::Pattern;
use crate::error::{Error, Result};
use crate::solve::krylov::{gmres, matvec, SymmetricPart};
use crate::solve::ordering;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LdltRef, LltRef, SymbolicCholesky,
    SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::sparse::linalg::lu::{factorize_symbolic_lu, LuRef, NumericLu, SymbolicLu};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side};
use std::time::Instant;

/// Smallest admissible ratio of a Cholesky pivot to its diagonal entry, L_jj² / A_jj. A column
/// that loses all but this fraction of its diagonal to the columns before it is dependent on them
/// up to round-off: exact rigid-body modes give ratios near 1e-16, the stiffest well-posed models
/// (slender structures, penalty contact 10⁹ times stiffer than the bodies) stay above 1e-11.
pub const PIVOT_RATIO: f64 = 1e-13;

/// A sparse LU on a fixed pattern: the symbolic analysis once, a numeric factorization per call.
/// The matrix is the general pattern's values, or a symmetric pattern's upper triangle mirrored.
struct GeneralLu {
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    /// Index into the caller's value array of every entry of the full pattern.
    source: Vec<usize>,
    values: Vec<f64>,
    symbolic: SymbolicLu<usize>,
    numeric: NumericLu<usize, f64>,
}

impl GeneralLu {
    fn new(pattern: &Pattern) -> Result<GeneralLu> {
        let n = pattern.n;
        let (col_ptr, row_idx, source) = if pattern.symmetric {
            // Both triangles of the upper pattern, rows sorted within each column.
            let mut cols: Vec<Vec<(usize, usize)>> = vec![Vec::new(); n];
            for c in 0..n {
                for k in pattern.col_ptr[c]..pattern.col_ptr[c + 1] {
                    let r = pattern.row_idx[k];
                    cols[c].push((r, k));
                    if r != c {
                        cols[r].push((c, k));
                    }
                }
            }
            let mut col_ptr = Vec::with_capacity(n + 1);
            let (mut row_idx, mut source) = (Vec::new(), Vec::new());
            col_ptr.push(0);
            for mut col in cols {
                col.sort_unstable();
                row_idx.extend(col.iter().map(|e| e.0));
                source.extend(col.iter().map(|e| e.1));
                col_ptr.push(row_idx.len());
            }
            (col_ptr, row_idx, source)
        } else {
            (
                pattern.col_ptr.clone(),
                pattern.row_idx.clone(),
                (0..pattern.nnz()).collect(),
            )
        };
        let sym = SymbolicSparseColMatRef::new_checked(n, n, &col_ptr, None, &row_idx);
        let symbolic = factorize_symbolic_lu(sym, Default::default())
            .map_err(|e| Error::Solve(format!("symbolic LU factorization failed: {e:?}")))?;
        Ok(GeneralLu {
            values: vec![0.0; row_idx.len()],
            col_ptr,
            row_idx,
            source,
            symbolic,
            numeric: NumericLu::new(),
        })
    }

    fn factorize(&mut self, values: &[f64], par: Par) -> Result<()> {
        for (v, &k) in self.values.iter_mut().zip(&self.source) {
            *v = values[k];
        }
        let n = self.col_ptr.len() - 1;
        let sym = SymbolicSparseColMatRef::new_checked(n, n, &self.col_ptr, None, &self.row_idx);
        let mat = SparseColMatRef::new(sym, &self.values);
        let mut mem = MemBuffer::try_new(
            self.symbolic
                .factorize_numeric_lu_scratch::<f64>(par, Default::default()),
        )
        .map_err(|_| Error::Solve("out of memory for the LU workspace".into()))?;
        self.symbolic
            .factorize_numeric_lu(
                &mut self.numeric,
                mat,
                par,
                MemStack::new(&mut mem),
                Default::default(),
            )
            .map_err(|_| singular())?;
        Ok(())
    }

    fn solve_in_place(&self, rhs: MatMut<'_, f64>, par: Par) {
        let mut mem = MemBuffer::new(self.symbolic.solve_in_place_scratch::<f64>(1, par));
        // SAFETY-free: `numeric` was produced by `symbolic` on this pattern.
        LuRef::new_unchecked(&self.symbolic, &self.numeric).solve_in_place_with_conj(
            Conj::No,
            rhs,
            par,
            MemStack::new(&mut mem),
        );
    }
}

enum Factor {
    None,
    Llt(Vec<f64>),
    /// LDLᵀ of a symmetric quasi-definite matrix with regularized pivots (a preconditioner).
    Ldlt(Vec<f64>),
    Lu,
    /// A general matrix above [`KRYLOV_MIN_UNKNOWNS`]: GMRES with its symmetric part.
    Krylov,
}

/// A general matrix solved by GMRES, preconditioned by a factorization of its symmetric part.
struct Krylov {
    general: Pattern,
    part: SymmetricPart,
    values: Vec<f64>,
    sym: FaerSolver,
}

/// Unknowns from which a general (non-symmetric) matrix is solved by GMRES preconditioned with its
/// symmetric part instead of a sparse LU (see [`super::krylov`]).
pub const KRYLOV_MIN_UNKNOWNS: usize = 20_000;
/// Smallest pivot of the regularized LDLᵀ preconditioner, relative to the largest diagonal.
const LDLT_REGULARIZATION: f64 = 1e-8;
/// GMRES stops at this relative residual.
pub(crate) const KRYLOV_TOL: f64 = 1e-12;

/// The faer implementation of [`LinearSolver`]: factorizes matrices that share one pattern.
pub struct FaerSolver {
    settings: SolverSettings,
    symbolic: Option<SymbolicCholesky<usize>>,
    lu: Option<GeneralLu>,
    /// Parallelism chosen with the symbolic analysis.
    par: Par,
    factor: Factor,
    krylov: Option<Box<Krylov>>,
    /// GMRES failed once on this pattern: LU from then on.
    krylov_failed: bool,
    stats: SolverStats,
}

impl Default for FaerSolver {
    fn default() -> Self {
        FaerSolver::new(SolverSettings::default())
    }
}

impl FaerSolver {
    /// A solver with `settings` (ordering, node groups, equations to eliminate last, ...).
    pub fn new(settings: SolverSettings) -> Self {
        FaerSolver {
            settings,
            symbolic: None,
            lu: None,
            par: Par::Seq,
            factor: Factor::None,
            krylov: None,
            krylov_failed: false,
            stats: SolverStats::default(),
        }
    }

    /// Its settings.
    pub fn settings(&self) -> &SolverSettings {
        &self.settings
    }
}

impl LinearSolver for FaerSolver {
    fn factorize(
        &mut self,
        pattern: &Pattern,
        values: &[f64],
        spd: bool,
        describe_eq: &dyn Fn(usize) -> String,
    ) -> Result<()> {
        FaerSolver::factorize(self, pattern, values, spd, describe_eq)
    }
    fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<()> {
        FaerSolver::solve_in_place(self, rhs)
    }
    fn stats(&self) -> &SolverStats {
        &self.stats
    }
    fn reset(&mut self) {
        FaerSolver::reset(self)
    }
    fn capabilities(&self) -> super::Capabilities {
        super::Capabilities {
            schur_block: true,
            ..Default::default()
        }
    }
    fn set_last_block(&mut self, eqs: Vec<usize>) {
        self.settings.last_block = Some(eqs);
        self.reset();
    }
    fn trailing_factor_block(&self) -> Option<(Vec<usize>, super::DenseMatrix)> {
        FaerSolver::trailing_factor_block(self)
    }
}

/// Parallelism for a pattern: faer's parallel supernodal kernels pay off on 3D-like patterns with
/// large supernodes; on 2D patterns the sequential factorization is faster (BENCHMARKS.md).
fn par_for(pattern: &Pattern) -> Par {
    let per_column = pattern.nnz() as f64 / pattern.n.max(1) as f64;
    let per_column = if pattern.symmetric {
        per_column
    } else {
        0.5 * per_column
    };
    if per_column > crate::solve::ordering::DENSE_PATTERN_PER_COLUMN {
        faer::get_global_parallelism()
    } else {
        Par::Seq
    }
}

/// The diagonal of a supernodal or simplicial factor's L storage, in elimination order: L_jj for
/// an LLᵀ, the pivot D_j for an LDLᵀ.
fn factor_diagonal(symbolic: &SymbolicCholesky<usize>, l_values: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; symbolic.nrows()];
    match symbolic.raw() {
        SymbolicCholeskyRaw::Supernodal(sn) => {
            use faer::sparse::linalg::cholesky::supernodal::SupernodalLltRef;
            let llt = SupernodalLltRef::<usize, f64>::new(sn, l_values);
            for s in 0..sn.n_supernodes() {
                let node = llt.supernode(s);
                let val = node.val();
                for jl in 0..val.ncols() {
                    out[node.start() + jl] = val[(jl, jl)];
                }
            }
        }
        SymbolicCholeskyRaw::Simplicial(sp) => {
            let (cp, ri) = (sp.col_ptr(), sp.row_idx());
            for (j, d) in out.iter_mut().enumerate() {
                if let Some(k) = (cp[j]..cp[j + 1]).find(|&k| ri[k] == j) {
                    *d = l_values[k];
                }
            }
        }
    }
    out
}

/// The smallest L_jj² / A_jj of a Cholesky factor and its position in elimination order.
fn smallest_pivot_ratio(
    symbolic: &SymbolicCholesky<usize>,
    l_values: &[f64],
    diag_of: &dyn Fn(usize) -> f64,
) -> (f64, usize) {
    let mut worst = (f64::INFINITY, 0);
    for (j, l) in factor_diagonal(symbolic, l_values).into_iter().enumerate() {
        let a = diag_of(j);
        let ratio = if a > 0.0 { l * l / a } else { f64::INFINITY };
        if ratio < worst.0 {
            worst = (ratio, j);
        }
    }
    worst
}

impl FaerSolver {
    /// Factorize the matrix given by its values on `pattern` (upper triangle of a symmetric
    /// matrix, or all entries of a general one). When a symmetric matrix must be positive definite
    /// (`spd`: linear elasticity) a failed LLᵀ is a mechanism and is reported at its equation via
    /// `describe_eq`; otherwise a sparse LU takes over. A singular matrix is an
    /// [`Error::Singular`] naming the equation where it shows, whichever the factorization.
    pub fn factorize(
        &mut self,
        pattern: &Pattern,
        values: &[f64],
        spd: bool,
        describe_eq: &dyn Fn(usize) -> String,
    ) -> Result<()> {
        let t = Instant::now();
        if !pattern.symmetric {
            if pattern.n >= self.settings.krylov_min && !self.krylov_failed {
                self.factorize_krylov(pattern, values, describe_eq)?;
            } else {
                self.factorize_lu(pattern, values)?;
            }
            self.stats.numeric_seconds = t.elapsed().as_secs_f64();
            return Ok(());
        }
        let n = pattern.n;
        let sym =
            SymbolicSparseColMatRef::new_checked(n, n, &pattern.col_ptr, None, &pattern.row_idx);
        if self.symbolic.is_none() {
            let t = Instant::now();
            let mut ord = ordering::compute(
                pattern,
                self.settings.groups.as_deref(),
                self.settings.ordering,
            )?;
            if let Some(last) = &self.settings.last_block {
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
                    supernodal_flop_ratio_threshold: if self.settings.last_block.is_some() {
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
        let llt = symbolic
            .factorize_numeric_llt::<f64>(
                &mut l_values,
                mat,
                Side::Upper,
                Default::default(),
                self.par,
                MemStack::new(&mut mem),
                Default::default(),
            )
            .map(|_| ());
        // Original equation at elimination position k.
        let original = |k: usize| match symbolic.perm() {
            Some(p) => p.arrays().0[k],
            None => k,
        };
        // A pivot that is not positive (faer, 1-based) or negligible against its diagonal.
        let failed_at = match &llt {
            Err(faer::linalg::solvers::LltError::NonPositivePivot { index }) => {
                Some(index.checked_sub(1).filter(|&k| k < n).map(original))
            }
            Ok(_) => {
                let diag = |k: usize| {
                    let e = original(k);
                    values[pattern.position(e, e)]
                };
                let (ratio, k) = smallest_pivot_ratio(symbolic, &l_values, &diag);
                (ratio < PIVOT_RATIO).then(|| Some(original(k)))
            }
        };
        match failed_at {
            None => {
                self.factor = Factor::Llt(l_values);
                self.stats.used_lu = false;
            }
            Some(eq) if spd || llt.is_ok() => {
                // Positive definite by construction, or positive pivots that vanish: singular.
                let at = eq
                    .map(|e| format!(" at {}", describe_eq(e)))
                    .unwrap_or_default();
                return Err(singular_at(&at));
            }
            Some(_) if self.settings.preconditioner => {
                self.factorize_ldlt(pattern, values, describe_eq)?
            }
            Some(_) => {
                // Not positive definite: LU on both triangles.
                self.factorize_lu(pattern, values)?;
            }
        }
        self.stats.numeric_seconds = t.elapsed().as_secs_f64();
        Ok(())
    }

    /// LDLᵀ of a symmetric matrix with the sign of every pivot prescribed: negative for the
    /// equations with no positive diagonal (multipliers of a saddle point), positive for the
    /// others; a pivot of the wrong sign (a multiplier eliminated before its displacements: zero)
    /// is replaced by [`LDLT_REGULARIZATION`] times the largest diagonal, which then acts as a
    /// stiff penalty: the factors are those of a nearby matrix, for GMRES to correct.
    fn factorize_ldlt(
        &mut self,
        pattern: &Pattern,
        values: &[f64],
        describe_eq: &dyn Fn(usize) -> String,
    ) -> Result<()> {
        let symbolic = self.symbolic.as_ref().expect("analysed");
        let n = pattern.n;
        let diag: Vec<f64> = (0..n).map(|e| values[pattern.position(e, e)]).collect();
        let signs: Vec<i8> = diag.iter().map(|&d| if d > 0.0 { 1 } else { -1 }).collect();
        let delta = LDLT_REGULARIZATION * diag.iter().fold(0.0f64, |m, d| m.max(d.abs()));
        let mut l_values = vec![0.0; symbolic.len_val()];
        let mut mem = MemBuffer::try_new(
            symbolic.factorize_numeric_ldlt_scratch::<f64>(self.par, Default::default()),
        )
        .map_err(|_| Error::Solve("out of memory for the factorization workspace".into()))?;
        symbolic
            .factorize_numeric_ldlt::<f64>(
                &mut l_values,
                SparseColMatRef::new(
                    faer::sparse::SymbolicSparseColMatRef::new_checked(
                        n,
                        n,
                        &pattern.col_ptr,
                        None,
                        &pattern.row_idx,
                    ),
                    values,
                ),
                Side::Upper,
                faer::linalg::cholesky::ldlt::factor::LdltRegularization {
                    dynamic_regularization_signs: Some(&signs),
                    dynamic_regularization_delta: delta,
                    // Pivots of the wrong sign or zero are replaced.
                    dynamic_regularization_epsilon: f64::MIN_POSITIVE,
                },
                self.par,
                MemStack::new(&mut mem),
                Default::default(),
            )
            .map_err(|e| Error::Solve(format!("LDLT factorization failed: {e:?}")))?;
        // An equation with a positive diagonal whose pivot was replaced (it was not positive:
        // the replacement is exactly δ) or vanishes against its diagonal or against the largest
        // pivot (the round-off of the stiff penalties that replaced multiplier pivots leave) is a
        // mechanism of the bodies, not a multiplier: singular there.
        let original = |k: usize| symbolic.perm().map_or(k, |p| p.arrays().0[k]);
        let pivots = factor_diagonal(symbolic, &l_values);
        let largest = pivots.iter().fold(0.0f64, |m, d| m.max(*d));
        let mechanism = pivots
            .iter()
            .enumerate()
            .find(|&(k, &d)| {
                let a = diag[original(k)];
                a > 0.0 && (d == delta || d < PIVOT_RATIO * a.max(largest))
            })
            .map(|(k, _)| original(k));
        if let Some(e) = mechanism {
            let at = format!(" at {}", describe_eq(e));
            return Err(singular_at(&at));
        }
        self.factor = Factor::Ldlt(l_values);
        self.stats.used_lu = false;
        Ok(())
    }

    /// A general matrix by GMRES: the symmetric part is factorized now by Cholesky, the
    /// iterations run at the solve; a symmetric part that is not positive definite (the saddle
    /// point of multipliers) gets a regularized LDLᵀ, a singular one is reported.
    fn factorize_krylov(
        &mut self,
        pattern: &Pattern,
        values: &[f64],
        describe_eq: &dyn Fn(usize) -> String,
    ) -> Result<()> {
        if self.krylov.is_none() {
            let sym = FaerSolver::new(SolverSettings {
                ordering: self.settings.ordering,
                groups: self.settings.groups.clone(),
                preconditioner: true,
                ..Default::default()
            });
            self.krylov = Some(Box::new(Krylov {
                general: pattern.clone(),
                part: SymmetricPart::new(pattern),
                values: Vec::new(),
                sym,
            }));
        }
        let k = self.krylov.as_mut().expect("set above");
        k.values = values.to_vec();
        let sym_values = k.part.values(values);
        match k
            .sym
            .factorize(&k.part.pattern, &sym_values, false, describe_eq)
        {
            Ok(()) => {
                self.stats.factor_nnz = k.sym.stats.factor_nnz;
                self.stats.ordering = k.sym.stats.ordering;
                self.factor = Factor::Krylov;
                self.stats.used_lu = false;
                Ok(())
            }
            // A mechanism of the bodies shows in the symmetric part (the skew part of a contact
            // tangent is small and restrains nothing).
            Err(e @ Error::Singular(_)) => Err(e),
            // Otherwise LU decides.
            Err(_) => {
                self.krylov_failed = true;
                self.factorize_lu(pattern, values)
            }
        }
    }

    fn factorize_lu(&mut self, pattern: &Pattern, values: &[f64]) -> Result<()> {
        if self.lu.is_none() {
            let t = Instant::now();
            self.lu = Some(GeneralLu::new(pattern)?);
            self.stats.symbolic_seconds = t.elapsed().as_secs_f64();
            self.par = par_for(pattern);
        }
        self.lu
            .as_mut()
            .expect("set above")
            .factorize(values, self.par)?;
        self.factor = Factor::Lu;
        self.stats.used_lu = true;
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
            Factor::Ldlt(values) => {
                let symbolic = self.symbolic.as_ref().expect("factorized");
                let mut mem = MemBuffer::new(symbolic.solve_in_place_scratch::<f64>(1, self.par));
                LdltRef::new(symbolic, values).solve_in_place_with_conj(
                    Conj::No,
                    m,
                    self.par,
                    MemStack::new(&mut mem),
                );
            }
            Factor::Lu => self
                .lu
                .as_ref()
                .expect("factorized")
                .solve_in_place(m, self.par),
            Factor::Krylov => {
                let k = self.krylov.as_mut().expect("factorized");
                let (cp, ri, vals) = (&k.general.col_ptr, &k.general.row_idx, &k.values);
                let sym = &mut k.sym;
                let solved = gmres(
                    rhs,
                    &mut |x, y| matvec(cp, ri, vals, x, y),
                    &mut |v| sym.solve_in_place(v),
                    KRYLOV_TOL,
                    50,
                    200,
                );
                match solved {
                    Ok(Some((x, iterations))) => {
                        rhs.copy_from_slice(&x);
                        self.stats.krylov_iterations = iterations;
                    }
                    _ => {
                        // Not nearly symmetric enough, or the symmetric part's factors were
                        // unusable (an indefinite part pivoted badly): LU for this pattern
                        // from now on.
                        self.krylov_failed = true;
                        self.stats.krylov_iterations = 0;
                        let (general, values) = (k.general.clone(), k.values.clone());
                        self.factorize_lu(&general, &values)?;
                        let m = MatMut::from_column_major_slice_mut(rhs, n, 1);
                        self.lu
                            .as_ref()
                            .expect("factorized")
                            .solve_in_place(m, self.par);
                    }
                }
            }
        }
        self.stats.solve_seconds = t.elapsed().as_secs_f64();
        if rhs.iter().any(|v| !v.is_finite()) {
            return Err(singular());
        }
        Ok(())
    }

    /// The trailing m × m block L₂₂ of the Cholesky factor (lower triangle, dense) and the equation
    /// at each of its positions, if the factor is supernodal and the `last_block` equations really
    /// are its last m positions. L₂₂L₂₂ᵀ is the Schur complement of the matrix on those equations.
    pub fn trailing_factor_block(&self) -> Option<(Vec<usize>, super::DenseMatrix)> {
        use faer::sparse::linalg::cholesky::supernodal::SupernodalLltRef;
        use faer::sparse::linalg::cholesky::SymbolicCholeskyRaw;
        let last = self.settings.last_block.as_ref()?;
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
        let mut l22 = super::DenseMatrix::zeros(m);
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
                    l22.set(start + il - b, j - b, val[(il, jl)]);
                }
                for (k, &r) in pattern.iter().enumerate() {
                    l22.set(r - b, j - b, val[(ncols + k, jl)]);
                }
            }
        }
        Some((eqs, l22))
    }

    /// Forget the symbolic analyses (the pattern changed).
    pub fn reset(&mut self) {
        self.symbolic = None;
        self.lu = None;
        self.krylov = None;
        self.krylov_failed = false;
        self.factor = Factor::None;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The general pattern (diagonal always present) and values of a dense matrix.
    fn from_dense(a: &[Vec<f64>]) -> (Pattern, Vec<f64>) {
        let n = a.len();
        let (mut col_ptr, mut row_idx, mut values) = (vec![0], Vec::new(), Vec::new());
        for j in 0..n {
            for (i, row) in a.iter().enumerate() {
                if row[j] != 0.0 || i == j {
                    row_idx.push(i);
                    values.push(row[j]);
                }
            }
            col_ptr.push(row_idx.len());
        }
        let pattern = Pattern {
            n,
            col_ptr,
            row_idx,
            symmetric: false,
        };
        (pattern, values)
    }

    /// Factorize and solve A x = b with GMRES from `krylov_min` unknowns: x and the GMRES
    /// iterations.
    fn solve(krylov_min: usize, a: &[Vec<f64>], b: &[f64]) -> Result<(Vec<f64>, usize)> {
        let (pattern, values) = from_dense(a);
        let mut s = FaerSolver::new(SolverSettings {
            krylov_min,
            ..Default::default()
        });
        s.factorize(&pattern, &values, false, &|e| format!("equation {e}"))?;
        let mut x = b.to_vec();
        s.solve_in_place(&mut x)?;
        Ok((x, s.stats.krylov_iterations))
    }

    /// GMRES forced on `a` gives the sparse LU's solution to 1e-10 in 1 to 15 iterations.
    fn assert_krylov_matches_lu(a: &[Vec<f64>], b: &[f64]) {
        let (lu, none) = solve(usize::MAX, a, b).unwrap();
        let (gm, its) = solve(0, a, b).unwrap();
        let scale = lu.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let diff = lu
            .iter()
            .zip(&gm)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert_eq!(none, 0);
        assert!(diff < 1e-10 * scale, "difference {diff:e}");
        assert!((1..=15).contains(&its), "{its} GMRES iterations");
    }

    /// A 5-point Laplacian on an m × m grid plus a first-difference term of weight `skew` in x
    /// (convection: not symmetric).
    fn convection_diffusion(m: usize, skew: f64) -> Vec<Vec<f64>> {
        let n = m * m;
        let mut a = vec![vec![0.0; n]; n];
        for j in 0..n {
            let (jx, jy) = (j % m, j / m);
            a[j][j] = 4.0;
            for (dx, dy) in [(-1i64, 0i64), (1, 0), (0, -1), (0, 1)] {
                let (ix, iy) = (jx as i64 + dx, jy as i64 + dy);
                if (0..m as i64).contains(&ix) && (0..m as i64).contains(&iy) {
                    // Entry (i, j): −1 − skew·dx, so that (j, i) is −1 + skew·dx.
                    a[(iy as usize) * m + ix as usize][j] = -1.0 - skew * dx as f64;
                }
            }
        }
        a
    }

    /// GMRES with the symmetric part (forced on a small matrix) gives the sparse LU's solution.
    #[test]
    fn krylov_and_lu_agree_on_a_non_symmetric_matrix() {
        let a = convection_diffusion(20, 0.1);
        let b: Vec<f64> = (0..a.len()).map(|i| (0.37 * i as f64).cos()).collect();
        assert_krylov_matches_lu(&a, &b);
    }

    /// A chain of 30 springs and three tie constraints as multipliers whose rows and columns
    /// differ by 5 % (as a contact tangent's do): the saddle point [K Cᵀ; G 0]. Without the
    /// support, the chain's translation is free (K 1 = 0, G 1 = C 1 = 0): singular.
    fn saddle(supported: bool) -> Vec<Vec<f64>> {
        let (n, m) = (30, 3);
        let mut a = vec![vec![0.0; n + m]; n + m];
        for i in 0..n - 1 {
            a[i][i] += 1.0;
            a[i + 1][i + 1] += 1.0;
            a[i][i + 1] -= 1.0;
            a[i + 1][i] -= 1.0;
        }
        if supported {
            a[0][0] += 1.0;
        }
        for (k, (p, q)) in [(5, 17), (9, 25), (12, 29)].into_iter().enumerate() {
            let r = n + k;
            (a[r][p], a[r][q]) = (1.0, -1.0);
            (a[p][r], a[q][r]) = (1.05, -1.05);
        }
        a
    }

    /// GMRES preconditioned by the regularized LDLᵀ of the symmetric part of a saddle point
    /// (multipliers) gives the LU's solution to 1e-10; with the bodies' stiffness singular (no
    /// support: the ties do not hold the chain) the system is reported singular.
    #[test]
    fn saddle_points_by_krylov_match_lu_and_mechanisms_are_singular() {
        let b: Vec<f64> = (0..33).map(|i| (0.7 * i as f64).sin()).collect();
        assert_krylov_matches_lu(&saddle(true), &b);
        let r = solve(0, &saddle(false), &b);
        assert!(matches!(r, Err(Error::Singular(_))), "{:?}", r.map(|x| x.1));
    }
}

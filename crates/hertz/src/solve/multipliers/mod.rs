//! Newton systems with Lagrange multipliers solved for the displacements alone: each contact
//! point's multipliers are eliminated through its slave node's equilibrium rows.
//!
//! A multiplier that acts on its slave node alone among the slave nodes — node-to-node and
//! node-to-segment multipliers, and mortar multipliers weighted with the dual basis, whose force
//! on slave node j is D_j times its own multiplier (∫ Φ_j N_k = δ_jk D_j) — enters the tangent
//! as
//!   rows S (the slave node's free equations):  K_S x + C λ = b_S,   C = Q [R; 0] (QR, r × p),
//!   other rows i:                              K_i x + T_iλ λ = b_i,
//!   its constraint rows:                       G x + d λ = b_L,
//! so that λ = R⁻¹ Q₁ᵀ (b_S − K_S x) = E (b_S − K_S x). Three ways follow
//! ([`MultiplierElimination::solve`] takes the first that applies, [`Method`]):
//! - a symmetric tangent, G = Cᵀ up to a row's scale and d = 0 (module `symmetric`): the slave
//!   unknowns are substituted by the motion that keeps the constraints, and the equations taken
//!   along it, a symmetric system for a sparse Cholesky;
//! - a general tangent near its symmetric counterpart (the same with the displacements' block
//!   symmetrized, each gap row its force column and the compliant multipliers condensed:
//!   large deformation, friction, a penalty in multiplier form; module `counterpart`): GMRES
//!   on the whole tangent, preconditioned with the counterpart's symmetric elimination, a
//!   friction force's components first rotated into the normal and tangent directions;
//! - a general tangent otherwise:
//!   (K_i − T_iλ E K_S) x = b_i − T_iλ E b_S   (the constraint rows among them),
//!   Q₂ᵀ K_S x = Q₂ᵀ b_S                      (the slave node's rows with no multiplier),
//!   a square system in the displacements with the fill of the slave rows in the master and
//!   constraint rows, for a sparse LU.
//!
//! Mortar on quadratic faces weighs with a dual basis biorthogonal to modified shape functions
//! N̂ = T N, whose multiplier also pushes the corners beside its mid-side node: the slave rows
//! are first combined by T and the unknowns changed to match (`Transform`: P A Pᵀ y = P b,
//! x = Pᵀ y), after which each multiplier acts on its own node's rows alone.
//!
//! The elimination is exact (the GMRES way to 1e-12 of the right-hand side): a multiplier is
//! eliminated only where the slave rows of the other eliminated points carry none of it (up to
//! round-off, 1e-12 of its own coupling) and C has full column rank; the others stay unknowns
//! of the reduced system.

mod counterpart;
mod rows;
mod symmetric;

use super::linear::{FaerSolver, LinearSolver, SolverSettings};
use crate::assembly::Pattern;
use crate::error::{Error, Result};
use crate::solve::krylov::gmres;
use crate::solve::linear::faer_direct::KRYLOV_TOL;
use counterpart::{friction_rotation, Counterpart};
use rows::{RowBuilder, Rows};
use symmetric::Reduction;

/// One contact point's multipliers and its slave node's free equations.
#[derive(Debug, Clone)]
pub struct Group {
    pub slave: Vec<usize>,
    pub lambdas: Vec<usize>,
}

/// The relative residual of an iterative solver's reduced solves as the preconditioner inside
/// GMRES (direct solvers are exact): GMRES then needs a few more iterations, the solves far
/// fewer.
const INNER_TOL: f64 = 1e-4;

/// Entries of other slave rows in an eliminated multiplier's column below this fraction of its
/// own coupling are round-off of the dual basis' biorthogonality and are dropped.
const COUPLING_TOL: f64 = 1e-12;

/// How a solve reduced the system.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Method {
    /// A symmetric tangent into a symmetric system (Cholesky).
    #[default]
    Symmetric,
    /// A general tangent by GMRES, preconditioned with its symmetric counterpart's.
    Preconditioned,
    /// A general tangent into a general system (sparse LU).
    General,
}

impl Method {
    /// How the method reads in a report.
    pub fn name(self) -> &'static str {
        match self {
            Method::Symmetric => "symmetric",
            Method::Preconditioned => "GMRES on the symmetric counterpart's",
            Method::General => "general",
        }
    }
}

/// The reduced system's solver, kept while its pattern stays the same.
pub struct MultiplierElimination {
    /// The reduced systems' solver. Where it needs positive definite matrices
    /// ([`super::linear::Capabilities::needs_definite`]: CG with an algebraic multigrid), a
    /// symmetric reduced system that keeps no multiplier is given it as positive definite,
    /// with `modes` carried into the reduced unknowns as its near-null space; a solver that
    /// does not tries Cholesky and falls back to an LDLᵀ by itself.
    solver: Box<dyn LinearSolver>,
    /// The model's rigid-body motions over the full system's unknowns (exact in the reduced
    /// unknowns but after a slave transform, whose change of the quadratic faces' unknowns they
    /// do not follow: a near-null space need not be exact).
    modes: Vec<Vec<f64>>,
    pattern: Option<Pattern>,
    /// Multipliers eliminated and kept in the last solve.
    pub eliminated: usize,
    pub kept: usize,
    /// How the last solve reduced the system.
    pub method: Method,
    /// GMRES iterations of the last solve (a general tangent preconditioned by the symmetric
    /// elimination of its symmetric counterpart), 0 for a direct solve.
    krylov_iterations: usize,
}

/// A change of basis of the displacement unknowns, x = Pᵀ y, with the equations combined by
/// the same P: (P T Pᵀ) y = P b, symmetric where T is. P is the identity but for the rows
/// listed (a slave corner's row plus α times its mid-sides' rows, a mid-side's scaled: see
/// `Formulation::slave_transform`), so that a multiplier biorthogonal to a modified basis acts
/// on its own slave node alone and is eliminated through its rows.
struct Transform {
    /// Per equation: its row of P, None for the identity's.
    rows: Vec<Option<Vec<(usize, f64)>>>,
    /// Per equation l: the (k, P_kl) of every row k reaching it (Pᵀ's row l).
    cols: Vec<Vec<(usize, f64)>>,
}

impl Transform {
    fn new(n: usize, entries: &[(usize, usize, f64)]) -> Transform {
        let mut rows: Vec<Option<Vec<(usize, f64)>>> = vec![None; n];
        for &(k, l, w) in entries {
            rows[k].get_or_insert_with(Vec::new).push((l, w));
        }
        let mut cols: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
        for (k, row) in rows.iter().enumerate() {
            match row {
                Some(r) => r.iter().for_each(|&(l, w)| cols[l].push((k, w))),
                None => cols[k].push((k, 1.0)),
            }
        }
        Transform { rows, cols }
    }

    /// P b.
    fn apply(&self, b: &[f64]) -> Vec<f64> {
        (0..b.len())
            .map(|k| match &self.rows[k] {
                Some(r) => r.iter().map(|&(l, w)| w * b[l]).sum(),
                None => b[k],
            })
            .collect()
    }

    /// Pᵀ y.
    fn back(&self, y: &[f64]) -> Vec<f64> {
        self.cols
            .iter()
            .map(|c| c.iter().map(|&(k, w)| w * y[k]).sum())
            .collect()
    }
}

/// An eliminated group: its rows, multipliers, Q (r × r, row-major) and E = R⁻¹Q₁ᵀ (p × r).
struct Eliminated {
    slave: Vec<usize>,
    lambdas: Vec<usize>,
    q: Vec<f64>,
    e: Vec<f64>,
}

/// Householder QR of the r × p matrix `c` (row-major), r ≥ p: Q (r × r, row-major) and R
/// (p × p, row-major, upper).
fn qr(c: &[f64], r: usize, p: usize) -> (Vec<f64>, Vec<f64>) {
    let mut a = c.to_vec();
    let mut q = vec![0.0; r * r];
    for i in 0..r {
        q[i * r + i] = 1.0;
    }
    for k in 0..p {
        let norm = (k..r).map(|i| a[i * p + k].powi(2)).sum::<f64>().sqrt();
        if norm == 0.0 {
            continue;
        }
        let alpha = if a[k * p + k] > 0.0 { -norm } else { norm };
        let mut v: Vec<f64> = (0..r)
            .map(|i| if i < k { 0.0 } else { a[i * p + k] })
            .collect();
        v[k] -= alpha;
        let vv: f64 = v.iter().map(|x| x * x).sum();
        if vv == 0.0 {
            continue;
        }
        // A ← (I − 2vvᵀ/vᵀv) A, Q ← Q (I − 2vvᵀ/vᵀv).
        for j in 0..p {
            let s: f64 = (0..r).map(|i| v[i] * a[i * p + j]).sum::<f64>() * 2.0 / vv;
            for i in 0..r {
                a[i * p + j] -= s * v[i];
            }
        }
        for i in 0..r {
            let s: f64 = (0..r).map(|l| q[i * r + l] * v[l]).sum::<f64>() * 2.0 / vv;
            for l in 0..r {
                q[i * r + l] -= s * v[l];
            }
        }
    }
    let rm = (0..p * p)
        .map(|ij| {
            let (i, j) = (ij / p, ij % p);
            if j >= i {
                a[i * p + j]
            } else {
                0.0
            }
        })
        .collect();
    (q, rm)
}

impl MultiplierElimination {
    /// Reduced systems of `krylov_min` unknowns and more are solved by GMRES (see
    /// [`FaerSolver`]).
    pub fn new(krylov_min: usize) -> MultiplierElimination {
        let solver = FaerSolver::new(SolverSettings {
            krylov_min,
            ..Default::default()
        });
        MultiplierElimination::with_solver(Box::new(solver), Vec::new())
    }

    /// The reduced systems solved by `solver`, with the model's rigid-body `modes` (see the
    /// fields).
    pub fn with_solver(
        solver: Box<dyn LinearSolver>,
        modes: Vec<Vec<f64>>,
    ) -> MultiplierElimination {
        MultiplierElimination {
            solver,
            modes,
            pattern: None,
            eliminated: 0,
            kept: 0,
            method: Method::default(),
            krylov_iterations: 0,
        }
    }

    /// Whether the reduced systems' solver needs positive definite matrices.
    fn needs_definite(&self) -> bool {
        self.solver.capabilities().needs_definite
    }

    /// The reduced system's last factorization and solve.
    pub fn stats(&self) -> super::linear::SolverStats {
        super::linear::SolverStats {
            krylov_iterations: self.krylov_iterations,
            ..self.solver.stats().clone()
        }
    }

    /// Record how many multipliers the last solve eliminated and kept.
    fn count(&mut self, eliminated: &[Eliminated], decoupled: &[usize], groups: &[Group]) {
        self.eliminated = eliminated.iter().map(|e| e.lambdas.len()).sum::<usize>()
            + decoupled
                .iter()
                .map(|&g| groups[g].lambdas.len())
                .sum::<usize>();
        self.kept = groups.iter().map(|g| g.lambdas.len()).sum::<usize>() - self.eliminated;
    }

    /// Solve T x = `rhs` in place (T: `values` on `pattern`, displacements and multipliers),
    /// eliminating the multipliers of `groups` where that is exact (see the module doc).
    /// A symmetric T, and a general one that GMRES solves on its symmetric counterpart's
    /// elimination, are always solved; any other only with `general` (else false is returned
    /// and `rhs` is untouched: the caller solves T itself). `transform` (equations k, l and
    /// P_kl, [`Transform`]) combines the slave rows first where the multipliers' forces are
    /// diagonal only in combined rows (mortar on quadratic faces).
    #[allow(clippy::too_many_arguments)]
    pub fn solve(
        &mut self,
        pattern: &Pattern,
        values: &[f64],
        rhs: &mut [f64],
        groups: &[Group],
        general: bool,
        transform: &[(usize, usize, f64)],
        describe: &dyn Fn(usize) -> String,
    ) -> Result<bool> {
        let n = rhs.len();
        let mut rows = Rows::new(pattern, values);
        let mut b = rhs.to_vec();
        let slave = (!transform.is_empty()).then(|| Transform::new(n, transform));
        if let Some(t) = &slave {
            rows = rows.transformed(t);
            b = t.apply(&b);
        }
        let rotation = friction_rotation(&rows, groups);
        let rotated = (!rotation.is_empty()).then(|| Transform::new(n, &rotation));
        if let Some(t) = &rotated {
            rows = rows.transformed(t);
            b = t.apply(&b);
        }
        if !self.solve_rows(rows, &mut b, groups, general, describe)? {
            return Ok(false);
        }
        for t in [&rotated, &slave].into_iter().flatten() {
            b = t.back(&b);
        }
        rhs.copy_from_slice(&b);
        Ok(true)
    }

    /// [`MultiplierElimination::solve`] on the tangent by rows.
    fn solve_rows(
        &mut self,
        rows: Rows,
        rhs: &mut [f64],
        groups: &[Group],
        general: bool,
        describe: &dyn Fn(usize) -> String,
    ) -> Result<bool> {
        let multipliers: Vec<usize> = groups.iter().flat_map(|g| g.lambdas.clone()).collect();
        self.method = Method::General;
        self.krylov_iterations = 0;
        if let Some((scale, out)) = rows.multiplier_scales(&multipliers) {
            if rows.is_symmetric_with(&scale, &out) {
                let scaled_rhs: Vec<f64> = rhs.iter().zip(&scale).map(|(b, s)| b / s).collect();
                let red = Reduction::new(rows.scaled(&scale), groups);
                if general || red.kept_multipliers == 0 {
                    let (reduced, vals) = red.reduced_matrix();
                    self.factorize_reduced(
                        reduced,
                        &vals,
                        &|k| red.unknown(k),
                        Some(&red),
                        describe,
                    )?;
                    let x = red.apply(self.solver.as_mut(), &scaled_rhs, groups, describe)?;
                    rhs.copy_from_slice(&x);
                    let (eliminated, decoupled) = red.counts();
                    self.count(eliminated, decoupled, groups);
                    self.method = Method::Symmetric;
                    return Ok(true);
                }
            }
        }
        if let Some(x) = self.preconditioned(&rows, rhs, groups, !general, describe)? {
            rhs.copy_from_slice(&x);
            return Ok(true);
        }
        if !general {
            self.count(&[], &[], &[]);
            return Ok(false);
        }
        match self.solve_general(&rows, rhs, groups, describe) {
            // A solver that needs definite matrices may fail where faer's LU pivots through:
            // MUMPS' LU met a zero pivot on the general elimination of a 3D block sliding with
            // friction.
            // The condensed counterpart takes over (not first: it chatters on steps the general
            // elimination solves).
            Err(Error::Singular(why)) if self.needs_definite() => {
                // The failed solver is set up afresh.
                self.pattern = None;
                match self.preconditioned(&rows, rhs, groups, true, describe)? {
                    Some(x) => {
                        rhs.copy_from_slice(&x);
                        Ok(true)
                    }
                    None => Err(Error::Singular(why)),
                }
            }
            solved => solved.map(|()| true),
        }
    }

    /// Factorize the reduced matrix `reduced` (`values`), its symbolic analysis kept while the
    /// pattern stays the same; `unknown`: the full system's unknown at a reduced place.
    /// `symmetric`: the symmetric elimination it comes from, positive definite if it keeps no
    /// multiplier (for a solver told so, with the near-null space carried into its unknowns);
    /// else the general one, whose kept multipliers `self.kept` counts.
    fn factorize_reduced(
        &mut self,
        reduced: Pattern,
        values: &[f64],
        unknown: &dyn Fn(usize) -> usize,
        symmetric: Option<&Reduction>,
        describe: &dyn Fn(usize) -> String,
    ) -> Result<()> {
        if self
            .pattern
            .as_ref()
            .is_none_or(|p| p.col_ptr != reduced.col_ptr || p.row_idx != reduced.row_idx)
        {
            self.solver.reset();
            self.pattern = Some(reduced);
            self.solver
                .set_multipliers(symmetric.map_or(self.kept, |r| r.kept_multipliers));
            if let (Some(red), false) = (symmetric, self.modes.is_empty()) {
                let modes: Vec<Vec<f64>> = self.modes.iter().map(|m| red.restrict(m)).collect();
                self.solver.set_near_null_space(&modes);
            }
        }
        let reduced = self.pattern.as_ref().expect("set above");
        let spd = self.needs_definite() && symmetric.is_some_and(|r| r.kept_multipliers == 0);
        self.solver
            .factorize(reduced, values, spd, &|k| describe(unknown(k)))
    }

    /// A general matrix solved by GMRES preconditioned with the symmetric elimination of its
    /// symmetric counterpart ([`Counterpart`]): a Cholesky of the reduced system instead of a
    /// sparse LU of the general one. Exact but for terms of the linearization where every
    /// multiplier is hard (large deformation: the normals' and the dual basis' variations; a
    /// few GMRES iterations); with compliant multipliers condensed (friction, a penalty in
    /// multiplier form) only with `condense`, as GMRES then takes tens of iterations where
    /// nodes slide (below the Krylov threshold the general elimination's LU is cheaper, and
    /// exact). None where the counterpart keeps multipliers or GMRES does not converge.
    fn preconditioned(
        &mut self,
        rows: &Rows,
        rhs: &[f64],
        groups: &[Group],
        condense: bool,
        describe: &dyn Fn(usize) -> String,
    ) -> Result<Option<Vec<f64>>> {
        let Some((counterpart, cp)) = Counterpart::new(rows, groups, condense) else {
            return Ok(None);
        };
        let red = Reduction::new(counterpart, &cp.groups);
        if red.kept_multipliers > 0 {
            return Ok(None);
        }
        let (reduced, vals) = red.reduced_matrix();
        if self
            .factorize_reduced(reduced, &vals, &|k| red.unknown(k), Some(&red), describe)
            .is_err()
        {
            return Ok(None);
        }
        // Flexible GMRES: the reduced solve, if iterative, need not be exact.
        let solver = self.solver.as_mut();
        solver.set_relative_tolerance(Some(INNER_TOL));
        let mut failed = None;
        let solved = gmres(
            rhs,
            &mut |x, y| rows.matvec(x, y),
            &mut |v| {
                match red.apply(solver, &cp.rhs(v), &cp.groups, describe) {
                    Ok(x) => v.copy_from_slice(&x),
                    Err(e) => failed = Some(e),
                }
                Ok(())
            },
            KRYLOV_TOL,
            50,
            200,
        );
        solver.set_relative_tolerance(None);
        let solved = solved?;
        match failed {
            // A solver that needs positive definite matrices takes the reduced system as one
            // (CG and a multigrid); in large deformation it need not be (CG stopped on an
            // indefinite matrix at the 2D ironing example's hardest step): the caller's general
            // elimination or whole tangent (MUMPS' LU) takes over.
            Some(Error::Solve(_) | Error::Singular(_)) if self.needs_definite() => {
                // The failed solver is set up afresh.
                self.pattern = None;
                return Ok(None);
            }
            Some(e) => return Err(e),
            None => {}
        }
        Ok(solved.map(|(x, iterations)| {
            self.krylov_iterations = iterations;
            self.method = Method::Preconditioned;
            let (eliminated, decoupled) = red.counts();
            self.count(eliminated, decoupled, &cp.groups);
            x
        }))
    }

    /// The general elimination (see the module doc): constraint rows in the places of the
    /// slave rows, for a sparse LU.
    fn solve_general(
        &mut self,
        rows: &Rows,
        rhs: &mut [f64],
        groups: &[Group],
        describe: &dyn Fn(usize) -> String,
    ) -> Result<()> {
        let n = rhs.len();
        let (eliminated, decoupled) = eliminable(rows, n, groups, false);
        let layout = Layout::new(n, &eliminated, &decoupled, groups);
        let (reduced_rows, mut b) = layout.reduced_rows(rows, rhs, &eliminated);
        let (reduced, vals) = reduced_rows.into_pattern();
        self.count(&eliminated, &decoupled, groups);
        let kept = &layout.kept;
        self.factorize_reduced(reduced, &vals, &|k| kept[k], None, describe)?;
        self.solver.solve_in_place(&mut b)?;
        // x, then each group's multipliers λ = E (b_S − K_S x).
        let mut x = vec![0.0; n];
        for (k, &i) in kept.iter().enumerate() {
            x[i] = b[k];
        }
        let solved = Solved {
            rows,
            gone: &layout.gone,
            rhs,
        };
        solved.eliminated_multipliers(&eliminated, &mut x);
        solved.decoupled_multipliers(&decoupled, groups, &mut x, describe)?;
        rhs.copy_from_slice(&x);
        Ok(())
    }
}

/// Where the unknowns and rows of the general elimination go.
struct Layout {
    /// The unknowns that leave the system: eliminated and decoupled multipliers.
    gone: Vec<bool>,
    /// Rows not carried over as they are: the eliminated groups' slave rows and the decoupled
    /// groups' own rows.
    replaced: Vec<bool>,
    /// Eliminated multiplier l is multiplier a of group g: place[l] = (g, a).
    place: Vec<(usize, usize)>,
    /// The unknowns kept, and each one's place in the reduced system.
    kept: Vec<usize>,
    pos: Vec<usize>,
    /// Row i of T goes to reduced row `target[i]`; the slave rows' places are taken by their
    /// group's constraint rows (the first p) and Q₂ᵀ rows (the rest).
    target: Vec<usize>,
}

impl Layout {
    fn new(n: usize, eliminated: &[Eliminated], decoupled: &[usize], groups: &[Group]) -> Layout {
        let mut gone = vec![false; n];
        let mut replaced = vec![false; n];
        let mut place = vec![(usize::MAX, 0); n];
        for (g, el) in eliminated.iter().enumerate() {
            for (a, &l) in el.lambdas.iter().enumerate() {
                gone[l] = true;
                place[l] = (g, a);
            }
            for &s in &el.slave {
                replaced[s] = true;
            }
        }
        // A decoupled group's rows and columns leave the system; its multipliers are solved
        // from its own rows afterwards.
        for &g in decoupled {
            for &l in &groups[g].lambdas {
                gone[l] = true;
                replaced[l] = true;
            }
        }
        let kept: Vec<usize> = (0..n).filter(|&i| !gone[i]).collect();
        let mut pos = vec![usize::MAX; n];
        for (k, &i) in kept.iter().enumerate() {
            pos[i] = k;
        }
        let mut target = pos.clone();
        for el in eliminated {
            for (a, &l) in el.lambdas.iter().enumerate() {
                target[l] = pos[el.slave[a]];
            }
        }
        Layout {
            gone,
            replaced,
            place,
            kept,
            pos,
            target,
        }
    }

    /// The reduced rows and right-hand side: row i minus Σ_g T_iλ E_g (K_S, b_S) of the groups
    /// whose multipliers it holds, and each eliminated group's slave rows with no multiplier,
    /// Q₂ᵀ K_S x = Q₂ᵀ b_S.
    fn reduced_rows(
        &self,
        rows: &Rows,
        rhs: &[f64],
        eliminated: &[Eliminated],
    ) -> (RowBuilder, Vec<f64>) {
        let (gone, pos) = (&self.gone, &self.pos);
        let mut reduced_rows = RowBuilder::new(self.kept.len());
        let mut b = vec![0.0; self.kept.len()];
        // Reduced row t += w × (row s of T on the kept unknowns, b_s); each reduced row is built
        // in one go and then closed.
        let mut add_row = |out: &mut RowBuilder, t: usize, s: usize, w: f64| {
            b[t] += w * rhs[s];
            for (c, v) in rows.row(s) {
                if !gone[c] {
                    out.add(pos[c], w * v);
                }
            }
        };
        for i in 0..rhs.len() {
            if self.replaced[i] {
                continue;
            }
            let t = self.target[i];
            add_row(&mut reduced_rows, t, i, 1.0);
            let mut z: Vec<(usize, Vec<f64>)> = Vec::new();
            for (c, v) in rows.row(i) {
                if !gone[c] {
                    continue;
                }
                let (g, a) = self.place[c];
                if g == usize::MAX {
                    // A decoupled multiplier: zero outside its own rows.
                    continue;
                }
                let el = &eliminated[g];
                let r = el.slave.len();
                let at = match z.iter().position(|e| e.0 == g) {
                    Some(at) => at,
                    None => {
                        z.push((g, vec![0.0; r]));
                        z.len() - 1
                    }
                };
                for (s, zs) in z[at].1.iter_mut().enumerate() {
                    *zs += v * el.e[a * r + s];
                }
            }
            for (g, zg) in z {
                let el = &eliminated[g];
                for (&s, &zs) in el.slave.iter().zip(&zg) {
                    add_row(&mut reduced_rows, t, s, -zs);
                }
            }
            reduced_rows.close(t);
        }
        for el in eliminated {
            let (r, p) = (el.slave.len(), el.lambdas.len());
            for col in p..r {
                let t = pos[el.slave[col]];
                for (a, &s) in el.slave.iter().enumerate() {
                    add_row(&mut reduced_rows, t, s, el.q[a * r + col]);
                }
                reduced_rows.close(t);
            }
        }
        (reduced_rows, b)
    }
}

/// The reduced system's solution and what recovers the multipliers from it.
struct Solved<'a> {
    rows: &'a Rows,
    /// Unknowns that left the reduced system.
    gone: &'a [bool],
    rhs: &'a [f64],
}

impl Solved<'_> {
    /// Each eliminated group's multipliers λ = E (b_S − K_S x), x the kept unknowns.
    fn eliminated_multipliers(&self, eliminated: &[Eliminated], x: &mut [f64]) {
        for el in eliminated {
            let r = el.slave.len();
            let res: Vec<f64> = el
                .slave
                .iter()
                .map(|&s| {
                    self.rhs[s]
                        - self
                            .rows
                            .row(s)
                            .filter(|(c, _)| !self.gone[*c])
                            .map(|(c, v)| v * x[c])
                            .sum::<f64>()
                })
                .collect();
            for (a, &l) in el.lambdas.iter().enumerate() {
                x[l] = (0..r).map(|s| el.e[a * r + s] * res[s]).sum();
            }
        }
    }

    /// Each decoupled group's multipliers from its own rows: T_LL λ = b_L − T_LK x.
    fn decoupled_multipliers(
        &self,
        decoupled: &[usize],
        groups: &[Group],
        x: &mut [f64],
        describe: &dyn Fn(usize) -> String,
    ) -> Result<()> {
        for &g in decoupled {
            let l = &groups[g].lambdas;
            let p = l.len();
            let mut a = vec![0.0; p * p];
            let mut f: Vec<f64> = l.iter().map(|&i| self.rhs[i]).collect();
            for (ai, &i) in l.iter().enumerate() {
                for (c, v) in self.rows.row(i) {
                    match l.iter().position(|&x| x == c) {
                        Some(b) => a[ai * p + b] += v,
                        None if !self.gone[c] => f[ai] -= v * x[c],
                        None => {}
                    }
                }
            }
            let lambda = solve_small(&mut a, &mut f, p).ok_or_else(|| {
                crate::error::Error::Singular(format!(
                    "the tangent matrix is singular at {}",
                    describe(l[0])
                ))
            })?;
            for (&i, v) in l.iter().zip(lambda) {
                x[i] = v;
            }
        }
        Ok(())
    }
}

/// The groups whose multipliers can be eliminated exactly, with their QR, and those whose
/// multipliers touch no row but their own (an open point's λ = 0).
/// With `hard_only`, groups whose multipliers have a compliance (a diagonal entry: a penalty
/// solved in multiplier form, a sliver's fading constraint) are not eliminated.
fn eliminable(
    rows: &Rows,
    n: usize,
    groups: &[Group],
    hard_only: bool,
) -> (Vec<Eliminated>, Vec<usize>) {
    // A slave row claimed by two groups (a node slave of two conditions) serves neither.
    let mut owner = vec![usize::MAX; n];
    let mut shared = vec![false; groups.len()];
    for (g, gr) in groups.iter().enumerate() {
        for &s in &gr.slave {
            if owner[s] == usize::MAX {
                owner[s] = g;
            } else {
                shared[g] = true;
                shared[owner[s]] = true;
            }
        }
    }
    // Columns of the multipliers, by rows: T[i, l] for the slave rows i.
    let mut lambda_of = vec![usize::MAX; n];
    for (g, gr) in groups.iter().enumerate() {
        for &l in &gr.lambdas {
            lambda_of[l] = g;
        }
    }
    let mut coupling: Vec<Vec<f64>> = groups
        .iter()
        .map(|gr| vec![0.0; gr.slave.len() * gr.lambdas.len()])
        .collect();
    // Groups whose columns hold a nonzero outside their own rows.
    let mut touched = vec![false; groups.len()];
    for i in 0..n {
        for (c, v) in rows.row(i) {
            let g = lambda_of[c];
            if g != usize::MAX && v != 0.0 && !groups[g].lambdas.contains(&i) {
                touched[g] = true;
            }
        }
    }
    // Largest entry of each group's columns in other groups' slave rows.
    let mut stray = vec![0.0f64; groups.len()];
    for (s, &g_row) in owner.iter().enumerate() {
        if g_row == usize::MAX {
            continue;
        }
        for (c, v) in rows.row(s) {
            let g = lambda_of[c];
            if g == usize::MAX {
                continue;
            }
            if g == g_row {
                let gr = &groups[g];
                let a = gr.slave.iter().position(|&x| x == s).expect("own row");
                let b = gr
                    .lambdas
                    .iter()
                    .position(|&x| x == c)
                    .expect("own multiplier");
                coupling[g][a * gr.lambdas.len() + b] = v;
            } else {
                stray[g] = stray[g].max(v.abs());
            }
        }
    }
    let mut out = Vec::new();
    let mut decoupled = Vec::new();
    for (g, gr) in groups.iter().enumerate() {
        let (r, p) = (gr.slave.len(), gr.lambdas.len());
        if !touched[g] && p > 0 {
            decoupled.push(g);
            continue;
        }
        if shared[g] || p == 0 || p > r {
            continue;
        }
        if hard_only
            && gr
                .lambdas
                .iter()
                .any(|&l| rows.row(l).any(|(c, v)| c == l && v != 0.0))
        {
            continue;
        }
        let c = &coupling[g];
        let size = c.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if !(size > 0.0) || stray[g] > COUPLING_TOL * size {
            continue;
        }
        let (q, rm) = qr(c, r, p);
        if (0..p).any(|i| rm[i * p + i].abs() <= 1e-10 * size) {
            continue;
        }
        // E = R⁻¹ Q₁ᵀ by back substitution, column by column of Q₁ᵀ.
        let mut e = vec![0.0; p * r];
        for s in 0..r {
            for i in (0..p).rev() {
                let mut v = q[s * r + i];
                for k in i + 1..p {
                    v -= rm[i * p + k] * e[k * r + s];
                }
                e[i * r + s] = v / rm[i * p + i];
            }
        }
        out.push(Eliminated {
            slave: gr.slave.clone(),
            lambdas: gr.lambdas.clone(),
            q,
            e,
        });
    }
    (out, decoupled)
}

/// The solution of the dense p × p system `a` x = `f` (Gaussian elimination with partial
/// pivoting), None if singular.
fn solve_small(a: &mut [f64], f: &mut [f64], p: usize) -> Option<Vec<f64>> {
    for k in 0..p {
        let piv = (k..p).max_by(|&i, &j| a[i * p + k].abs().total_cmp(&a[j * p + k].abs()))?;
        if a[piv * p + k] == 0.0 {
            return None;
        }
        for j in 0..p {
            a.swap(k * p + j, piv * p + j);
        }
        f.swap(k, piv);
        for i in k + 1..p {
            let m = a[i * p + k] / a[k * p + k];
            for j in k..p {
                a[i * p + j] -= m * a[k * p + j];
            }
            f[i] -= m * f[k];
        }
    }
    let mut x = vec![0.0; p];
    for i in (0..p).rev() {
        let s: f64 = (i + 1..p).map(|j| a[i * p + j] * x[j]).sum();
        x[i] = (f[i] - s) / a[i * p + i];
    }
    Some(x)
}
#[cfg(test)]
mod tests {
    use super::*;

    /// A dense matrix's general pattern and values.
    fn dense(a: &[Vec<f64>]) -> (Pattern, Vec<f64>) {
        let mut rows = RowBuilder::new(a.len());
        for (i, row) in a.iter().enumerate() {
            for (j, &v) in row.iter().enumerate() {
                if v != 0.0 {
                    rows.add(j, v);
                }
            }
            rows.close(i);
        }
        rows.into_pattern()
    }

    /// The pattern holds every entry (duplicates summed, a row closed twice merged) and its
    /// transpose's places and the diagonal, with zeros.
    #[test]
    fn reduced_rows_become_a_structurally_symmetric_pattern() {
        let mut rows = RowBuilder::new(3);
        rows.add(2, 1.0);
        rows.add(0, 2.0);
        rows.add(2, 0.5);
        rows.close(0);
        rows.add(1, 4.0);
        rows.close(2);
        rows.add(1, -1.0);
        rows.close(2);
        let (p, v) = rows.into_pattern();
        let at = |r: usize, c: usize| v[p.position(r, c)];
        assert_eq!(
            (at(0, 0), at(0, 2), at(2, 1), at(2, 0)),
            (2.0, 1.5, 3.0, 0.0)
        );
        assert_eq!((at(1, 1), at(1, 2), at(2, 2)), (0.0, 0.0, 0.0));
        assert_eq!(p.nnz(), 7);
    }

    /// Solve `a` x = `rhs` with the multipliers of `groups` eliminated, assert that x is the full
    /// LU solve's to 1e-13, and return the (eliminated, kept) multipliers.
    fn against_full_solve(a: &[Vec<f64>], rhs: &[f64], groups: &[Group]) -> (usize, usize) {
        let el = solved_against_full_solve(a, rhs, groups, true, &[], 1e-13);
        (el.eliminated, el.kept)
    }

    /// Solve `a` x = `rhs` with the multipliers of `groups` eliminated (`general` and the slave
    /// rows' `transform` as in [`MultiplierElimination::solve`], which must take it), assert that
    /// x is the full LU solve's to `tol`, and return the elimination.
    fn solved_against_full_solve(
        a: &[Vec<f64>],
        rhs: &[f64],
        groups: &[Group],
        general: bool,
        transform: &[(usize, usize, f64)],
        tol: f64,
    ) -> MultiplierElimination {
        let (pattern, values) = dense(a);
        let mut full = FaerSolver::default();
        full.factorize(&pattern, &values, false, &|i| format!("{i}"))
            .unwrap();
        let mut want = rhs.to_vec();
        full.solve_in_place(&mut want).unwrap();
        let mut got = rhs.to_vec();
        let mut el = MultiplierElimination::new(crate::solve::linear::KRYLOV_MIN_UNKNOWNS);
        assert!(el
            .solve(
                &pattern,
                &values,
                &mut got,
                groups,
                general,
                transform,
                &|i| format!("{i}")
            )
            .unwrap());
        for (g, w) in got.iter().zip(&want) {
            assert!((g - w).abs() < tol, "{got:?} vs {want:?}");
        }
        el
    }

    #[test]
    fn qr_reproduces_the_matrix() {
        let c = [3.0, -1.0, 2.0, 0.5, -4.0, 1.5];
        let (q, r) = qr(&c, 3, 2);
        for i in 0..3 {
            for j in 0..2 {
                let v: f64 = (0..2).map(|k| q[i * 3 + k] * r[k * 2 + j]).sum();
                assert!((v - c[i * 2 + j]).abs() < 1e-14, "{v} vs {}", c[i * 2 + j]);
            }
            for k in 0..3 {
                let o: f64 = (0..3).map(|l| q[l * 3 + i] * q[l * 3 + k]).sum();
                assert!((o - f64::from(u8::from(i == k))).abs() < 1e-14);
            }
        }
    }

    /// A multiplier biorthogonal to a modified basis (mortar on a quadratic face): λ_m (5) acts
    /// on its mid-side node 1 with D/(1 − 2α) and on the corner 0 beside it with −α D/(1 − 2α),
    /// λ_c (4) on the corner alone; both also on a master node 3. Taken as they are, λ_m cannot
    /// be eliminated through node 1's row (the corner's row carries it too) and is kept; with
    /// the rows combined by T (corner row + α mid row, mid row × (1 − 2α)) both are, and the
    /// solution is the full solve's.
    #[test]
    fn a_slave_transform_lets_modified_basis_multipliers_be_eliminated() {
        let (alpha, d) = (0.2, 0.5);
        let (own, side) = (d / (1.0 - 2.0 * alpha), -alpha * d / (1.0 - 2.0 * alpha));
        let a = vec![
            vec![4.0, -1.0, 0.0, -0.5, 0.8, side],
            vec![-1.0, 3.0, -0.5, 0.0, 0.0, own],
            vec![0.0, -0.5, 2.0, 0.0, 0.0, 0.0],
            vec![-0.5, 0.0, 0.0, 3.0, -0.8, -d],
            vec![0.8, 0.0, 0.0, -0.8, 0.0, 0.0],
            vec![side, own, 0.0, -d, 0.0, 0.0],
        ];
        let rhs = [1.0, -0.3, 0.2, 0.25, 0.01, -0.02];
        let groups = [
            Group {
                slave: vec![0],
                lambdas: vec![4],
            },
            Group {
                slave: vec![1],
                lambdas: vec![5],
            },
        ];
        let plain = solved_against_full_solve(&a, &rhs, &groups, true, &[], 1e-13);
        assert_eq!((plain.eliminated, plain.kept), (1, 1));
        let t = [(0, 0, 1.0), (0, 1, alpha), (1, 1, 1.0 - 2.0 * alpha)];
        let el = solved_against_full_solve(&a, &rhs, &groups, true, &t, 1e-13);
        assert_eq!(
            (el.eliminated, el.kept, el.method),
            (2, 0, Method::Symmetric)
        );
    }

    /// Two floating 2D bodies of two nodes each (springs in x and y), slave node 1 (unknowns
    /// 2, 3) tied to master node 2 (4, 5) along n = (0.6, 0.8) by multiplier 8: a translation
    /// keeps the constraint, so its restriction to the reduced unknowns (the slave's free
    /// direction as Q's column) is a null vector of the reduced matrix, as it is of K.
    #[test]
    fn a_rigid_motion_restricted_to_the_reduced_unknowns_is_a_null_vector() {
        let mut a = vec![vec![0.0; 9]; 9];
        for (p, q, k) in [(0, 1, 1.0), (2, 3, 2.5)] {
            for d in 0..2 {
                let (i, j) = (2 * p + d, 2 * q + d);
                a[i][i] += k;
                a[j][j] += k;
                a[i][j] -= k;
                a[j][i] -= k;
            }
        }
        for (row, v) in [(2, 0.6), (3, 0.8), (4, -0.6), (5, -0.8)] {
            a[row][8] = v;
            a[8][row] = v;
        }
        let (pattern, values) = dense(&a);
        let groups = [Group {
            slave: vec![2, 3],
            lambdas: vec![8],
        }];
        let red = Reduction::new(Rows::new(&pattern, &values), &groups);
        assert_eq!(red.kept_multipliers, 0);
        let (reduced, vals) = red.reduced_matrix();
        // The slave's free direction is ±(−0.8, 0.6): y = ∓0.8 for x, ±0.6 for y.
        for (t, y) in [([1.0, 0.0], 0.8), ([0.0, 1.0], 0.6)] {
            let mut v: Vec<f64> = (0..8).map(|i| t[i % 2]).collect();
            v.push(0.0);
            let z = red.restrict(&v);
            assert_eq!(z.len(), 7);
            let mut kz = vec![0.0; z.len()];
            for c in 0..reduced.n {
                for k in reduced.col_ptr[c]..reduced.col_ptr[c + 1] {
                    let r = reduced.row_idx[k];
                    kz[r] += vals[k] * z[c];
                    if r != c {
                        kz[c] += vals[k] * z[r];
                    }
                }
            }
            let square: f64 = z.iter().map(|x| x * x).sum();
            assert!((square - 3.0 - y * y).abs() < 1e-14, "{z:?}");
            assert!(kz.iter().all(|x| x.abs() < 1e-14), "{kz:?}");
        }
    }

    /// Two springs in series, the middle node held against a wall by a multiplier acting on it
    /// alone (slave rows 1, 2; multiplier 4 ties u_1 + u_2 (a rotated direction) to 0.01), and a
    /// master node 3 the multiplier also loads: the reduced solve gives the full solve's x.
    #[test]
    fn elimination_matches_the_full_solve() {
        let a = vec![
            vec![4.0, -1.0, 0.0, 0.0, 0.0],
            vec![-1.0, 3.0, 0.5, -1.0, 0.6],
            vec![0.0, 0.5, 2.0, 0.0, 0.8],
            vec![0.0, -1.0, 0.0, 2.0, -1.0],
            vec![0.0, 0.6, 0.8, -1.0, 0.0],
        ];
        let rhs = [1.0, 0.0, -0.5, 0.25, 0.01];
        let groups = [Group {
            slave: vec![1, 2],
            lambdas: vec![4],
        }];
        assert_eq!(against_full_solve(&a, &rhs, &groups), (1, 0));
    }

    /// The same springs with a symmetric tangent whose gap row is its force column times 2
    /// (a nodal gap against a weighted force), a second slave node whose multiplier has a
    /// compliance (kept), and an open point's multiplier (its own row alone): the symmetric
    /// elimination gives the full solve's x, multipliers included.
    #[test]
    fn symmetric_elimination_matches_the_full_solve() {
        // Unknowns 0-3 and 5, 6 displacements (slave node 1, 2; slave node 5, 6), 4, 7 and 8
        // multipliers.
        let k = [
            [4.0, -1.0, 0.0, 0.0, 0.0, 0.0, 0.0],
            [-1.0, 3.0, 0.5, -1.0, 0.0, 0.2, 0.0],
            [0.0, 0.5, 2.0, 0.0, 0.0, 0.0, -0.3],
            [0.0, -1.0, 0.0, 2.0, -1.0, 0.0, 0.0],
            [0.0, 0.0, 0.0, -1.0, 3.0, -0.5, 0.0],
            [0.0, 0.2, 0.0, 0.0, -0.5, 2.5, 0.4],
            [0.0, 0.0, -0.3, 0.0, 0.0, 0.4, 1.5],
        ];
        let disp = [0, 1, 2, 3, 5, 6, 9];
        let mut a = vec![vec![0.0; 10]; 10];
        for (i, &di) in disp.iter().enumerate() {
            for (j, &dj) in disp.iter().enumerate() {
                a[di][dj] = k[i][j];
            }
        }
        // Multiplier 4 on slave rows 1, 2 and master row 3; its row is twice its column.
        for (row, v) in [(1, 0.6), (2, 0.8), (3, -1.0)] {
            a[row][4] = v;
            a[4][row] = 2.0 * v;
        }
        // Multiplier 7 on slave rows 5, 6 and master row 9, with a compliance.
        for (row, v) in [(5, 1.0), (6, 0.5), (9, -0.7)] {
            a[row][7] = v;
            a[7][row] = v;
        }
        a[7][7] = -0.05;
        // Multiplier 8 of an open point: λ = 0.3 from its own row.
        a[8][8] = 1.0;
        let rhs = [1.0, 0.0, -0.5, 0.25, 0.02, 0.1, -0.2, 0.01, 0.3, 0.4];
        let groups = [
            Group {
                slave: vec![1, 2],
                lambdas: vec![4],
            },
            Group {
                slave: vec![5, 6],
                lambdas: vec![7],
            },
            Group {
                slave: vec![],
                lambdas: vec![8],
            },
        ];
        assert_eq!(against_full_solve(&a, &rhs, &groups), (2, 1));
        // The same with the row's factor off by 1e-6: not symmetric, the general elimination
        // (which also eliminates the compliant multiplier).
        a[4][1] *= 1.000001;
        assert_eq!(against_full_solve(&a, &rhs, &groups), (3, 0));
    }

    /// A general tangent (the displacements' block not symmetric, the gap row twice the force
    /// column but for a term on the master row, as in large deformation) is solved by GMRES
    /// preconditioned with the symmetric elimination of its symmetric counterpart: the full
    /// solve's x, in a few iterations.
    #[test]
    fn a_general_tangent_is_solved_by_gmres_on_the_symmetric_elimination() {
        let mut a = vec![
            vec![4.0, -1.2, 0.0, 0.0, 0.0],
            vec![-0.8, 3.0, 0.5, -1.0, 0.6],
            vec![0.0, 0.4, 2.0, 0.1, 0.8],
            vec![0.0, -1.0, 0.0, 2.0, -1.0],
            vec![0.0, 1.2, 1.6, -2.3, 0.0],
        ];
        let rhs = [1.0, 0.0, -0.5, 0.25, 0.01];
        let groups = [Group {
            slave: vec![1, 2],
            lambdas: vec![4],
        }];
        // Without `general`: only the preconditioned path can take it.
        let el = solved_against_full_solve(&a, &rhs, &groups, false, &[], 1e-12);
        let iterations = el.stats().krylov_iterations;
        assert!((1..=5).contains(&iterations), "{iterations}");
        assert_eq!(
            (el.eliminated, el.kept, el.method),
            (1, 0, Method::Preconditioned)
        );
        // A gap row far from its column (its slave entries swapped): still the full solve
        // (GMRES, or the general elimination if it fails).
        a[4][1] = 1.6;
        a[4][2] = 1.2;
        against_full_solve(&a, &rhs, &groups);
    }

    /// Two 3D slave nodes with Coulomb friction (multipliers λ_T in Cartesian components, then
    /// λ_N; c_T = 10), each against a master node, springs between and to the ground: node A
    /// sticks (rows n nᵀ λ_T / c_T − P (x_s − x_m)), node B slides along ŝ at ρ = μλ/|v| = 0.4
    /// (rows ((I − ρ p pᵀ) λ_T − μ ŝ λ_N) / c_T − ρ p pᵀ (x_s − x_m), p = n × ŝ): the tangent,
    /// a right-hand side and the groups.
    fn friction_pair() -> (Vec<Vec<f64>>, Vec<f64>, [Group; 2]) {
        let n = 20;
        let mut a = vec![vec![0.0; n]; n];
        // Pair A: master 0..3, slave 3..6, λ_T 12..15, λ_N 15; pair B: 6..9, 9..12, 16..19, 19.
        for (m, s) in [(0, 3), (6, 9)] {
            for d in 0..3 {
                let (i, j) = (m + d, s + d);
                a[i][i] += 3.0 + 0.5 * d as f64;
                a[j][j] += 2.0 + 0.3 * d as f64;
                a[i][j] -= 1.0;
                a[j][i] -= 1.0;
            }
            a[s][s + 1] += 0.4;
            a[s + 1][s] += 0.4;
        }
        let c = 10.0;
        let normals = [[0.36, 0.48, 0.8], [0.0, 0.6, 0.8]];
        let (slide, across, rho, mu) = ([1.0, 0.0, 0.0], [0.0, 0.8, -0.6], 0.4, 0.3);
        for (k, ((m, s), lt)) in [(0, 3), (6, 9)].into_iter().zip([12, 16]).enumerate() {
            let (nv, ln) = (normals[k], lt + 3);
            for d in 0..3 {
                // Forces: λ_T,d along axis d, λ_N along −n on the slave (+n on the master).
                a[s + d][lt + d] = 1.0;
                a[m + d][lt + d] = -1.0;
                a[s + d][ln] = -nv[d];
                a[m + d][ln] = nv[d];
                a[ln][s + d] = -nv[d];
                a[ln][m + d] = nv[d];
            }
            for i in 0..3 {
                for j in 0..3 {
                    let (block, tie) = if k == 0 {
                        let p = f64::from(u8::from(i == j)) - nv[i] * nv[j];
                        (nv[i] * nv[j] / c, p)
                    } else {
                        let pp = rho * across[i] * across[j];
                        (f64::from(u8::from(i == j)) / c - pp / c, pp)
                    };
                    a[lt + i][lt + j] = block;
                    a[lt + i][s + j] = -tie;
                    a[lt + i][m + j] = tie;
                }
                if k == 1 {
                    a[lt + i][ln] = -mu * slide[i] / c;
                }
            }
        }
        let rhs: Vec<f64> = (0..n).map(|i| ((i * 7 % 11) as f64 - 5.0) * 0.1).collect();
        let groups = [
            Group {
                slave: vec![3, 4, 5],
                lambdas: vec![12, 13, 14, 15],
            },
            Group {
                slave: vec![9, 10, 11],
                lambdas: vec![16, 17, 18, 19],
            },
        ];
        (a, rhs, groups)
    }

    /// [`friction_pair`] without `general`: GMRES on the counterpart (the forces rotated into
    /// (t₁, t₂, n), A's tangential ones hard, B's condensed) gives the full solve's x in a few
    /// iterations, every multiplier out of the reduced system; with it, the general
    /// elimination's LU does, keeping the friction multipliers.
    #[test]
    fn friction_multipliers_are_solved_on_the_rotated_counterpart() {
        let (a, rhs, groups) = friction_pair();
        let el = solved_against_full_solve(&a, &rhs, &groups, false, &[], 1e-12);
        let iterations = el.stats().krylov_iterations;
        assert!((1..=6).contains(&iterations), "{iterations}");
        assert_eq!(
            (el.eliminated, el.kept, el.method),
            (8, 0, Method::Preconditioned)
        );
        let el = solved_against_full_solve(&a, &rhs, &groups, true, &[], 1e-12);
        assert_eq!(el.method, Method::General);
    }

    /// A solver from outside whose positive definite solves fail (as PETSc's CG stops on an
    /// indefinite matrix), faer's LU otherwise.
    struct NotDefinite {
        inner: FaerSolver,
        spd: bool,
    }

    impl LinearSolver for NotDefinite {
        fn factorize(
            &mut self,
            pattern: &Pattern,
            values: &[f64],
            spd: bool,
            describe_eq: &dyn Fn(usize) -> String,
        ) -> Result<()> {
            self.spd = spd;
            self.inner.factorize(pattern, values, false, describe_eq)
        }
        fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<()> {
            if self.spd {
                return Err(Error::Solve("indefinite".into()));
            }
            self.inner.solve_in_place(rhs)
        }
        fn stats(&self) -> &super::super::linear::SolverStats {
            self.inner.stats()
        }
        fn reset(&mut self) {
            self.inner.reset();
        }
        fn capabilities(&self) -> super::super::linear::Capabilities {
            super::super::linear::Capabilities {
                needs_definite: true,
                ..Default::default()
            }
        }
    }

    /// [`friction_pair`] without `general`, with a solver from outside whose positive definite
    /// (CG) solves fail: the counterpart gives way to the caller (false, the right-hand side
    /// untouched: the whole tangent goes to the solver), not an error that cuts the step.
    #[test]
    fn a_failing_definite_solve_from_outside_gives_way_to_the_whole_tangent() {
        let (a, rhs, groups) = friction_pair();
        let (pattern, values) = dense(&a);
        let solver = NotDefinite {
            inner: FaerSolver::default(),
            spd: false,
        };
        let mut el = MultiplierElimination::with_solver(Box::new(solver), Vec::new());
        let mut got = rhs.clone();
        let solved = el
            .solve(&pattern, &values, &mut got, &groups, false, &[], &|i| {
                format!("{i}")
            })
            .unwrap();
        assert!(!solved);
        assert_eq!(got, rhs);
    }

    /// A penalty in multiplier form (row = column, diagonal −1/ε) on springs of stiffness ~3:
    /// ε = 10 is condensed into the counterpart as the penalty's stiffness, ε = 10⁶ (far stiffer
    /// than the springs along its column) tied as a hard constraint; either way GMRES on the
    /// counterpart gives the full solve's x.
    #[test]
    fn a_stiff_penalty_is_tied_and_a_soft_one_condensed_in_the_counterpart() {
        for (penalty, condensed) in [(10.0, true), (1e6, false)] {
            let mut a = vec![
                vec![4.0, -1.0, 0.0, 0.0, 0.0],
                vec![-1.0, 3.0, 0.5, -1.0, 0.0],
                vec![0.0, 0.5, 2.0, 0.0, 0.0],
                vec![0.0, -1.0, 0.0, 2.0, 0.0],
                vec![0.0, 0.0, 0.0, 0.0, -1.0 / penalty],
            ];
            for (row, v) in [(1, 0.6), (2, 0.8), (3, -1.0)] {
                a[row][4] = v;
                a[4][row] = v;
            }
            // A term the counterpart leaves to GMRES: the displacements' block not symmetric.
            a[0][1] = -1.2;
            let rhs = [1.0, 0.0, -0.5, 0.25, 0.01];
            let groups = [Group {
                slave: vec![1, 2],
                lambdas: vec![4],
            }];
            let (pattern, values) = dense(&a);
            let rows = Rows::new(&pattern, &values);
            assert!(Counterpart::new(&rows, &groups, true).is_some());
            // Taken without condensing where it is tied, refused where it would be condensed.
            let tied = Counterpart::new(&rows, &groups, false).is_some();
            assert_eq!(tied, !condensed, "penalty {penalty}");
            let el = solved_against_full_solve(&a, &rhs, &groups, false, &[], 1e-12);
            assert_eq!(el.method, Method::Preconditioned, "penalty {penalty}");
        }
    }

    /// A multiplier that also loads another group's slave row is kept, and the solve is still
    /// the full one.
    #[test]
    fn a_multiplier_on_two_slave_nodes_is_kept() {
        let a = vec![
            vec![2.0, -1.0, 1.0, 0.3],
            vec![-1.0, 2.0, 0.2, 1.0],
            vec![1.0, 0.2, 0.0, 0.0],
            vec![0.3, 1.0, 0.0, 0.0],
        ];
        let rhs = [0.5, -0.5, 0.1, 0.2];
        let groups = [
            Group {
                slave: vec![0],
                lambdas: vec![2],
            },
            Group {
                slave: vec![1],
                lambdas: vec![3],
            },
        ];
        assert_eq!(against_full_solve(&a, &rhs, &groups), (0, 2));
    }
}

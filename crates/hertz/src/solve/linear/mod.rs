//! Linear solvers behind one interface: analyse a pattern and factorize (or set up) values,
//! solve in place, report what was done. The Newton driver sees only [`LinearSolver`] and asks
//! each solver what it can do ([`Capabilities`]): the condensed contact step needs a Schur block,
//! a loose solve of a branch guess pays only with an iterative solver, and a solver whose fast
//! methods need a positive definite matrix gets the systems that are.
//!
//! * [`FaerSolver`] (`faer_direct`): sparse LLᵀ with a fill-reducing ordering, a regularized LDLᵀ
//!   preconditioner, sparse LU, and GMRES preconditioned by the symmetric part from
//!   [`SolverSettings::krylov_min`] unknowns on non-symmetric patterns;
//! * [`DenseLu`] (`dense`): a dense LU with partial pivoting, a reference for small systems.
//!
//! A new solver (e.g. PETSc's KSP) implements [`LinearSolver`]; a singular matrix is an
//! [`crate::error::Error::Singular`] naming the equation through `describe_eq`.

pub mod dense;
pub mod faer_direct;

pub use dense::DenseLu;
pub use faer_direct::{FaerSolver, KRYLOV_MIN_UNKNOWNS, PIVOT_RATIO};

use super::ordering::OrderingKind;
use crate::assembly::Pattern;
use crate::error::{Error, Result};

/// The error for a singular matrix whose dependent equation is known (`at`: " at node N DOF d",
/// or empty).
pub(crate) fn singular_at(at: &str) -> Error {
    Error::Singular(format!(
        "the stiffness matrix is singular{at}: a mechanism or an unrestrained rigid-body motion \
         (check the supports and the elements connected there)"
    ))
}

/// The error for a singular matrix found only by a failed factorization or solve.
pub(crate) fn singular() -> Error {
    Error::Singular("the tangent matrix is singular: are all rigid-body motions restrained?".into())
}

/// The rigid-body motions of `model` over the free equations of `dofs`: translations and
/// rotations about the centroid (3 in 2D, 6 in 3D), orthonormalized; entries only on the
/// displacement DOFs of nodes (not on slave-node codes or multipliers).
pub fn rigid_body_modes(
    model: &crate::model::Model,
    dofs: &crate::assembly::DofMap,
) -> Vec<Vec<f64>> {
    let dim = model.domain.nsd();
    let n = model.nodes.len().max(1) as f64;
    let centre: [f64; 3] =
        std::array::from_fn(|k| model.nodes.iter().map(|p| p.coords[k]).sum::<f64>() / n);
    // Motion of node n along DOF d (1-based) in mode m.
    let motion = |m: usize, x: [f64; 3], d: usize| -> f64 {
        let r = [x[0] - centre[0], x[1] - centre[1], x[2] - centre[2]];
        match (dim, m) {
            (_, m) if m < dim => f64::from(u8::from(d == m)),
            // 2D: the rotation about z.
            (2, _) => [-r[1], r[0], 0.0][d],
            // 3D: rotations about x, y, z (ω × r).
            (_, m) => {
                let w: [f64; 3] = std::array::from_fn(|k| f64::from(u8::from(k == m - 3)));
                [
                    w[1] * r[2] - w[2] * r[1],
                    w[2] * r[0] - w[0] * r[2],
                    w[0] * r[1] - w[1] * r[0],
                ][d]
            }
        }
    };
    let count = match dim {
        2 => 3,
        3 => 6,
        _ => 1,
    };
    let mut modes: Vec<Vec<f64>> = Vec::with_capacity(count);
    for m in 0..count {
        let mut v = vec![0.0; dofs.n_free];
        for (node, list) in dofs.node_dofs.iter().enumerate() {
            for &(id, code) in list {
                let d = id as usize - 1;
                if code < dofs.n_free - dofs.n_lambda && d < dim {
                    v[code] = motion(m, model.nodes[node].coords, d);
                }
            }
        }
        // Gram–Schmidt against the modes before.
        for w in &modes {
            let dot: f64 = v.iter().zip(w).map(|(a, b)| a * b).sum();
            v.iter_mut().zip(w).for_each(|(a, b)| *a -= dot * b);
        }
        let norm = v.iter().map(|a| a * a).sum::<f64>().sqrt();
        if norm > 1e-12 {
            v.iter_mut().for_each(|a| *a /= norm);
            modes.push(v);
        }
    }
    modes
}

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
    /// Krylov iterations of the last solve (hertz's GMRES, or PETSc's KSP; 0 for a direct
    /// solve).
    pub krylov_iterations: usize,
}

/// How a solver orders and splits its work.
#[derive(Debug, Clone)]
pub struct SolverSettings {
    /// Fill-reducing ordering to use.
    pub ordering: OrderingKind,
    /// Node of every equation (lets METIS order the node graph).
    pub groups: Option<Vec<usize>>,
    /// Equations to eliminate last (their Schur complement is then the trailing factor block).
    pub last_block: Option<Vec<usize>>,
    /// A symmetric matrix that is not positive definite gets an LDLᵀ with regularized pivots
    /// instead of an LU: accurate enough to precondition, not to solve.
    pub preconditioner: bool,
    /// Size from which general (non-symmetric) matrices go to GMRES.
    pub krylov_min: usize,
}

impl Default for SolverSettings {
    fn default() -> Self {
        SolverSettings {
            ordering: OrderingKind::Auto,
            groups: None,
            last_block: None,
            preconditioner: false,
            krylov_min: KRYLOV_MIN_UNKNOWNS,
        }
    }
}

/// What a solver can do beyond factorizing and solving, asked of it: nothing decides on where a
/// solver comes from.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Capabilities {
    /// It factorizes with the equations of [`LinearSolver::set_last_block`] last and gives the
    /// factor's trailing block ([`LinearSolver::trailing_factor_block`]): the Schur complement
    /// the condensed contact step is made of.
    pub schur_block: bool,
    /// Its solves stop at a tolerance ([`LinearSolver::set_relative_tolerance`]): the contact
    /// branch search solves its guesses loosely and the last one again.
    pub iterative: bool,
    /// Its methods for large systems need a positive definite matrix (CG with a multigrid), and
    /// its general one is a direct factorization that can meet a zero pivot where an LU with
    /// pivoting does not: a reduced system of eliminated multipliers is given it as positive
    /// definite where it is, and a general elimination it fails on falls back to the condensed
    /// counterpart.
    pub needs_definite: bool,
}

/// A dense square matrix stored column by column (a factor's trailing block: its lower
/// triangle, zeros above).
#[derive(Debug, Clone, PartialEq)]
pub struct DenseMatrix {
    n: usize,
    values: Vec<f64>,
}

impl DenseMatrix {
    /// The n × n zero matrix.
    pub fn zeros(n: usize) -> DenseMatrix {
        DenseMatrix {
            n,
            values: vec![0.0; n * n],
        }
    }

    pub fn n(&self) -> usize {
        self.n
    }

    /// Entry (i, j).
    pub fn get(&self, i: usize, j: usize) -> f64 {
        self.values[j * self.n + i]
    }

    /// Set entry (i, j) to `v`.
    pub fn set(&mut self, i: usize, j: usize, v: f64) {
        self.values[j * self.n + i] = v;
    }
}

/// A solver for matrices that share one sparsity pattern.
pub trait LinearSolver {
    /// What it can do beyond factorizing and solving (none of it by default).
    fn capabilities(&self) -> Capabilities {
        Capabilities::default()
    }

    /// Factorize (or set up) the matrix given by its values on `pattern`: the upper triangle of
    /// a symmetric pattern, or every entry of a general one. `spd`: the matrix must be positive
    /// definite (linear elasticity), so a failed Cholesky factorization is a mechanism. A
    /// singular matrix is an `Error::Singular` naming its equation through `describe_eq`.
    fn factorize(
        &mut self,
        pattern: &Pattern,
        values: &[f64],
        spd: bool,
        describe_eq: &dyn Fn(usize) -> String,
    ) -> Result<()>;

    /// Solve with the last factorization, `rhs` overwritten by the solution.
    fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<()>;

    /// Solve again with the last factorization for `rhs`, near the last solve's own (the same
    /// system solved before to a looser tolerance): an iterative solver starts from the last
    /// solution.
    fn resolve_in_place(&mut self, rhs: &mut [f64]) -> Result<()> {
        self.solve_in_place(rhs)
    }

    /// What the last factorization and solve did.
    fn stats(&self) -> &SolverStats;

    /// Forget what was analysed (the pattern changed).
    fn reset(&mut self);

    /// Optional: the rigid-body motions of the model over the free equations (3 in 2D, 6 in 3D,
    /// orthonormal; zero on the multipliers), for a solver that can use them (an algebraic
    /// multigrid's near-null space). Told before the first factorization, and again before a
    /// factorization on other unknowns (a reduced system's).
    fn set_near_null_space(&mut self, _modes: &[Vec<f64>]) {}

    /// With [`Capabilities::schur_block`]: eliminate the equations `eqs` last in the
    /// factorizations to come (their symbolic analysis afresh).
    fn set_last_block(&mut self, _eqs: Vec<usize>) {}

    /// With [`Capabilities::schur_block`]: the trailing block L₂₂ of the last Cholesky factor,
    /// whose last equations are those of [`LinearSolver::set_last_block`], with the equation at
    /// each of its positions (L₂₂L₂₂ᵀ is the Schur complement on them); None where this
    /// factorization has no such block (an LDLᵀ of an indefinite matrix).
    fn trailing_factor_block(&self) -> Option<(Vec<usize>, DenseMatrix)> {
        None
    }

    /// Optional: the relative residual an iterative solver stops at in the solves to come (a
    /// preconditioner's inner solve may stop far earlier); None: its own again. A direct solver
    /// ignores it.
    fn set_relative_tolerance(&mut self, _tol: Option<f64>) {}

    /// Optional: `count` unknowns of the matrices to come are Lagrange multipliers (a saddle
    /// point, which an algebraic multigrid cannot precondition). Told before the first
    /// factorization, and again before a factorization on other unknowns.
    fn set_multipliers(&mut self, _count: usize) {}

    /// Optional: from now on every process gives [`LinearSolver::factorize`] the whole matrix
    /// (the same values on every process), not its share; a solver that spans processes takes
    /// each its own rows of it. Told once, before the first factorization.
    fn take_whole_matrices(&mut self) {}

    /// Optional: the processes this solver spans (PETSc under `mpirun -n N`, N > 1). Then each
    /// process assembles its own share of the elements ([`super::partition`]), the residual is
    /// the [`Distributed::sum`] of the shares, and [`LinearSolver::factorize`] gets this
    /// process's share of the tangent, which the solver sums. None: one process assembles all.
    fn distributed(&self) -> Option<&dyn Distributed> {
        None
    }
}

/// A solver's processes, for assembly by shares (see [`LinearSolver::distributed`]).
pub trait Distributed {
    /// This process's number, from 0.
    fn rank(&self) -> usize;

    /// The number of processes (more than one).
    fn size(&self) -> usize;

    /// Replace `v` on every process by the sum of every process's `v` (all of the same length).
    fn sum(&self, v: &mut [f64]) -> Result<()>;
}

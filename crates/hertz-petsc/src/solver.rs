//! [`PetscSolver`]: hertz's [`LinearSolver`] on a PETSc AIJ matrix and KSP.

use crate::ffi::*;
use crate::Session;
use hertz::assembly::Pattern;
use hertz::error::{Error, Result};
use hertz::solve::linear::{Capabilities, Distributed, LinearSolver, SolverStats};
use std::ffi::CString;
use std::os::raw::{c_char, c_int};
use std::ptr::null_mut;
use std::time::Instant;

/// A PETSc call's error code as hertz's error. Across ranks a failed call ends the job: the
/// other ranks would wait in their next collective call forever.
fn check(code: PetscErrorCode, what: &str) -> Result<()> {
    if code == 0 {
        return Ok(());
    }
    let message = format!("PETSc: {what} failed (error code {code})");
    let (rank, size) = ranks();
    if size > 1 {
        eprintln!("error: rank {rank}: {message}; ending the job");
        // SAFETY: MPI is initialized; MPI_Abort does not return.
        unsafe {
            MPI_Abort(PETSC_COMM_WORLD, 3);
        }
    }
    Err(Error::Solve(message))
}

fn cstr(s: &str) -> CString {
    CString::new(s).expect("no NUL in PETSc names")
}

pub(crate) fn start(options: Option<&str>) -> std::result::Result<Session, String> {
    let fail =
        |what: &str, code: PetscErrorCode| format!("PETSc: {what} failed (error code {code})");
    // SAFETY: PETSc is initialized once per process, before any other call; NULL argc/argv is
    // allowed (options then come from PETSC_OPTIONS and the string below).
    unsafe {
        let code = PetscInitialize(null_mut(), null_mut(), std::ptr::null(), std::ptr::null());
        if code != 0 {
            return Err(fail("PetscInitialize", code));
        }
        // Errors come back as codes that hertz reports; PETSc prints nothing.
        PetscPushErrorHandler(PetscReturnErrorHandler, null_mut());
        if let Some(o) = options {
            let s = cstr(o);
            let code = PetscOptionsInsertString(null_mut(), s.as_ptr());
            if code != 0 {
                return Err(format!(
                    "PETSc options `{o}`: not understood (error code {code})"
                ));
            }
        }
        for (name, value) in ITERATIVE_DEFAULTS {
            let (n, v) = (cstr(name), cstr(value));
            let mut set: PetscBool = PETSC_FALSE;
            PetscOptionsHasName(null_mut(), std::ptr::null(), n.as_ptr(), &mut set);
            if set == PETSC_FALSE {
                PetscOptionsSetValue(null_mut(), n.as_ptr(), v.as_ptr());
            }
        }
        // The options are checked once, on a KSP of no matrix: an unknown method is an error now,
        // not at the first solve.
        let mut ksp: KSP = null_mut();
        KSPCreate(PETSC_COMM_WORLD, &mut ksp);
        let code = KSPSetFromOptions(ksp);
        KSPDestroy(&mut ksp);
        if code != 0 {
            PetscFinalize();
            return Err(format!(
                "PETSc does not accept the options {} (error code {code}: an unknown \
                 -ksp_type or -pc_type?)",
                options.map_or("of PETSC_OPTIONS".to_string(), |o| format!("`{o}`"))
            ));
        }
        let (mut rank, mut size): (c_int, c_int) = (0, 1);
        MPI_Comm_rank(PETSC_COMM_WORLD, &mut rank);
        MPI_Comm_size(PETSC_COMM_WORLD, &mut size);
        Ok(Session {
            rank: rank as usize,
            size: size as usize,
            options: options.map(str::to_string),
        })
    }
}

/// The names (with their `-`) of the options given in `options` or `PETSC_OPTIONS` that PETSc
/// has not read so far: misspelled, or for a method the run did not take. Options hertz sets
/// itself are not reported.
pub(crate) fn unused(options: Option<&str>) -> Vec<String> {
    let env = std::env::var("PETSC_OPTIONS").unwrap_or_default();
    let given: Vec<&str> = options
        .unwrap_or_default()
        .split_whitespace()
        .chain(env.split_whitespace())
        .filter_map(|t| t.strip_prefix('-'))
        .filter(|t| t.starts_with(|c: char| c.is_ascii_alphabetic()))
        .collect();
    let mut left = Vec::new();
    let (mut n, mut names, mut values): (PetscInt, *mut *mut c_char, *mut *mut c_char) =
        (0, null_mut(), null_mut());
    // SAFETY: PETSc is initialized; the arrays PetscOptionsLeftGet allocates hold n C strings
    // and are given back to PetscOptionsLeftRestore.
    unsafe {
        if PetscOptionsLeftGet(null_mut(), &mut n, &mut names, &mut values) != 0 {
            return left;
        }
        for k in 0..n.max(0) as usize {
            let name = std::ffi::CStr::from_ptr(*names.add(k)).to_string_lossy();
            let name = name.trim_start_matches('-');
            if given.contains(&name) {
                left.push(format!("-{name}"));
            }
        }
        PetscOptionsLeftRestore(null_mut(), &mut n, &mut names, &mut values);
    }
    left
}

pub(crate) fn finish() {
    // SAFETY: every PETSc object was destroyed with its solver, before the session ends.
    unsafe {
        PetscFinalize();
    }
}

/// This process's rank and the number of ranks.
fn ranks() -> (usize, usize) {
    let (mut rank, mut size): (c_int, c_int) = (0, 1);
    // SAFETY: PETSc (and MPI) are initialized by the session that made this solver.
    unsafe {
        MPI_Comm_rank(PETSC_COMM_WORLD, &mut rank);
        MPI_Comm_size(PETSC_COMM_WORLD, &mut size);
    }
    (rank as usize, size as usize)
}

/// The rows [lo, hi) of this rank (PETSc's PETSC_DECIDE split: the first n mod size ranks get
/// one row more).
fn ownership(n: usize) -> (usize, usize) {
    let (r, s) = ranks();
    let base = n / s;
    let extra = n % s;
    let lo = r * base + r.min(extra);
    (lo, lo + base + usize::from(r < extra))
}

/// The owned rows of a pattern's matrix, row by row: (column, position in the values) of every
/// entry, both triangles of a symmetric pattern.
struct OwnedRows {
    lo: usize,
    rows: Vec<Vec<(PetscInt, usize)>>,
}

impl OwnedRows {
    fn new(pattern: &Pattern, lo: usize, hi: usize) -> OwnedRows {
        let mut rows = vec![Vec::new(); hi - lo];
        for c in 0..pattern.n {
            for k in pattern.col_ptr[c]..pattern.col_ptr[c + 1] {
                let r = pattern.row_idx[k];
                if (lo..hi).contains(&r) {
                    rows[r - lo].push((c as PetscInt, k));
                }
                if pattern.symmetric && r != c && (lo..hi).contains(&c) {
                    rows[c - lo].push((r as PetscInt, k));
                }
            }
        }
        for row in &mut rows {
            row.sort_unstable();
        }
        OwnedRows { lo, rows }
    }
}

/// PETSc's KSP on an AIJ matrix distributed by rows. On more than one rank each rank gives it
/// its share of the tangent (its elements', see [`LinearSolver::distributed`]), which PETSc sums.
pub struct PetscSolver {
    mat: Mat,
    ksp: KSP,
    b: PetscVec,
    x: PetscVec,
    n: usize,
    owned: Option<OwnedRows>,
    stats: SolverStats,
    /// The rigid-body motions (GAMG's near-null space), if told.
    modes: Vec<Vec<f64>>,
    /// The method the KSP has (None: none yet).
    method: Option<Method>,
    /// The KSP's own relative residual (1e-12, or the options') while hertz has set another
    /// (see [`LinearSolver::set_relative_tolerance`]).
    own_rtol: Option<f64>,
    /// The number of multipliers among the unknowns (see [`LinearSolver::set_multipliers`]).
    multipliers: usize,
    /// Every rank gives the whole matrix, not its share (see
    /// [`LinearSolver::take_whole_matrices`]).
    whole: bool,
    /// This process's rank and the number of ranks.
    rank: usize,
    size: usize,
}

/// hertz's default methods, from the matrix: CG + GAMG for a positive definite tangent (linear
/// elasticity, and the systems left when hertz eliminates multipliers); GMRES + BoomerAMG (hypre,
/// tuned for 3D elasticity unless the options say otherwise) for another tangent of
/// [`ITERATIVE_MIN`] unknowns or more without multipliers (penalty contact, where a direct
/// factorization of a large 3D system does not fit); MUMPS' LDLᵀ or LU otherwise (saddle points
/// of multipliers, small systems).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Method {
    Multigrid,
    Iterative,
    Cholesky,
    Lu,
}

/// The size from which a tangent that is neither positive definite nor a saddle point goes to
/// GMRES + BoomerAMG (hertz's own solver's Krylov threshold).
const ITERATIVE_MIN: usize = hertz::solve::linear::KRYLOV_MIN_UNKNOWNS;

/// The settings of [`Method::Iterative`], each applied unless the options set it: BoomerAMG's
/// usual ones for 3D elasticity (with hypre's own defaults the solves of the 3D Hertz sphere's
/// penalty tangents, 31 000 unknowns, took twelve times as long: 131 s against 10.5 s), and
/// GMRES restarted after 100 iterations instead of 30.
const ITERATIVE_DEFAULTS: [(&str, &str); 6] = [
    ("-pc_hypre_boomeramg_strong_threshold", "0.5"),
    ("-pc_hypre_boomeramg_coarsen_type", "HMIS"),
    ("-pc_hypre_boomeramg_interp_type", "ext+i"),
    ("-pc_hypre_boomeramg_P_max", "4"),
    ("-pc_hypre_boomeramg_agg_nl", "1"),
    ("-ksp_gmres_restart", "100"),
];

impl Default for PetscSolver {
    fn default() -> Self {
        Self::new()
    }
}

impl PetscSolver {
    pub fn new() -> PetscSolver {
        PetscSolver {
            mat: null_mut(),
            ksp: null_mut(),
            b: null_mut(),
            x: null_mut(),
            n: 0,
            owned: None,
            stats: SolverStats::default(),
            modes: Vec::new(),
            method: None,
            own_rtol: None,
            multipliers: 0,
            whole: false,
            rank: ranks().0,
            size: ranks().1,
        }
    }

    /// Every entry of the owned rows inserted, entry k (a position in the pattern's values) with
    /// `value(k)`.
    fn insert_owned_rows(&self, value: impl Fn(usize) -> f64) -> Result<()> {
        let owned = self.owned.as_ref().expect("created");
        let (mut cols, mut vals): (Vec<PetscInt>, Vec<f64>) = (Vec::new(), Vec::new());
        // SAFETY: the matrix was preallocated for exactly these entries; the slices outlive the
        // calls.
        unsafe {
            for (i, row) in owned.rows.iter().enumerate() {
                cols.clear();
                vals.clear();
                cols.extend(row.iter().map(|e| e.0));
                vals.extend(row.iter().map(|e| value(e.1)));
                let r = (owned.lo + i) as PetscInt;
                check(
                    MatSetValues(
                        self.mat,
                        1,
                        &r,
                        cols.len() as PetscInt,
                        cols.as_ptr(),
                        vals.as_ptr(),
                        INSERT_VALUES,
                    ),
                    "MatSetValues",
                )?;
            }
        }
        Ok(())
    }

    /// The matrix's final assembly (entries of other ranks' rows sent to them).
    fn assemble(&self) -> Result<()> {
        // SAFETY: the matrix exists; assembly is collective and every rank calls it.
        unsafe {
            check(
                MatAssemblyBegin(self.mat, MAT_FINAL_ASSEMBLY),
                "MatAssemblyBegin",
            )?;
            check(
                MatAssemblyEnd(self.mat, MAT_FINAL_ASSEMBLY),
                "MatAssemblyEnd",
            )
        }
    }

    /// Every entry of `values` on `pattern` (both triangles of a symmetric one) added to the
    /// zeroed matrix, the zeros left out: this rank's share of a tangent that the ranks' shares
    /// sum to; PETSc sends the entries of other ranks' rows to them at assembly.
    fn add_share(&self, pattern: &Pattern, values: &[f64]) -> Result<()> {
        let (mut rows, mut vals): (Vec<PetscInt>, Vec<f64>) = (Vec::new(), Vec::new());
        // SAFETY: every entry is in the preallocated pattern; the slices outlive the calls.
        unsafe {
            check(MatZeroEntries(self.mat), "MatZeroEntries")?;
            for c in 0..pattern.n {
                rows.clear();
                vals.clear();
                let at = pattern.col_ptr[c]..pattern.col_ptr[c + 1];
                for (&r, &v) in pattern.row_idx[at.clone()].iter().zip(&values[at]) {
                    if v != 0.0 {
                        rows.push(r as PetscInt);
                        vals.push(v);
                    }
                }
                if rows.is_empty() {
                    continue;
                }
                let col = c as PetscInt;
                check(
                    MatSetValues(
                        self.mat,
                        rows.len() as PetscInt,
                        rows.as_ptr(),
                        1,
                        &col,
                        vals.as_ptr(),
                        ADD_VALUES,
                    ),
                    "MatSetValues",
                )?;
                if pattern.symmetric {
                    // The other triangle: row c, the same entries off the diagonal.
                    let (r, v): (Vec<PetscInt>, Vec<f64>) = rows
                        .iter()
                        .zip(&vals)
                        .filter(|(r, _)| **r != col)
                        .map(|(r, v)| (*r, *v))
                        .unzip();
                    if !r.is_empty() {
                        check(
                            MatSetValues(
                                self.mat,
                                1,
                                &col,
                                r.len() as PetscInt,
                                r.as_ptr(),
                                v.as_ptr(),
                                ADD_VALUES,
                            ),
                            "MatSetValues",
                        )?;
                    }
                }
            }
        }
        Ok(())
    }

    /// Give the matrix the rigid-body motions as its near-null space (what GAMG coarsens with).
    fn attach_modes(&mut self, lo: usize, hi: usize) -> Result<()> {
        if self.modes.is_empty() || self.modes[0].len() != self.n {
            return Ok(());
        }
        let idx: Vec<PetscInt> = (lo..hi).map(|i| i as PetscInt).collect();
        let mut vecs: Vec<PetscVec> = Vec::with_capacity(self.modes.len());
        // SAFETY: the vectors are duplicates of the matrix's and destroyed below; the null space
        // keeps its own references.
        unsafe {
            for m in &self.modes {
                let mut v: PetscVec = null_mut();
                check(VecDuplicate(self.x, &mut v), "VecDuplicate")?;
                check(
                    VecSetValues(
                        v,
                        idx.len() as PetscInt,
                        idx.as_ptr(),
                        m[lo..hi].as_ptr(),
                        INSERT_VALUES,
                    ),
                    "VecSetValues",
                )?;
                check(VecAssemblyBegin(v), "VecAssemblyBegin")?;
                check(VecAssemblyEnd(v), "VecAssemblyEnd")?;
                vecs.push(v);
            }
            let mut sp: MatNullSpace = null_mut();
            check(
                MatNullSpaceCreate(
                    PETSC_COMM_WORLD,
                    PETSC_FALSE,
                    vecs.len() as PetscInt,
                    vecs.as_ptr(),
                    &mut sp,
                ),
                "MatNullSpaceCreate",
            )?;
            check(MatSetNearNullSpace(self.mat, sp), "MatSetNearNullSpace")?;
            MatNullSpaceDestroy(&mut sp);
            for v in &mut vecs {
                VecDestroy(v);
            }
        }
        Ok(())
    }

    /// The matrix, its vectors and the KSP for `pattern` (its method is chosen at the first
    /// factorization, from the matrix: [`PetscSolver::choose_method`]).
    fn create(&mut self, pattern: &Pattern) -> Result<()> {
        self.destroy();
        let n = pattern.n;
        let (lo, hi) = ownership(n);
        let owned = OwnedRows::new(pattern, lo, hi);
        let diag: Vec<PetscInt> = owned
            .rows
            .iter()
            .map(|r| {
                r.iter()
                    .filter(|(c, _)| (lo..hi).contains(&(*c as usize)))
                    .count() as PetscInt
            })
            .collect();
        let off: Vec<PetscInt> = owned
            .rows
            .iter()
            .zip(&diag)
            .map(|(r, d)| r.len() as PetscInt - d)
            .collect();
        let local = (hi - lo) as PetscInt;
        // SAFETY: the handles are created here and destroyed in `destroy`; the arrays outlive
        // the calls that read them.
        unsafe {
            check(MatCreate(PETSC_COMM_WORLD, &mut self.mat), "MatCreate")?;
            check(
                MatSetSizes(self.mat, local, local, n as PetscInt, n as PetscInt),
                "MatSetSizes",
            )?;
            let aij = cstr("aij");
            check(MatSetType(self.mat, aij.as_ptr()), "MatSetType")?;
            check(
                MatSeqAIJSetPreallocation(self.mat, 0, diag.as_ptr()),
                "preallocation",
            )?;
            check(
                MatMPIAIJSetPreallocation(self.mat, 0, diag.as_ptr(), 0, off.as_ptr()),
                "preallocation",
            )?;
            check(
                MatCreateVecs(self.mat, &mut self.x, &mut self.b),
                "MatCreateVecs",
            )?;
            check(KSPCreate(PETSC_COMM_WORLD, &mut self.ksp), "KSPCreate")?;
            check(
                KSPSetTolerances(self.ksp, 1e-12, 1e-50, -2.0, 10_000),
                "KSPSetTolerances",
            )?;
        }
        self.method = None;
        self.own_rtol = None;
        self.n = n;
        self.owned = Some(owned);
        self.attach_modes(lo, hi)
    }

    /// Give the KSP hertz's default method for the assembled matrix, if it is not the one it
    /// has (see [`Method`]), the user's options applied over it.
    fn choose_method(&mut self, spd: bool, symmetric: bool) -> Result<()> {
        let method = if spd {
            Method::Multigrid
        } else if self.n >= ITERATIVE_MIN && self.multipliers == 0 {
            Method::Iterative
        } else if symmetric {
            Method::Cholesky
        } else {
            Method::Lu
        };
        if self.method == Some(method) {
            return Ok(());
        }
        // SAFETY: the KSP is this solver's; the strings outlive the calls.
        unsafe {
            let mut pc: PC = null_mut();
            check(KSPGetPC(self.ksp, &mut pc), "KSPGetPC")?;
            let (ksp_type, pc_type) = match method {
                Method::Multigrid => ("cg", "gamg"),
                Method::Iterative => ("gmres", "hypre"),
                Method::Cholesky => ("preonly", "cholesky"),
                Method::Lu => ("preonly", "lu"),
            };
            let kt = cstr(ksp_type);
            check(KSPSetType(self.ksp, kt.as_ptr()), "KSPSetType")?;
            let pt = cstr(pc_type);
            if PCSetType(pc, pt.as_ptr()) != 0 {
                // A PETSc built without hypre: its own algebraic multigrid.
                let gamg = cstr("gamg");
                check(PCSetType(pc, gamg.as_ptr()), "PCSetType")?;
            }
            if matches!(method, Method::Cholesky | Method::Lu) {
                let mumps = cstr("mumps");
                check(
                    PCFactorSetMatSolverType(pc, mumps.as_ptr()),
                    "PCFactorSetMatSolverType",
                )?;
            }
            // The user's options override these defaults.
            check(
                KSPSetFromOptions(self.ksp),
                "KSPSetFromOptions (the PETSc options)",
            )?;
        }
        self.method = Some(method);
        Ok(())
    }

    fn destroy(&mut self) {
        // SAFETY: each handle is null or was created by this solver; PETSc's destroy functions
        // take null handles.
        unsafe {
            if !self.ksp.is_null() {
                KSPDestroy(&mut self.ksp);
            }
            if !self.b.is_null() {
                VecDestroy(&mut self.b);
            }
            if !self.x.is_null() {
                VecDestroy(&mut self.x);
            }
            if !self.mat.is_null() {
                MatDestroy(&mut self.mat);
            }
        }
        self.owned = None;
        self.n = 0;
        self.method = None;
    }

    /// The solution vector on every rank, into `out`.
    fn gather(&self, out: &mut [f64]) -> Result<()> {
        if self.size > 1 {
            return gather_to_all(self.x, out);
        }
        // SAFETY: `x` is assembled; the array read is restored.
        unsafe {
            let mut data: *const PetscScalar = std::ptr::null();
            check(VecGetArrayRead(self.x, &mut data), "VecGetArrayRead")?;
            out.copy_from_slice(std::slice::from_raw_parts(data, self.n));
            check(
                VecRestoreArrayRead(self.x, &mut data),
                "VecRestoreArrayRead",
            )?;
        }
        Ok(())
    }
}

/// The whole of the distributed vector `v` (assembled) on every rank, into `out`.
fn gather_to_all(v: PetscVec, out: &mut [f64]) -> Result<()> {
    // SAFETY: the scatter and its vector are made and freed here; the array read is restored
    // first.
    unsafe {
        let (mut all, mut ctx): (PetscVec, VecScatter) = (null_mut(), null_mut());
        check(
            VecScatterCreateToAll(v, &mut ctx, &mut all),
            "VecScatterCreateToAll",
        )?;
        check(
            VecScatterBegin(ctx, v, all, INSERT_VALUES, SCATTER_FORWARD),
            "VecScatterBegin",
        )?;
        check(
            VecScatterEnd(ctx, v, all, INSERT_VALUES, SCATTER_FORWARD),
            "VecScatterEnd",
        )?;
        let mut data: *const PetscScalar = std::ptr::null();
        check(VecGetArrayRead(all, &mut data), "VecGetArrayRead")?;
        out.copy_from_slice(std::slice::from_raw_parts(data, out.len()));
        check(VecRestoreArrayRead(all, &mut data), "VecRestoreArrayRead")?;
        VecScatterDestroy(&mut ctx);
        VecDestroy(&mut all);
    }
    Ok(())
}

impl Drop for PetscSolver {
    fn drop(&mut self) {
        self.destroy();
    }
}

impl LinearSolver for PetscSolver {
    /// KSP's methods stop at a tolerance, and its fast ones for large systems (CG with GAMG)
    /// need a positive definite matrix; it offers no Schur block of a factor.
    fn capabilities(&self) -> Capabilities {
        Capabilities {
            schur_block: false,
            iterative: true,
            needs_definite: true,
        }
    }

    fn factorize(
        &mut self,
        pattern: &Pattern,
        values: &[f64],
        spd: bool,
        _describe_eq: &dyn Fn(usize) -> String,
    ) -> Result<()> {
        let clock = Instant::now();
        let fresh = self.owned.is_none() || self.n != pattern.n;
        if fresh {
            self.create(pattern)?;
        }
        if self.size > 1 && !self.whole {
            // The first final assembly squeezes out the preallocated entries nobody set, and an
            // entry that a later share sets (a contact point that closes) would then be a new
            // nonzero, an error on the rank that owns it: the owned rows' whole pattern goes in
            // as zeros first.
            if fresh {
                self.insert_owned_rows(|_| 0.0)?;
                self.assemble()?;
            }
            self.add_share(pattern, values)?;
        } else {
            self.insert_owned_rows(|k| values[k])?;
        }
        self.assemble()?;
        // SAFETY: the matrix is assembled; the KSP is this solver's.
        unsafe {
            if pattern.symmetric {
                // MUMPS then factorizes LDLᵀ (SYM = 2); SPD: Cholesky (SYM = 1).
                check(
                    MatSetOption(self.mat, MAT_SYMMETRIC, PETSC_TRUE),
                    "MatSetOption",
                )?;
                check(
                    MatSetOption(self.mat, MAT_SYMMETRY_ETERNAL, PETSC_TRUE),
                    "MatSetOption",
                )?;
                if spd {
                    check(MatSetOption(self.mat, MAT_SPD, PETSC_TRUE), "MatSetOption")?;
                }
            }
        }
        self.choose_method(spd, pattern.symmetric)?;
        // SAFETY: the matrix is assembled; the KSP is this solver's.
        unsafe {
            check(
                KSPSetOperators(self.ksp, self.mat, self.mat),
                "KSPSetOperators",
            )?;
            if KSPSetUp(self.ksp) != 0 {
                return Err(Error::Singular(
                    "PETSc could not set up its preconditioner or factorize the tangent \
                     (singular: are all rigid-body motions restrained?)"
                        .into(),
                ));
            }
        }
        self.stats = SolverStats {
            ordering: "PETSc",
            numeric_seconds: clock.elapsed().as_secs_f64(),
            ..SolverStats::default()
        };
        Ok(())
    }

    fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<()> {
        let clock = Instant::now();
        let owned = self
            .owned
            .as_ref()
            .ok_or_else(|| Error::Solve("PETSc: solve before factorize".into()))?;
        let lo = owned.lo;
        let hi = lo + owned.rows.len();
        let idx: Vec<PetscInt> = (lo..hi).map(|i| i as PetscInt).collect();
        // SAFETY: b and x belong to the matrix; the index and value slices outlive the calls.
        unsafe {
            check(
                VecSetValues(
                    self.b,
                    idx.len() as PetscInt,
                    idx.as_ptr(),
                    rhs[lo..hi].as_ptr(),
                    INSERT_VALUES,
                ),
                "VecSetValues",
            )?;
            check(VecAssemblyBegin(self.b), "VecAssemblyBegin")?;
            check(VecAssemblyEnd(self.b), "VecAssemblyEnd")?;
            if KSPSolve(self.ksp, self.b, self.x) != 0 {
                return Err(Error::Singular(
                    "PETSc's solve failed (a singular tangent: are all rigid-body motions restrained?)".into(),
                ));
            }
            let mut reason: KSPConvergedReason = 0;
            check(
                KSPGetConvergedReason(self.ksp, &mut reason),
                "KSPGetConvergedReason",
            )?;
            let mut its: PetscInt = 0;
            check(
                KSPGetIterationNumber(self.ksp, &mut its),
                "KSPGetIterationNumber",
            )?;
            // KSP_DIVERGED_PC_FAILED: the factorization or the multigrid setup met a zero pivot.
            if reason == -11 {
                return Err(Error::Singular(
                    "PETSc's preconditioner failed on the tangent (singular: a mechanism or an \
                     unrestrained rigid-body motion; check the supports)"
                        .into(),
                ));
            }
            if reason < 0 {
                return Err(Error::Solve(format!(
                    "PETSc's KSP did not converge (reason {reason} after {its} iterations; see \
                     KSPConvergedReason, or choose another method with -ksp_type/-pc_type)"
                )));
            }
            self.stats.krylov_iterations = its as usize;
        }
        self.gather(rhs)?;
        self.stats.solve_seconds = clock.elapsed().as_secs_f64();
        Ok(())
    }

    fn resolve_in_place(&mut self, rhs: &mut [f64]) -> Result<()> {
        // A direct solve (preonly) takes no initial guess.
        let mut kind: *const std::os::raw::c_char = std::ptr::null();
        // SAFETY: the KSP is this solver's; PETSc returns its own type name.
        let iterative = !self.ksp.is_null()
            && unsafe { KSPGetType(self.ksp, &mut kind) } == 0
            && !kind.is_null()
            && unsafe { std::ffi::CStr::from_ptr(kind) }.to_bytes() != b"preonly";
        if !iterative {
            return self.solve_in_place(rhs);
        }
        // SAFETY: the KSP is this solver's; `x` still holds the last solution.
        unsafe {
            check(
                KSPSetInitialGuessNonzero(self.ksp, PETSC_TRUE),
                "KSPSetInitialGuessNonzero",
            )?;
        }
        let solved = self.solve_in_place(rhs);
        // SAFETY: as above.
        unsafe {
            KSPSetInitialGuessNonzero(self.ksp, PETSC_FALSE);
        }
        solved
    }

    fn stats(&self) -> &SolverStats {
        &self.stats
    }

    fn set_near_null_space(&mut self, modes: &[Vec<f64>]) {
        self.modes = modes.to_vec();
    }

    fn set_relative_tolerance(&mut self, tol: Option<f64>) {
        if self.ksp.is_null() {
            return;
        }
        // SAFETY: the KSP is this solver's; the outputs are locals.
        unsafe {
            let rtol = match (tol, self.own_rtol) {
                (Some(t), Some(_)) => t,
                (Some(t), None) => {
                    let (mut own, mut atol, mut dtol, mut its) = (0.0, 0.0, 0.0, 0);
                    KSPGetTolerances(self.ksp, &mut own, &mut atol, &mut dtol, &mut its);
                    self.own_rtol = Some(own);
                    t
                }
                (None, Some(own)) => {
                    self.own_rtol = None;
                    own
                }
                (None, None) => return,
            };
            KSPSetTolerances(
                self.ksp,
                rtol,
                PETSC_DEFAULT_REAL,
                PETSC_DEFAULT_REAL,
                PETSC_DEFAULT,
            );
        }
    }

    fn set_multipliers(&mut self, count: usize) {
        self.multipliers = count;
    }

    fn take_whole_matrices(&mut self) {
        self.whole = true;
    }

    fn reset(&mut self) {
        self.destroy();
    }

    fn distributed(&self) -> Option<&dyn Distributed> {
        (self.size > 1).then_some(self as &dyn Distributed)
    }
}

impl Distributed for PetscSolver {
    fn rank(&self) -> usize {
        self.rank
    }

    fn size(&self) -> usize {
        self.size
    }

    /// Each rank adds its `v` into a vector spread over the ranks, which is then gathered whole
    /// on every rank.
    fn sum(&self, v: &mut [f64]) -> Result<()> {
        let n = v.len();
        let idx: Vec<PetscInt> = (0..n as PetscInt).collect();
        // SAFETY: the vectors are created and destroyed here; the arrays read are restored first.
        unsafe {
            let mut spread: PetscVec = null_mut();
            check(
                VecCreateMPI(PETSC_COMM_WORLD, PETSC_DECIDE, n as PetscInt, &mut spread),
                "VecCreateMPI",
            )?;
            check(VecSet(spread, 0.0), "VecSet")?;
            check(
                VecSetValues(spread, n as PetscInt, idx.as_ptr(), v.as_ptr(), ADD_VALUES),
                "VecSetValues",
            )?;
            check(VecAssemblyBegin(spread), "VecAssemblyBegin")?;
            check(VecAssemblyEnd(spread), "VecAssemblyEnd")?;
            let gathered = gather_to_all(spread, v);
            VecDestroy(&mut spread);
            gathered
        }
    }
}

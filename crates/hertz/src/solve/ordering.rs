//! Fill-reducing orderings of the free-free stiffness: AMD (faer) for small systems, METIS
//! nested dissection for large ones. METIS runs on the node graph (the DOFs of one node form a
//! group), which is d² times smaller than the DOF graph and orders as well.

use crate::assembly::Pattern;
use crate::error::{Error, Result};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::SymbolicSparseColMatRef;

/// Which ordering to use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum OrderingKind {
    /// METIS for large systems (see `compute`), AMD otherwise.
    #[default]
    Auto,
    Amd,
    Metis,
}

/// Upper-triangle nonzeros per column above which a pattern counts as 3D-like.
pub const DENSE_PATTERN_PER_COLUMN: f64 = 20.0;

/// 3D-like systems at least this large use METIS under `Auto`.
pub const AUTO_METIS_MIN: usize = 20_000;

/// A permutation: `fwd[new] = old`, `inv[old] = new`.
pub struct Ordering {
    pub fwd: Vec<usize>,
    pub inv: Vec<usize>,
    pub name: &'static str,
}

impl Ordering {
    /// Move `eqs` to the end of the elimination order, keeping the relative order of the rest.
    pub fn move_to_end(&mut self, eqs: &[usize]) {
        let mut last = vec![false; self.fwd.len()];
        for &e in eqs {
            last[e] = true;
        }
        let (front, back): (Vec<usize>, Vec<usize>) = self.fwd.iter().partition(|&&e| !last[e]);
        self.fwd = front.into_iter().chain(back).collect();
        for (new, &old) in self.fwd.iter().enumerate() {
            self.inv[old] = new;
        }
    }
}

/// Compute the ordering of `pattern` (upper CSC). `groups[eq]` names the node of each equation.
pub fn compute(
    pattern: &Pattern,
    groups: Option<&[usize]>,
    kind: OrderingKind,
) -> Result<Ordering> {
    let n = pattern.n;
    let use_metis = match kind {
        OrderingKind::Amd => false,
        OrderingKind::Metis => true,
        // Nested dissection pays off on 3D-like patterns (many nonzeros per column); on 2D
        // patterns AMD gives a faster factorization up to 10^6 unknowns (BENCHMARKS.md).
        OrderingKind::Auto => {
            n >= AUTO_METIS_MIN && pattern.nnz() as f64 / n.max(1) as f64 > DENSE_PATTERN_PER_COLUMN
        }
    };
    if use_metis && n > 1 {
        metis(pattern, groups)
    } else {
        amd(pattern)
    }
}

fn amd(pattern: &Pattern) -> Result<Ordering> {
    let n = pattern.n;
    let sym = SymbolicSparseColMatRef::new_checked(n, n, &pattern.col_ptr, None, &pattern.row_idx);
    let mut fwd = vec![0usize; n];
    let mut inv = vec![0usize; n];
    let mut mem = MemBuffer::try_new(faer::sparse::linalg::amd::order_scratch::<usize>(
        n,
        pattern.nnz(),
    ))
    .map_err(|_| Error::Solve("out of memory for the AMD ordering".into()))?;
    faer::sparse::linalg::amd::order(
        &mut fwd,
        &mut inv,
        sym,
        Default::default(),
        MemStack::new(&mut mem),
    )
    .map_err(|e| Error::Solve(format!("AMD ordering failed: {e:?}")))?;
    Ok(Ordering {
        fwd,
        inv,
        name: "AMD",
    })
}

fn metis(pattern: &Pattern, groups: Option<&[usize]>) -> Result<Ordering> {
    let n = pattern.n;
    let identity: Vec<usize>;
    let groups = match groups {
        Some(g) => g,
        None => {
            identity = (0..n).collect();
            &identity
        }
    };
    // Renumber groups densely in order of first appearance.
    let mut dense = std::collections::HashMap::new();
    let gid: Vec<usize> = groups
        .iter()
        .map(|g| {
            let len = dense.len();
            *dense.entry(*g).or_insert(len)
        })
        .collect();
    let ng = dense.len();
    let mut adj: Vec<Vec<i32>> = vec![Vec::new(); ng];
    for c in 0..n {
        for &r in &pattern.row_idx[pattern.col_ptr[c]..pattern.col_ptr[c + 1]] {
            let (a, b) = (gid[r], gid[c]);
            if a != b {
                adj[a].push(b as i32);
                adj[b].push(a as i32);
            }
        }
    }
    let mut xadj = Vec::with_capacity(ng + 1);
    let mut adjncy = Vec::new();
    xadj.push(0i32);
    for mut list in adj {
        list.sort_unstable();
        list.dedup();
        adjncy.extend_from_slice(&list);
        if adjncy.len() > i32::MAX as usize {
            return Err(Error::Solve("graph too large for 32-bit METIS".into()));
        }
        xadj.push(adjncy.len() as i32);
    }
    let mut nv = ng as i32;
    let mut perm = vec![0i32; ng];
    let mut iperm = vec![0i32; ng];
    let mut options = [0i32; metis_sys::METIS_NOPTIONS as usize];
    // SAFETY: the arrays have the sizes METIS documents (xadj ng+1, adjncy xadj[ng], perm/iperm
    // ng, options METIS_NOPTIONS) and outlive the calls.
    let status = unsafe {
        metis_sys::METIS_SetDefaultOptions(options.as_mut_ptr());
        if adjncy.is_empty() {
            adjncy.push(0);
        }
        metis_sys::METIS_NodeND(
            &mut nv,
            xadj.as_mut_ptr(),
            adjncy.as_mut_ptr(),
            std::ptr::null_mut(),
            options.as_mut_ptr(),
            perm.as_mut_ptr(),
            iperm.as_mut_ptr(),
        )
    };
    if status != metis_sys::rstatus_et_METIS_OK {
        return Err(Error::Solve(format!(
            "METIS ordering failed (status {status})"
        )));
    }
    // Expand the group order to equations.
    let mut members: Vec<Vec<usize>> = vec![Vec::new(); ng];
    for (eq, &g) in gid.iter().enumerate() {
        members[g].push(eq);
    }
    let mut fwd = Vec::with_capacity(n);
    for &g in &perm {
        fwd.extend_from_slice(&members[g as usize]);
    }
    let mut inv = vec![0usize; n];
    for (new, &old) in fwd.iter().enumerate() {
        inv[old] = new;
    }
    Ok(Ordering {
        fwd,
        inv,
        name: "METIS",
    })
}

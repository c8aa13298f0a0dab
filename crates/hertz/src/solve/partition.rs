//! The elements split among the processes of a distributed solve: METIS' partition of the
//! mesh's dual graph (elements joined where they share a node), so that each process assembles a
//! compact block of elements and the tangent's entries it sends to other processes are few.
//! Every process computes the same partition (METIS is deterministic for the same input), and
//! the shares each assembles are summed here ([`Ranks::assemble`]).

use super::linear::Distributed;
use crate::assembly::{Assembler, Contribution, Evaluation};
use crate::error::{Error, Result};
use crate::model::Model;

/// This process among the ones a distributed solver spans (more than one).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Ranks {
    pub rank: usize,
    pub size: usize,
}

impl Ranks {
    /// The elements' internal forces (and tangent, and K_fp·Δu_p) at `u`: each process
    /// assembles its share of the elements (the first adds `extra`), the forces are summed on
    /// every process through `d` and the tangent stays this process's share, for the solver to
    /// sum.
    pub fn assemble(
        self,
        asm: &Assembler,
        d: &dyn Distributed,
        u: &[f64],
        want_k: bool,
        dup: Option<&[f64]>,
        extra: &[Contribution],
    ) -> Result<Evaluation> {
        let share = asm.evaluate_share(u, want_k, dup, if self.rank == 0 { extra } else { &[] });
        // An element that fails (inverts) fails on its own rank: every rank must take the same
        // way on (a cut-back), or the others wait in the sum forever. The sum carries a flag
        // per rank.
        let nf = asm.dofs.n_primary();
        let ndup = dup.map_or(0, |_| asm.dofs.n_free);
        let mut all = vec![0.0; nf + ndup + 4 + self.size];
        match &share {
            Ok(ev) => {
                all[..nf].copy_from_slice(&ev.f_int);
                if let Some(v) = &ev.k_fp_dup {
                    all[nf..nf + ndup].copy_from_slice(v);
                }
                all[nf + ndup..nf + ndup + 4].copy_from_slice(&ev.ebe);
            }
            Err(_) => all[nf + ndup + 4 + self.rank] = 1.0,
        }
        d.sum(&mut all)?;
        let failed = all[nf + ndup + 4..].iter().position(|&f| f != 0.0);
        let mut ev = match (share, failed) {
            (Err(e), _) => return Err(e),
            (Ok(_), Some(r)) => {
                return Err(Error::Solve(format!(
                    "an element failed on rank {r} (its message is in that rank's output)"
                )))
            }
            (Ok(ev), None) => ev,
        };
        ev.f_int.copy_from_slice(&all[..nf]);
        if let Some(v) = ev.k_fp_dup.as_mut() {
            v.copy_from_slice(&all[nf..nf + ndup]);
        }
        ev.ebe.copy_from_slice(&all[nf + ndup..nf + ndup + 4]);
        Ok(ev)
    }
}

/// The part (0..parts) of each element of `model`. Contiguous blocks of the element list when
/// there are fewer elements than parts or METIS declines (a mesh without shared nodes).
pub fn elements(model: &Model, parts: usize) -> Result<Vec<usize>> {
    let ne = model.elements.len();
    if parts <= 1 || ne == 0 {
        return Ok(vec![0; ne]);
    }
    if ne < 2 * parts {
        return Ok(blocks(ne, parts));
    }
    let mut eptr: Vec<i32> = Vec::with_capacity(ne + 1);
    let mut eind: Vec<i32> = Vec::new();
    eptr.push(0);
    for e in &model.elements {
        eind.extend(e.nodes.iter().map(|&n| n as i32));
        if eind.len() > i32::MAX as usize {
            return Err(Error::Solve("mesh too large for 32-bit METIS".into()));
        }
        eptr.push(eind.len() as i32);
    }
    let mut n_elem = ne as i32;
    let mut n_node = model.nodes.len() as i32;
    // Neighbours through one shared node: any element kind, any mix of them.
    let mut common = 1i32;
    let mut n_parts = parts as i32;
    let mut objval = 0i32;
    let mut epart = vec![0i32; ne];
    let mut npart = vec![0i32; model.nodes.len()];
    let mut options = [0i32; metis_sys::METIS_NOPTIONS as usize];
    // SAFETY: the arrays have the sizes METIS documents (eptr ne+1, eind eptr[ne], epart ne,
    // npart nn, options METIS_NOPTIONS) and outlive the call.
    let status = unsafe {
        metis_sys::METIS_SetDefaultOptions(options.as_mut_ptr());
        metis_sys::METIS_PartMeshDual(
            &mut n_elem,
            &mut n_node,
            eptr.as_mut_ptr(),
            eind.as_mut_ptr(),
            std::ptr::null_mut(),
            std::ptr::null_mut(),
            &mut common,
            &mut n_parts,
            std::ptr::null_mut(),
            options.as_mut_ptr(),
            &mut objval,
            epart.as_mut_ptr(),
            npart.as_mut_ptr(),
        )
    };
    if status != metis_sys::rstatus_et_METIS_OK {
        return Ok(blocks(ne, parts));
    }
    Ok(epart.into_iter().map(|p| p as usize).collect())
}

/// `n` items in `parts` contiguous blocks of sizes differing by at most one.
fn blocks(n: usize, parts: usize) -> Vec<usize> {
    (0..n).map(|i| i * parts / n).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fewer_elements_than_parts_take_blocks() {
        assert_eq!(blocks(5, 2), vec![0, 0, 0, 1, 1]);
        assert_eq!(blocks(3, 3), vec![0, 1, 2]);
    }
}

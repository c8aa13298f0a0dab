//! [`MassMatrix`]: the model's mass over the primary DOFs (free and prescribed, so that prescribed
//! motion drives the free DOFs through M_fp·a_p), assembled once from the element masses.

use super::{DofMap, Pattern};
use crate::error::Result;
use crate::model::Model;
use crate::solid::mass::element_mass;

/// An element's mass with none on the nodes `without` (Khenous, Laborde and Renard's mass
/// redistribution): M' = Pᵀ M P, where P moves such a node with the mean of the element's
/// other nodes. It keeps the element's mass and a translation's momentum; a node without mass
/// takes its contact force by equilibrium, so a unilateral contact neither chatters nor makes
/// energy under the trapezoidal rule. None if every node is `without`.
pub fn redistribute(m: &[f64], without: &[bool]) -> Option<Vec<f64>> {
    let nn = without.len();
    let keep: Vec<usize> = (0..nn).filter(|&a| !without[a]).collect();
    if keep.is_empty() {
        return None;
    }
    // P (nn × nn): identity on kept nodes, 1/k on the kept columns of a removed node's row.
    let mut p = vec![0.0; nn * nn];
    for a in 0..nn {
        if without[a] {
            for &b in &keep {
                p[a * nn + b] = 1.0 / keep.len() as f64;
            }
        } else {
            p[a * nn + a] = 1.0;
        }
    }
    let mut mp = vec![0.0; nn * nn];
    for a in 0..nn {
        for c in 0..nn {
            mp[a * nn + c] = (0..nn).map(|b| m[a * nn + b] * p[b * nn + c]).sum();
        }
    }
    let mut out = vec![0.0; nn * nn];
    for c in 0..nn {
        for d in 0..nn {
            out[c * nn + d] = (0..nn).map(|a| p[a * nn + c] * mp[a * nn + d]).sum();
        }
    }
    Some(out)
}

/// A sparse symmetric matrix over the primary DOFs, both triangles stored (CSR).
pub struct MassMatrix {
    row_ptr: Vec<usize>,
    col_idx: Vec<usize>,
    values: Vec<f64>,
}

impl MassMatrix {
    /// The consistent (or `lumped`) mass of every element of `model`, numbered by `dofs`
    /// (a `SlaveNode`'s through its masters' weights), with no mass on the nodes `massless`
    /// (see [`redistribute`]).
    pub fn new(
        model: &Model,
        dofs: &DofMap,
        lumped: bool,
        massless: &[bool],
    ) -> Result<MassMatrix> {
        let np = dofs.n_primary();
        let mut triplets: Vec<(usize, usize, f64)> = Vec::new();
        for (e, el) in model.elements.iter().enumerate() {
            let mut m = element_mass(model, e, lumped)?;
            let nn = el.nodes.len();
            let without: Vec<bool> = el.nodes.iter().map(|&n| massless[n]).collect();
            if without.iter().any(|&w| w) {
                m = redistribute(&m, &without).ok_or_else(|| crate::error::Error::Input {
                    span: el.span.clone(),
                    msg: format!(
                        "element {}: every node is a contact node, so its mass cannot be moved \
                         off the contact surface (use a finer mesh across the body, or \
                         `keepcontactmass`)",
                        el.label
                    ),
                })?;
            }
            for &d in el.dof_ids() {
                let codes: Vec<Option<usize>> = el.nodes.iter().map(|&n| dofs.code(n, d)).collect();
                for a in 0..nn {
                    let Some(ca) = codes[a] else { continue };
                    for b in 0..nn {
                        let (Some(cb), mab) = (codes[b], m[a * nn + b]) else {
                            continue;
                        };
                        if mab == 0.0 {
                            continue;
                        }
                        for (p, wp) in dofs.entries(ca) {
                            for (q, wq) in dofs.entries(cb) {
                                triplets.push((p, q, wp * wq * mab));
                            }
                        }
                    }
                }
            }
        }
        triplets.sort_unstable_by_key(|&(p, q, _)| (p, q));
        let mut row_ptr = vec![0; np + 1];
        let (mut col_idx, mut values): (Vec<usize>, Vec<f64>) = (Vec::new(), Vec::new());
        let mut last = None;
        for (p, q, v) in triplets {
            if last == Some((p, q)) {
                *values.last_mut().expect("an entry") += v;
            } else {
                col_idx.push(q);
                values.push(v);
                row_ptr[p + 1] += 1;
                last = Some((p, q));
            }
        }
        for p in 0..np {
            row_ptr[p + 1] += row_ptr[p];
        }
        Ok(MassMatrix {
            row_ptr,
            col_idx,
            values,
        })
    }

    /// y += s·M·x over the primary DOFs.
    pub fn apply_add(&self, s: f64, x: &[f64], y: &mut [f64]) {
        for (p, yp) in y.iter_mut().enumerate().take(self.row_ptr.len() - 1) {
            let range = self.row_ptr[p]..self.row_ptr[p + 1];
            let sum: f64 = self.col_idx[range.clone()]
                .iter()
                .zip(&self.values[range])
                .map(|(&q, &m)| m * x[q])
                .sum();
            *yp += s * sum;
        }
    }

    /// ½ xᵀ M x: the kinetic energy of velocities `x`.
    pub fn half_norm(&self, x: &[f64]) -> f64 {
        let mut mx = vec![0.0; x.len()];
        self.apply_add(1.0, x, &mut mx);
        0.5 * x.iter().zip(&mx).map(|(a, b)| a * b).sum::<f64>()
    }

    /// Add s·M over the free equations (< `nf`) to tangent values `k` on `pattern` (its upper
    /// triangle when symmetric); the element pattern holds every coupling of M.
    pub fn add_to_tangent(&self, s: f64, nf: usize, pattern: &Pattern, k: &mut [f64]) {
        for p in 0..nf.min(self.row_ptr.len() - 1) {
            for i in self.row_ptr[p]..self.row_ptr[p + 1] {
                let q = self.col_idx[i];
                if q < nf && (q >= p || !pattern.symmetric) {
                    k[pattern.position(p, q)] += s * self.values[i];
                }
            }
        }
    }

    /// The diagonal of M over the first `n` primary DOFs.
    pub fn diagonal(&self, n: usize) -> Vec<f64> {
        (0..n)
            .map(|p| {
                (self.row_ptr[p]..self.row_ptr[p + 1])
                    .find(|&i| self.col_idx[i] == p)
                    .map_or(0.0, |i| self.values[i])
            })
            .collect()
    }
}

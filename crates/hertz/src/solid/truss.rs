//! Two-node bar in small strain (Truss1d, Truss2d). B is built on the initial geometry
//! (spec §1.9): ε = e·(u₂ − u₁)/L, σ = σ(ε; state) from the material's point law (E·ε for
//! `IsoLE`), N = Aσ, tangent A·(dσ/dε)/L.
//!
//! Glossary: `x_ref` end coordinates in the element's plane (1 or 2 components used), `u` end
//! displacements (u₁, u₂ per component), `area` A, `old`/`new` the point's committed state and
//! the state this strain leaves.

use super::kernel::{ElementKernel, GpState, KernelError};
use crate::material::law::respond_into;
use crate::material::PointLaw;

/// Internal force `fe`, tangent `ke` (row-major) and the single GP state of a bar.
#[allow(clippy::too_many_arguments)]
pub fn evaluate_into(
    dim: usize,
    x_ref: [[f64; 2]; 2],
    u: &[f64],
    law: &dyn PointLaw,
    (old, new): (&[f64], &mut [f64]),
    area: f64,
    fe: &mut [f64],
    ke: Option<&mut [f64]>,
    states: Option<&mut Vec<GpState>>,
) -> Result<(), String> {
    let mut e = [0.0; 2];
    let mut len2 = 0.0;
    for i in 0..dim {
        e[i] = x_ref[1][i] - x_ref[0][i];
        len2 += e[i] * e[i];
    }
    let len = len2.sqrt();
    if len < 1e-300 {
        return Err("bar of zero length".into());
    }
    for v in e.iter_mut() {
        *v /= len;
    }
    let strain: f64 = (0..dim).map(|i| e[i] * (u[dim + i] - u[i])).sum::<f64>() / len;
    let (mut stress, mut tangent) = ([0.0], [0.0]);
    respond_into(law, &[strain], old, (&mut stress, &mut tangent, new))?;
    let (stress, tangent) = (stress[0], tangent[0]);
    let force = area * stress;
    for i in 0..dim {
        fe[i] = -force * e[i];
        fe[dim + i] = force * e[i];
    }
    if let Some(k) = ke {
        let c = tangent * area / len;
        let nd = 2 * dim;
        for a in 0..2 {
            for b in 0..2 {
                let s = if a == b { c } else { -c };
                for i in 0..dim {
                    for j in 0..dim {
                        k[(a * dim + i) * nd + b * dim + j] = s * e[i] * e[j];
                    }
                }
            }
        }
    }
    if let Some(st) = states {
        let mut g = GpState::default();
        g.strain[0] = strain;
        g.stress[0] = stress;
        g.plastic = law.plastic(new);
        st.push(g);
    }
    Ok(())
}

/// A point's coordinates in a bar's plane: its components along `axes`, the first `dim` of them
/// (1 for Truss1d, the second then 0).
pub fn in_bar_plane(c: [f64; 3], axes: [usize; 2], dim: usize) -> [f64; 2] {
    let mut x = [0.0; 2];
    for k in 0..dim {
        x[k] = c[axes[k]];
    }
    x
}

/// The global axes of a bar's plane: x for Truss1d; x–z (default), x–y or y–z for Truss2d.
pub fn truss_axes(el: &crate::model::Element) -> [usize; 2] {
    match (el.etype, el.truss_plane) {
        (crate::model::ElementType::Truss1d, _) => [0, 0],
        (_, 1) => [0, 1],
        (_, 2) => [1, 2],
        _ => [0, 2],
    }
}

/// A two-node bar: its axes in the element's plane (`axes[0]` alone for a 1D bar), its
/// cross-section area and its material's point law.
pub struct TrussKernel<'a> {
    /// Displacement components per node (1 or 2).
    pub dim: usize,
    /// The global axes of the element's plane.
    pub axes: [usize; 2],
    pub area: f64,
    pub law: &'a dyn PointLaw,
}

impl ElementKernel for TrussKernel<'_> {
    fn evaluate_into(
        &self,
        x_ref: &[[f64; 3]],
        u: &[f64],
        state: (&[f64], &mut [f64]),
        fe: &mut [f64],
        ke: Option<&mut [f64]>,
        states: Option<&mut Vec<GpState>>,
    ) -> Result<(), KernelError> {
        let x = [0, 1].map(|a| in_bar_plane(x_ref[a], self.axes, self.dim));
        evaluate_into(self.dim, x, u, self.law, state, self.area, fe, ke, states)
            .map_err(|msg| KernelError { gp: 1, msg })
    }
}

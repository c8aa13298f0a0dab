//! The element-kernel interface: what the assembler asks of an element, whatever its kind. A new
//! element kind implements [`ElementKernel`]; the assembler gathers its nodal data, calls it and
//! scatters the result.

use super::continuum::{GpState, KernelError};
use super::loads::in_bar_plane;
use super::truss;
use crate::material::PointLaw;

/// An element's physics at given nodal positions and displacements.
pub trait ElementKernel {
    /// Internal force `fe` (its DOFs in element order), the tangent `ke` (row-major) if asked,
    /// and integration-point results if asked, from the reference coordinates `x_ref` of its
    /// nodes, their displacements `u`, and its points' material `state`: the committed one and
    /// the one this deformation leaves.
    fn evaluate_into(
        &self,
        x_ref: &[[f64; 3]],
        u: &[f64],
        state: (&[f64], &mut [f64]),
        fe: &mut [f64],
        ke: Option<&mut [f64]>,
        states: Option<&mut Vec<GpState>>,
    ) -> Result<(), KernelError>;
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
        truss::evaluate_into(self.dim, x, u, self.law, state, self.area, fe, ke, states)
            .map_err(|msg| KernelError { gp: 1, msg })
    }
}

//! The element-kernel interface: what the assembler asks of an element, whatever its kind. A new
//! element kind implements [`ElementKernel`]; the assembler gathers its nodal data, calls it and
//! scatters the result.

/// Results at one integration point, in full 6-component Voigt form (spec §1.17).
#[derive(Debug, Clone, Copy, Default)]
pub struct GpState {
    /// Small strain, or Green–Lagrange strain E for nlgeo.
    pub strain: [f64; 6],
    /// Cauchy stress (small strain), or second Piola–Kirchhoff S.
    pub stress: [f64; 6],
    /// Deformation gradient, row-major 3×3.
    pub f: [[f64; 3]; 3],
    /// First Piola–Kirchhoff stress P = F·S, row-major 3×3.
    pub p: [[f64; 3]; 3],
    /// A plastic law's plastic strain, κ and damage (None for the others).
    pub plastic: Option<crate::material::plasticity::PlasticState>,
}

impl GpState {
    /// The mean of `f` over an element's points (zeros where it has none): the element's
    /// value in the VTU's cell data and in the Python results' nodal averages.
    pub fn mean(points: &[GpState], f: impl Fn(&GpState) -> [f64; 6]) -> [f64; 6] {
        let mut mean = [0.0; 6];
        for p in points {
            for (m, v) in mean.iter_mut().zip(f(p)) {
                *m += v / points.len() as f64;
            }
        }
        mean
    }
}

/// A failed evaluation: degenerate reference geometry or an inverted element.
#[derive(Debug, Clone)]
pub struct KernelError {
    pub gp: usize,
    pub msg: String,
}

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

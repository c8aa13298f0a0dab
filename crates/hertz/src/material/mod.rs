//! Materials: stress and tangent from the deformation at a point. Linear elasticity (`IsoLE`;
//! St. Venant–Kirchhoff in large deformation) works in reduced Voigt form with S = D:E; the
//! compressible hyperelastic laws of upstream OOFEM give the first Piola–Kirchhoff stress and
//! its tangent from F. A law is prepared once per (material, stress mode) as a [`Constitutive`].

pub mod elasticity;
pub mod hyperelastic;
pub mod spectral;

pub use elasticity::{voigt_components, Elasticity, VOIGT_PAIRS};
pub use hyperelastic::Hyperelastic;

use crate::model::{Material, MaterialLaw, StressMode};

/// What an element kernel evaluates at its integration points.
#[derive(Debug, Clone)]
#[allow(clippy::large_enum_variant)] // one per (material, stress mode): size does not matter
pub enum Constitutive {
    /// S = D:E (small strain: σ = D:ε).
    Linear(Elasticity),
    /// P(F) and ∂P/∂F (large deformation only).
    Hyper(Hyperelastic),
    /// The same in plane stress: the out-of-plane stretch is solved at each point from
    /// P₃₃ = 0 and condensed out of the tangent.
    HyperPlaneStress(Hyperelastic),
}

impl Constitutive {
    /// The law of material `m` for elements in `mode`; `nlgeo` selects the large-deformation
    /// form. A hyperelastic material in a small-strain element is its linearization: linear
    /// elasticity with its small-strain moduli (upstream OOFEM aborts there).
    pub fn new(m: &Material, mode: StressMode, nlgeo: bool) -> Constitutive {
        match &m.law {
            MaterialLaw::Hyperelastic(h) if nlgeo && mode == StressMode::PlaneStress => {
                Constitutive::HyperPlaneStress(h.clone())
            }
            MaterialLaw::Hyperelastic(h) if nlgeo => Constitutive::Hyper(h.clone()),
            _ => Constitutive::Linear(Elasticity::new(m.young(), m.poisson(), mode)),
        }
    }
}

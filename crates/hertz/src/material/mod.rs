//! Materials: stress and tangent from the deformation at a point. The small-strain laws —
//! linear elasticity (`IsoLE`; St. Venant–Kirchhoff in large deformation, S = D:E) and von Mises
//! plasticity of bars (`MisesMat`, with a state per integration point) — work in reduced Voigt
//! form behind [`PointLaw`]; the compressible hyperelastic laws of upstream OOFEM give the first
//! Piola–Kirchhoff stress and its tangent from F. A law is prepared once per (material, stress
//! mode) as a [`Constitutive`].

pub mod elasticity;
pub mod hyperelastic;
pub mod law;
pub mod mises;
pub mod spectral;

pub use elasticity::{voigt_components, voigt_components_of, Elasticity, VOIGT_PAIRS};
pub use hyperelastic::Hyperelastic;
pub use law::PointLaw;
pub use mises::UniaxialMises;

use crate::model::{Material, MaterialLaw, StressMode};

/// What an element kernel evaluates at its integration points.
#[derive(Debug, Clone)]
pub enum Constitutive {
    /// A point law of the strain (small strain: σ(ε); large deformation: S(E)), with state.
    Small(std::sync::Arc<dyn PointLaw>),
    /// P(F) and ∂P/∂F (large deformation only).
    Hyper(Hyperelastic),
    /// The same in plane stress: the out-of-plane stretch is solved at each point from
    /// P₃₃ = 0 and condensed out of the tangent.
    HyperPlaneStress(Hyperelastic),
}

impl Constitutive {
    /// State variables per integration point.
    pub fn state_len(&self) -> usize {
        match self {
            Constitutive::Small(law) => law.state_len(),
            _ => 0,
        }
    }

    /// Write the initial state of one integration point.
    pub fn initial_state(&self, state: &mut [f64]) {
        if let Constitutive::Small(law) = self {
            law.initial_state(state);
        }
    }

    /// The law of material `m` for elements in `mode`; `nlgeo` selects the large-deformation
    /// form. A hyperelastic material in a small-strain element is its linearization: linear
    /// elasticity with its small-strain moduli (upstream OOFEM aborts there).
    pub fn new(m: &Material, mode: StressMode, nlgeo: bool) -> Constitutive {
        match &m.law {
            MaterialLaw::Hyperelastic(h) if nlgeo && mode == StressMode::PlaneStress => {
                Constitutive::HyperPlaneStress(h.clone())
            }
            MaterialLaw::Hyperelastic(h) if nlgeo => Constitutive::Hyper(h.clone()),
            MaterialLaw::Mises {
                young,
                yield_stress,
                hardening,
                ..
            } => Constitutive::Small(std::sync::Arc::new(UniaxialMises {
                young: *young,
                yield_stress: *yield_stress,
                hardening: *hardening,
            })),
            _ => Constitutive::Small(std::sync::Arc::new(Elasticity::new(
                m.young(),
                m.poisson(),
                mode,
            ))),
        }
    }
}

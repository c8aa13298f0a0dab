//! Materials: stress and tangent from the deformation at a point, every law behind one trait
//! ([`PointLaw`], `law.rs`), one file per law: linear elasticity (`IsoLE`; St. Venant–Kirchhoff
//! in large deformation, S = D:E), von Mises plasticity (`MisesMat`, [`plasticity`]: small and
//! finite strain, every stress mode, with a state per integration point) and the compressible hyperelastic energies of upstream OOFEM
//! ([`hyperelastic`]). The model holds a material's parameters; [`law_of`] makes its law for an
//! element's stress mode, once per (material, mode, nlgeo).

pub mod elasticity;
pub mod hyperelastic;
pub mod law;
pub mod plasticity;
pub mod spectral;

pub use elasticity::{voigt_components, voigt_components_of, Elasticity, VOIGT_PAIRS};
pub use law::{PointLaw, Response};

use crate::model::{Material, MaterialLaw, StressMode};
use hyperelastic::{HyperelasticLaw, MooneyRivlin, Ogden, SimoPister};
use std::sync::Arc;

/// A material's law as elements share it.
pub type Law = Arc<dyn PointLaw>;

/// The law of material `m` for elements in `mode`; `nlgeo` selects the large-deformation form.
/// A hyperelastic material in a small-strain element is its linearization: linear elasticity
/// with its small-strain moduli (upstream OOFEM aborts there).
pub fn law_of(m: &Material, mode: StressMode, nlgeo: bool) -> Law {
    match &m.law {
        MaterialLaw::Mises(mises) => plasticity::mises_law(mises, mode, nlgeo),
        MaterialLaw::MooneyRivlin { c1, c2, k } if nlgeo => Arc::new(HyperelasticLaw::new(
            Box::new(MooneyRivlin {
                c1: *c1,
                c2: *c2,
                k: *k,
            }),
            mode,
        )),
        MaterialLaw::Ogden { alpha, mu, k } if nlgeo => Arc::new(HyperelasticLaw::new(
            Box::new(Ogden {
                alpha: alpha.clone(),
                mu: mu.clone(),
                k: *k,
            }),
            mode,
        )),
        MaterialLaw::SimoPister { g, k } if nlgeo => Arc::new(HyperelasticLaw::new(
            Box::new(SimoPister { g: *g, k: *k }),
            mode,
        )),
        _ => Arc::new(Elasticity::new(m.young(), m.poisson(), mode)),
    }
}

//! DOF numbering, the sparse pattern and the element loop that assembles internal forces and
//! tangents. Knows elements through their kernels and every other contribution (contact) only as
//! a [`Contribution`]: location codes, a local residual and a local tangent.

pub mod assembler;
pub mod dofs;
pub mod mass;
pub mod nodal;
pub mod rigid;

pub use assembler::{Assembler, Evaluation, Pattern, PatternValues};
pub use dofs::{DofMap, ExtraDofs};
pub use mass::MassMatrix;
pub use nodal::NodalState;

/// A local contribution of something other than an element (a contact pair): location codes, the
/// local residual (internal force) and the row-major local tangent. An empty `fe` contributes
/// nothing; `codes` alone still reserve the couplings in the pattern.
#[derive(Debug, Clone, Default)]
pub struct Contribution {
    pub codes: Vec<usize>,
    pub fe: Vec<f64>,
    pub ke: Vec<f64>,
}

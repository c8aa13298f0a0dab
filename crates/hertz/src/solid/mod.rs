//! Element kernels and materials: point-wise physics, no global structures.

pub mod continuum;
pub mod kernel;
pub mod loads;
pub mod truss;

pub use continuum::{ContinuumKernel, GpState};
pub use kernel::{ElementKernel, TrussKernel};

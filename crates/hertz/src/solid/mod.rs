//! Element kernels and materials: point-wise physics, no global structures.

pub mod barred;
pub mod continuum;
pub mod follower;
pub mod kernel;
pub mod loads;
pub mod mass;
pub mod truss;

pub use continuum::ContinuumKernel;
pub use kernel::{ElementKernel, GpState, KernelError};
pub use truss::TrussKernel;

//! Reference-element geometry: shape functions, quadrature rules, element boundaries.
//! Nothing here knows about physics.

pub mod geometry;
pub mod quadrature;
pub mod shape;

pub use quadrature::{gauss_line, rule, QuadPoint};
pub use shape::Shape;

/// The most nodes an element may have: room for the 20-node brick and the 27-node one, so that a
/// new shape needs no change of the kernels' buffers.
pub const MAX_NODES: usize = 27;
/// The most DOFs of an element: three per node.
pub const MAX_DOFS: usize = 3 * MAX_NODES;

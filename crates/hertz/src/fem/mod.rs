//! Reference-element geometry: shape functions, quadrature rules, element boundaries.
//! Nothing here knows about physics.

pub mod geometry;
pub mod quadrature;
pub mod shape;

pub use quadrature::{gauss_line, rule, QuadPoint};
pub use shape::Shape;

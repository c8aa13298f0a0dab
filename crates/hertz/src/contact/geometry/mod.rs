//! Contact geometry: master surfaces made of element edges (2D) or faces (3D), and rigid
//! analytical shapes.
//! Knows positions and normals only, no laws and no DOFs.

pub mod bodies;
pub mod edges;
pub mod faces;
pub mod rigid;
pub mod scalar;

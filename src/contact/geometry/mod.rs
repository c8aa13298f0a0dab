//! Contact geometry: master surfaces made of element edges, and rigid analytical shapes.
//! Knows positions and normals only, no laws and no DOFs.

pub mod edges;
pub mod rigid;
pub mod scalar;

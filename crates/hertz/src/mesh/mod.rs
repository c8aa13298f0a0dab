//! Meshes from other programs.

pub mod gmsh;
